#include "geardyn/region_plot.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "geardyn/common/check.hpp"

namespace geardyn::app {
namespace {

constexpr int kLeft = 90, kRight = 30, kTop = 50, kBottom = 60;

// Tick step 1, 2 or 5 × 10^k giving about `target` intervals (Heckbert's nice numbers).
double NiceStep(double span, int target) {
  const double raw = span / target;
  const double mag = std::pow(10.0, std::floor(std::log10(raw)));
  const double f = raw / mag;
  return (f < 1.5 ? 1.0 : f < 3.0 ? 2.0 : f < 7.0 ? 5.0 : 10.0) * mag;
}

std::string Escape(const std::string& s) {
  std::string out;
  for (char c : s) {
    out += c == '<'   ? std::string("&lt;")
           : c == '>' ? std::string("&gt;")
           : c == '&' ? std::string("&amp;")
                      : std::string(1, c);
  }
  return out;
}

std::string Number(double v) {
  std::ostringstream s;
  s.precision(4);
  s << (std::abs(v) < 1e-300 ? 0.0 : v);
  return s.str();
}

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
    << Escape(spec.title) << "</text>\n<g shape-rendering=\"crispEdges\">\n";
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
      s << "<rect x=\"" << Number(x0) << "\" y=\"" << Number(y0) << "\" width=\""
        << Number(x1 - x0 + 0.5) << "\" height=\"" << Number(y1 - y0 + 0.5) << "\" fill=\"" << fill
        << "\" fill-opacity=\"" << Number(opacity) << "\"/>\n";
    }
  }
  s << "</g>\n";

  // Frame and ticks.
  const double left = kLeft, right = spec.width - kRight, top = kTop,
               bottom = spec.height - kBottom;
  s << "<rect x=\"" << left << "\" y=\"" << top << "\" width=\"" << right - left << "\" height=\""
    << bottom - top << "\" fill=\"none\" stroke=\"black\"/>\n";
  const auto ticks = [&](const Scale& sc, bool horizontal) {
    const double step = NiceStep(sc.hi - sc.lo, 8);
    for (double v = std::ceil(sc.lo / step) * step; v <= sc.hi + 1e-9 * step; v += step) {
      const double p = sc(v);
      if (horizontal) {
        s << "<line x1=\"" << Number(p) << "\" y1=\"" << bottom << "\" x2=\"" << Number(p)
          << "\" y2=\"" << bottom + 5 << "\" stroke=\"black\"/><text x=\"" << Number(p) << "\" y=\""
          << bottom + 18 << "\" text-anchor=\"middle\">" << Number(v) << "</text>\n";
      } else {
        s << "<line x1=\"" << left - 5 << "\" y1=\"" << Number(p) << "\" x2=\"" << left
          << "\" y2=\"" << Number(p) << "\" stroke=\"black\"/><text x=\"" << left - 8 << "\" y=\""
          << Number(p + 4) << "\" text-anchor=\"end\">" << Number(v) << "</text>\n";
      }
    }
  };
  ticks(sx, true);
  ticks(sy, false);
  s << "<text x=\"" << (left + right) / 2 << "\" y=\"" << spec.height - 15
    << "\" text-anchor=\"middle\">" << Escape(spec.x_label) << "</text>\n"
    << "<text transform=\"translate(18," << (top + bottom) / 2
    << ") rotate(-90)\" text-anchor=\"middle\">" << Escape(spec.y_label) << "</text>\n";

  // Resonance markers, transition curves, labels (in this order: labels stay readable).
  for (const RegionPlotMarker& m : spec.markers) {
    if (m.x < sx.lo || m.x > sx.hi) continue;
    const double p = sx(m.x);
    s << "<line x1=\"" << Number(p) << "\" y1=\"" << top << "\" x2=\"" << Number(p) << "\" y2=\""
      << bottom << "\" stroke=\"#555\" stroke-dasharray=\"4,4\"/><text x=\"" << Number(p)
      << "\" y=\"" << top - 6 << "\" text-anchor=\"middle\" font-size=\"10\">" << Escape(m.text)
      << "</text>\n";
  }
  for (const RegionPlotCurve& c : spec.curves) {
    if (c.x.empty()) continue;
    s << "<" << (c.closed ? "polygon" : "polyline") << " fill=\"none\" stroke=\"black\" "
      << "stroke-width=\"1.5\" points=\"";
    for (std::size_t k = 0; k < c.x.size() && k < c.y.size(); ++k) {
      s << (k ? " " : "") << Number(sx(c.x[k])) << "," << Number(sy(c.y[k]));
    }
    s << "\"/>\n";
  }
  for (const RegionPlotLabel& l : spec.labels) {
    s << "<text x=\"" << Number(sx(l.x)) << "\" y=\"" << Number(sy(l.y))
      << "\" text-anchor=\"middle\" font-weight=\"bold\" stroke=\"white\" stroke-width=\"3\" "
         "paint-order=\"stroke\">"
      << Escape(l.text) << "</text>\n";
  }
  s << "</svg>\n";
  return s.str();
}

}  // namespace geardyn::app
