/// @file
/// @brief A dependency-free SVG stability-chart plot: the grid cells shaded by their verdict
/// (unstable cells darker with growing max|λ|), the transition curves drawn over them, the
/// region labels inside their regions and optional dashed resonance markers along x.
///
/// **Labels never overlap** (label_layout.hpp). Resonance-marker labels go above the frame in
/// rows: each takes the lowest row where it meets no label already there, and the frame moves
/// down when more rows are needed. Region labels are placed, largest region first, at the first
/// of their anchors (best first) where the label's box stays inside the frame and meets no label
/// placed before; if none fits, at the nearest free position around the first anchor, joined to
/// it by a thin leader line; if the frame has no room left, the label is omitted and a note at
/// the bottom says how many were.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace geardyn::app {

/// A point in data coordinates.
struct RegionPlotPoint {
  double x = 0.0;
  double y = 0.0;
};

/// A region label (e.g. "2f_3/1"), centred on the first free anchor.
struct RegionPlotLabel {
  double x = 0.0;  ///< preferred anchor (e.g. the region's most unstable point)
  double y = 0.0;
  std::string text;
  /// Further anchors inside the region, best first (tried after (x, y)); their number also
  /// orders the labels: the one with most anchors is placed first.
  std::vector<RegionPlotPoint> anchors;
};

/// A vertical dashed line at x with a label at the top (e.g. a resonance speed).
struct RegionPlotMarker {
  double x = 0.0;
  std::string text;
};

/// A polyline in data coordinates.
struct RegionPlotCurve {
  std::vector<double> x;
  std::vector<double> y;
  bool closed = false;
  std::string colour;  ///< SVG stroke colour (empty: black)
  std::string label;   ///< legend entry (empty: none; one entry per distinct label)
};

/// The plot. Grid arrays are row-major (index = iy·x_values.size() + ix).
struct RegionPlotSpec {
  std::string title;
  std::string x_label;           ///< with unit
  std::string y_label;           ///< with unit
  std::vector<double> x_values;  ///< ≥ 2 ascending grid values
  std::vector<double> y_values;  ///< ≥ 2 ascending grid values
  std::vector<double> max_abs_multiplier;
  std::vector<std::uint8_t> stable;
  std::vector<std::uint8_t> ok;
  std::vector<RegionPlotCurve> curves;
  std::vector<RegionPlotLabel> labels;
  std::vector<RegionPlotMarker> markers;
  int width = 900;   ///< [px]
  int height = 620;  ///< [px]
};

/// @brief Renders the chart as a standalone SVG document.
/// @throws InvalidInput if the grid arrays do not have x_values.size()·y_values.size() entries
///   or an axis has fewer than 2 values.
std::string RenderRegionSvg(const RegionPlotSpec& spec);

}  // namespace geardyn::app
