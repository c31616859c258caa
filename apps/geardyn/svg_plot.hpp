/// @file
/// @brief A small, dependency-free SVG line-plot writer for the command's result plots: stacked
/// panels sharing one x axis, several series per panel, solid or dashed, with "nice" ticks.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace geardyn::app {

/// One curve. Non-finite y values break the line (nothing is drawn across them).
struct PlotSeries {
  std::string label;      ///< legend text (empty: no legend entry)
  std::vector<double> x;  ///< abscissae (same length as y)
  std::vector<double> y;  ///< ordinates
  bool dashed = false;    ///< dashed line (e.g. an unstable branch)
  std::string colour;     ///< SVG stroke colour (empty: the palette colour of its index)
};

/// A labelled point mark (e.g. a jump of a frequency-response curve): a circle and its label.
struct PlotMarker {
  double x = 0.0;
  double y = 0.0;
  std::string label;               ///< text next to the circle (empty: none)
  std::string colour = "#000000";  ///< SVG colour of the circle and the label
};

/// One panel: a y axis and its curves.
struct PlotPanel {
  std::string y_label;  ///< axis label with unit, e.g. "K [N/m]"
  std::vector<PlotSeries> series;
  std::vector<PlotMarker> markers;  ///< drawn over the series (non-finite ones skipped)
};

/// A figure of panels stacked vertically over a common x axis.
struct PlotSpec {
  std::string title;
  std::string x_label;  ///< with unit
  std::vector<PlotPanel> panels;
  int width = 900;         ///< [px]
  int panel_height = 220;  ///< [px]
};

/// @brief Renders the figure as a standalone SVG document.
/// @throws InvalidInput if a series has x and y of different lengths.
std::string RenderSvg(const PlotSpec& spec);

/// The palette colour RenderSvg gives series `index` of a panel when its colour is empty (to
/// draw two series, e.g. stable solid and unstable dashed, in one colour).
const char* PlotColour(std::size_t index);

}  // namespace geardyn::app
