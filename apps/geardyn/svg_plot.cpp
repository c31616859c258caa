#include "geardyn/svg_plot.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <sstream>

#include "geardyn/common/check.hpp"
#include "geardyn/svg_text.hpp"

namespace geardyn::app {
namespace {

constexpr std::array<const char*, 6> kColours = {"#1f77b4", "#d62728", "#2ca02c",
                                                 "#9467bd", "#ff7f0e", "#17becf"};
constexpr int kLeft = 90, kRight = 20, kTop = 40, kGap = 30, kBottom = 50;

struct Range {
  double lo = std::numeric_limits<double>::infinity();
  double hi = -std::numeric_limits<double>::infinity();
  void Add(double v) {
    if (std::isfinite(v)) {
      lo = std::min(lo, v);
      hi = std::max(hi, v);
    }
  }
  // A degenerate or empty range is widened so that the axis still has a scale.
  void Finish() {
    if (!(lo <= hi)) {
      lo = 0.0;
      hi = 1.0;
    } else if (hi - lo <= 1e-12 * std::max(std::abs(lo), std::abs(hi))) {
      const double pad = lo == 0.0 ? 1.0 : 0.05 * std::abs(lo);
      lo -= pad;
      hi += pad;
    } else {  // a 5 % margin keeps curves off the frame
      const double pad = 0.05 * (hi - lo);
      lo -= pad;
      hi += pad;
    }
  }
};

}  // namespace

const char* PlotColour(std::size_t index) { return kColours[index % kColours.size()]; }

std::string RenderSvg(const PlotSpec& spec) {
  const int n = static_cast<int>(spec.panels.size());
  const int height = kTop + n * spec.panel_height + std::max(0, n - 1) * kGap + kBottom;
  const double plot_w = spec.width - kLeft - kRight;
  Range xr;
  for (const PlotPanel& p : spec.panels) {
    for (const PlotSeries& s : p.series) {
      GEARDYN_THROW_UNLESS(s.x.size() == s.y.size(),
                           "plot series '" << s.label << "': " << s.x.size() << " x values, "
                                           << s.y.size() << " y values");
      for (double v : s.x) xr.Add(v);
    }
    for (const PlotMarker& m : p.markers) xr.Add(m.x);
  }
  xr.Finish();
  const auto px = [&](double x) { return kLeft + (x - xr.lo) / (xr.hi - xr.lo) * plot_w; };

  std::ostringstream svg;
  svg << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << spec.width << "\" height=\""
      << height << "\" font-family=\"sans-serif\" font-size=\"12\">\n"
      << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n"
      << "<text x=\"" << spec.width / 2 << "\" y=\"22\" text-anchor=\"middle\" font-size=\"15\">"
      << EscapeSvgText(spec.title) << "</text>\n";
  const double x_step = NiceTickStep(xr.hi - xr.lo, 8);
  for (int i = 0; i < n; ++i) {
    const PlotPanel& panel = spec.panels[i];
    const double top = kTop + i * (spec.panel_height + kGap);
    const double bottom = top + spec.panel_height;
    Range yr;
    for (const PlotSeries& s : panel.series) {
      for (double v : s.y) yr.Add(v);
    }
    for (const PlotMarker& m : panel.markers) yr.Add(m.y);
    yr.Finish();
    const auto py = [&](double y) {
      return bottom - (y - yr.lo) / (yr.hi - yr.lo) * spec.panel_height;
    };
    svg << "<rect x=\"" << kLeft << "\" y=\"" << top << "\" width=\"" << plot_w << "\" height=\""
        << spec.panel_height << "\" fill=\"none\" stroke=\"black\"/>\n";
    const double y_step = NiceTickStep(yr.hi - yr.lo, 5);
    for (double t = std::ceil(yr.lo / y_step) * y_step; t <= yr.hi + 1e-9 * y_step; t += y_step) {
      svg << "<line x1=\"" << kLeft << "\" x2=\"" << kLeft + plot_w << "\" y1=\"" << py(t)
          << "\" y2=\"" << py(t) << "\" stroke=\"#ddd\"/>"
          << "<text x=\"" << kLeft - 6 << "\" y=\"" << py(t) + 4 << "\" text-anchor=\"end\">"
          << FormatTickNumber(t) << "</text>\n";
    }
    for (double t = std::ceil(xr.lo / x_step) * x_step; t <= xr.hi + 1e-9 * x_step; t += x_step) {
      svg << "<line x1=\"" << px(t) << "\" x2=\"" << px(t) << "\" y1=\"" << top << "\" y2=\""
          << bottom << "\" stroke=\"#eee\"/>";
      if (i == n - 1) {
        svg << "<text x=\"" << px(t) << "\" y=\"" << bottom + 16 << "\" text-anchor=\"middle\">"
            << FormatTickNumber(t) << "</text>";
      }
      svg << "\n";
    }
    svg << "<text transform=\"translate(18," << (top + bottom) / 2
        << ") rotate(-90)\" text-anchor=\"middle\">" << EscapeSvgText(panel.y_label) << "</text>\n";
    int legend_rows = 0;  // labelled series so far (unlabelled ones take no legend row)
    for (size_t k = 0; k < panel.series.size(); ++k) {
      const PlotSeries& s = panel.series[k];
      const char* colour = s.colour.empty() ? kColours[k % kColours.size()] : s.colour.c_str();
      std::ostringstream path;
      bool pen_down = false;
      for (size_t j = 0; j < s.x.size(); ++j) {
        if (!std::isfinite(s.x[j]) || !std::isfinite(s.y[j])) {
          pen_down = false;
          continue;
        }
        path << (pen_down ? " L" : " M") << px(s.x[j]) << " " << py(s.y[j]);
        pen_down = true;
      }
      svg << "<path d=\"" << path.str() << "\" fill=\"none\" stroke=\"" << colour
          << "\" stroke-width=\"1.5\"" << (s.dashed ? " stroke-dasharray=\"6 4\"" : "") << "/>\n";
      if (!s.label.empty()) {
        svg << "<text x=\"" << kLeft + plot_w - 8 << "\" y=\"" << top + 16 + 15 * legend_rows++
            << "\" text-anchor=\"end\" fill=\"" << colour << "\">" << EscapeSvgText(s.label)
            << "</text>\n";
      }
    }
    for (const PlotMarker& m : panel.markers) {
      if (!std::isfinite(m.x) || !std::isfinite(m.y)) continue;
      svg << "<circle cx=\"" << px(m.x) << "\" cy=\"" << py(m.y)
          << "\" r=\"4\" fill=\"none\" stroke=\"" << m.colour << "\" stroke-width=\"1.5\"/>";
      if (!m.label.empty()) {
        const bool right_half = px(m.x) > kLeft + 0.5 * plot_w;  // keep the label in the frame
        svg << "<text x=\"" << px(m.x) + (right_half ? -6 : 6) << "\" y=\"" << py(m.y) - 6
            << "\" text-anchor=\"" << (right_half ? "end" : "start") << "\" fill=\"" << m.colour
            << "\">" << EscapeSvgText(m.label) << "</text>";
      }
      svg << "\n";
    }
  }
  svg << "<text x=\"" << kLeft + plot_w / 2 << "\" y=\"" << height - 12
      << "\" text-anchor=\"middle\">" << EscapeSvgText(spec.x_label) << "</text>\n</svg>\n";
  return svg.str();
}

}  // namespace geardyn::app
