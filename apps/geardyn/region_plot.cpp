#include "geardyn/region_plot.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "geardyn/common/check.hpp"
#include "geardyn/svg_text.hpp"

namespace geardyn::app {
namespace {

constexpr int kLeft = 90, kRight = 30, kTop = 50, kBottom = 60;

// Maps a data interval [lo, hi] onto pixels [p0, p1].
struct Scale {
  double lo, hi, p0, p1;
  double operator()(double v) const { return p0 + (v - lo) / (hi - lo) * (p1 - p0); }
};

}  // namespace

std::string RenderRegionSvg(const RegionPlotSpec& spec) {
  const std::size_t nx = spec.x_values.size(), ny = spec.y_values.size();
  GEARDYN_THROW_UNLESS(nx >= 2 && ny >= 2, "RenderRegionSvg: each axis needs at least 2 values");
  GEARDYN_THROW_UNLESS(spec.max_abs_multiplier.size() == nx * ny && spec.stable.size() == nx * ny &&
                           spec.ok.size() == nx * ny,
                       "RenderRegionSvg: the grid arrays must have x_values.size()·"
                       "y_values.size() entries");
  // Cells cover half a step on each side of their grid value.
  const double dx = (spec.x_values.back() - spec.x_values.front()) / static_cast<double>(nx - 1);
  const double dy = (spec.y_values.back() - spec.y_values.front()) / static_cast<double>(ny - 1);
  const Scale sx{spec.x_values.front() - 0.5 * dx, spec.x_values.back() + 0.5 * dx,
                 static_cast<double>(kLeft), static_cast<double>(spec.width - kRight)};
  const Scale sy{spec.y_values.front() - 0.5 * dy, spec.y_values.back() + 0.5 * dy,
                 static_cast<double>(spec.height - kBottom), static_cast<double>(kTop)};
  double log_max = 0.0;  // shading scale: ln max|λ| of the most unstable point
  for (std::size_t i = 0; i < nx * ny; ++i) {
    if (spec.ok[i] && !spec.stable[i] && std::isfinite(spec.max_abs_multiplier[i])) {
      log_max = std::max(log_max, std::log(spec.max_abs_multiplier[i]));
    }
  }

  std::ostringstream s;
  s << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << spec.width << "\" height=\""
    << spec.height << "\" font-family=\"sans-serif\" font-size=\"12\">\n"
    << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n"
    << "<text x=\"" << spec.width / 2 << "\" y=\"24\" text-anchor=\"middle\" font-size=\"15\">"
    << EscapeSvgText(spec.title) << "</text>\n<g shape-rendering=\"crispEdges\">\n";
  for (std::size_t iy = 0; iy < ny; ++iy) {
    for (std::size_t ix = 0; ix < nx; ++ix) {
      const std::size_t i = iy * nx + ix;
      const double x0 = sx(spec.x_values[ix] - 0.5 * dx), x1 = sx(spec.x_values[ix] + 0.5 * dx);
      const double y0 = sy(spec.y_values[iy] + 0.5 * dy), y1 = sy(spec.y_values[iy] - 0.5 * dy);
      std::string fill = "#f5f7fb";
      double opacity = 1.0;
      if (!spec.ok[i]) {
        fill = "#9e9e9e";
      } else if (!spec.stable[i]) {
        fill = "#d62728";
        const double g = log_max > 0.0 ? std::log(spec.max_abs_multiplier[i]) / log_max : 1.0;
        opacity = 0.3 + 0.6 * std::clamp(std::sqrt(std::max(g, 0.0)), 0.0, 1.0);
      }
      s << "<rect x=\"" << FormatTickNumber(x0) << "\" y=\"" << FormatTickNumber(y0)
        << "\" width=\"" << FormatTickNumber(x1 - x0 + 0.5) << "\" height=\""
        << FormatTickNumber(y1 - y0 + 0.5) << "\" fill=\"" << fill << "\" fill-opacity=\""
        << FormatTickNumber(opacity) << "\"/>\n";
    }
  }
  s << "</g>\n";

  // Frame and ticks.
  const double left = kLeft, right = spec.width - kRight, top = kTop,
               bottom = spec.height - kBottom;
  s << "<rect x=\"" << left << "\" y=\"" << top << "\" width=\"" << right - left << "\" height=\""
    << bottom - top << "\" fill=\"none\" stroke=\"black\"/>\n";
  const auto ticks = [&](const Scale& sc, bool horizontal) {
    const double step = NiceTickStep(sc.hi - sc.lo, 8);
    for (double v = std::ceil(sc.lo / step) * step; v <= sc.hi + 1e-9 * step; v += step) {
      const double p = sc(v);
      if (horizontal) {
        s << "<line x1=\"" << FormatTickNumber(p) << "\" y1=\"" << bottom << "\" x2=\""
          << FormatTickNumber(p) << "\" y2=\"" << bottom + 5 << "\" stroke=\"black\"/><text x=\""
          << FormatTickNumber(p) << "\" y=\"" << bottom + 18 << "\" text-anchor=\"middle\">"
          << FormatTickNumber(v) << "</text>\n";
      } else {
        s << "<line x1=\"" << left - 5 << "\" y1=\"" << FormatTickNumber(p) << "\" x2=\"" << left
          << "\" y2=\"" << FormatTickNumber(p) << "\" stroke=\"black\"/><text x=\"" << left - 8
          << "\" y=\"" << FormatTickNumber(p + 4) << "\" text-anchor=\"end\">"
          << FormatTickNumber(v) << "</text>\n";
      }
    }
  };
  ticks(sx, true);
  ticks(sy, false);
  s << "<text x=\"" << (left + right) / 2 << "\" y=\"" << spec.height - 15
    << "\" text-anchor=\"middle\">" << EscapeSvgText(spec.x_label) << "</text>\n"
    << "<text transform=\"translate(18," << (top + bottom) / 2
    << ") rotate(-90)\" text-anchor=\"middle\">" << EscapeSvgText(spec.y_label) << "</text>\n";

  // Resonance markers, transition curves, labels (in this order: labels stay readable).
  for (const RegionPlotMarker& m : spec.markers) {
    if (m.x < sx.lo || m.x > sx.hi) continue;
    const double p = sx(m.x);
    s << "<line x1=\"" << FormatTickNumber(p) << "\" y1=\"" << top << "\" x2=\""
      << FormatTickNumber(p) << "\" y2=\"" << bottom
      << "\" stroke=\"#555\" stroke-dasharray=\"4,4\"/><text x=\"" << FormatTickNumber(p)
      << "\" y=\"" << top - 6 << "\" text-anchor=\"middle\" font-size=\"10\">"
      << EscapeSvgText(m.text) << "</text>\n";
  }
  for (const RegionPlotCurve& c : spec.curves) {
    if (c.x.empty()) continue;
    s << "<" << (c.closed ? "polygon" : "polyline") << " fill=\"none\" stroke=\"black\" "
      << "stroke-width=\"1.5\" points=\"";
    for (std::size_t k = 0; k < c.x.size() && k < c.y.size(); ++k) {
      s << (k ? " " : "") << FormatTickNumber(sx(c.x[k])) << "," << FormatTickNumber(sy(c.y[k]));
    }
    s << "\"/>\n";
  }
  for (const RegionPlotLabel& l : spec.labels) {
    s << "<text x=\"" << FormatTickNumber(sx(l.x)) << "\" y=\"" << FormatTickNumber(sy(l.y))
      << "\" text-anchor=\"middle\" font-weight=\"bold\" stroke=\"white\" stroke-width=\"3\" "
         "paint-order=\"stroke\">"
      << EscapeSvgText(l.text) << "</text>\n";
  }
  s << "</svg>\n";
  return s.str();
}

}  // namespace geardyn::app
