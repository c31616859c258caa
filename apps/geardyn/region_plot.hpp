/// @file
/// @brief A dependency-free SVG stability-chart plot: the grid cells shaded by their verdict
/// (unstable cells darker with growing max|λ|), the transition curves drawn over them, the
/// region labels at the regions' centroids and optional dashed resonance markers along x.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace geardyn::app {

/// A text label at a data point (e.g. "2f_3/1" at a region's centroid).
struct RegionPlotLabel {
  double x = 0.0;
  double y = 0.0;
  std::string text;
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
