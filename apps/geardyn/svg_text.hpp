/// @file
/// @brief Text helpers shared by the SVG writers (svg_plot, region_plot): XML escaping, compact
/// numbers and "nice" tick steps.
#pragma once

#include <string>

namespace geardyn::app {

/// Tick step 1, 2 or 5 × 10^k giving about `target` intervals over `span` (Heckbert's nice
/// numbers).
double NiceTickStep(double span, int target);

/// `s` with <, > and & escaped for SVG text.
std::string EscapeSvgText(const std::string& s);

/// `v` with 4 significant digits (tiny magnitudes below 1e-300 printed as 0).
std::string FormatTickNumber(double v);

}  // namespace geardyn::app
