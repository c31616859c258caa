#include "geardyn/region_plot.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "geardyn/common/check.hpp"
#include "geardyn/label_layout.hpp"
#include "geardyn/svg_text.hpp"

namespace geardyn::app {
namespace {

constexpr int kLeft = 90, kRight = 30, kTop = 50, kBottom = 60;
// Resonance-marker labels: font size, row pitch and the gap between row 0 and the frame [px];
// the title (font 15, baseline 24) ends above kTitleBottom.
constexpr double kMarkerFont = 10.0, kMarkerRow = 12.0, kMarkerGap = 6.0, kTitleBottom = 30.0;
// Region labels: bold font size and the white halo (stroke-width 3) plus 1 px of air [px].
constexpr double kLabelFont = 12.0, kLabelHalo = 2.5;
// Text attributes that make the rendered width exactly the laid-out one (label_layout.hpp).
std::string LengthAttributes(const std::string& text, double font_size) {
  return " textLength=\"" + FormatTickNumber(TextWidth(text, font_size)) +
         "\" lengthAdjust=\"spacingAndGlyphs\"";
}

// A marker label: its centre x and row (0 next to the frame).
struct MarkerSlot {
  double x = 0.0;
  int row = 0;
};

// Rows for the marker labels at pixel positions px (font kMarkerFont): each takes the lowest row
// where its box meets no label already in that row; centres are kept within [0, width].
std::vector<MarkerSlot> LayOutMarkerRows(const std::vector<double>& px,
                                         const std::vector<std::string>& text, double width,
                                         int* num_rows) {
  std::vector<MarkerSlot> slots(px.size());
  std::vector<std::vector<TextBox>> rows;
  for (std::size_t k = 0; k < px.size(); ++k) {
    const double half = 0.5 * TextWidth(text[k], kMarkerFont) + 1.0;
    const double x =
        std::clamp(px[k], std::min(half, 0.5 * width), std::max(width - half, 0.5 * width));
    const TextBox box = CentredTextBox(x, 0.0, text[k], kMarkerFont, 1.0);
    std::size_t r = 0;
    for (; r < rows.size(); ++r) {
      if (std::none_of(rows[r].begin(), rows[r].end(),
                       [&box](const TextBox& b) { return b.Intersects(box); })) {
        break;
      }
    }
    if (r == rows.size()) rows.emplace_back();
    rows[r].push_back(box);
    slots[k] = {x, static_cast<int>(r)};
  }
  *num_rows = static_cast<int>(rows.size());
  return slots;
}

// Maps a data interval [lo, hi] onto pixels [p0, p1].
struct Scale {
  double lo, hi, p0, p1;
  double operator()(double v) const { return p0 + (v - lo) / (hi - lo) * (p1 - p0); }
};

// Region labels (see the @file): anchors in order, then the free position nearest to the first
// anchor (with a leader line), else omitted; writes the leader lines, the labels and the note.
void LayOutRegionLabels(const RegionPlotSpec& spec, const Scale& sx, const Scale& sy,
                        const TextBox& frame, std::ostringstream& s) {
  // Baseline offset that centres the box (kAscent above, kDescent below) on the anchor.
  const double centre_shift = 0.5 * (kAscent - kDescent) * kLabelFont;
  std::vector<std::size_t> order(spec.labels.size());
  for (std::size_t k = 0; k < order.size(); ++k) order[k] = k;
  std::stable_sort(order.begin(), order.end(), [&spec](std::size_t a, std::size_t b) {
    return spec.labels[a].anchors.size() > spec.labels[b].anchors.size();
  });
  LabelLayout layout(frame);
  std::ostringstream leaders, texts;
  int omitted = 0;
  for (const std::size_t k : order) {
    const RegionPlotLabel& l = spec.labels[k];
    const auto box_at = [&](double px, double py) {
      return CentredTextBox(px, py + centre_shift, l.text, kLabelFont, kLabelHalo);
    };
    bool placed = false;
    double at_x = 0.0, at_y = 0.0;
    for (std::size_t a = 0; a <= l.anchors.size() && !placed; ++a) {
      const double px = sx(a == 0 ? l.x : l.anchors[a - 1].x);
      const double py = sy(a == 0 ? l.y : l.anchors[a - 1].y);
      if (layout.Place(box_at(px, py))) {
        placed = true;
        at_x = px;
        at_y = py;
      }
    }
    const double ax = sx(l.x), ay = sy(l.y);
    bool leader = false;
    if (!placed) {
      // Nearest free position on a lattice of half a label width by one label height.
      const TextBox b0 = box_at(0.0, 0.0);
      const double step_x = 0.5 * (b0.x1 - b0.x0), step_y = b0.y1 - b0.y0;
      const int nx = static_cast<int>((frame.x1 - frame.x0) / step_x) + 1;
      const int ny = static_cast<int>((frame.y1 - frame.y0) / step_y) + 1;
      double best = 0.0;
      for (int j = -ny; j <= ny; ++j) {
        for (int i = -nx; i <= nx; ++i) {
          const double px = ax + i * step_x, py = ay + j * step_y;
          const double d = std::hypot(px - ax, py - ay);
          if ((!placed || d < best) && layout.Fits(box_at(px, py))) {
            placed = true;
            best = d;
            at_x = px;
            at_y = py;
          }
        }
      }
      if (placed) {
        layout.Place(box_at(at_x, at_y));
        leader = true;
      }
    }
    if (!placed) {
      ++omitted;
      continue;
    }
    if (leader) {
      leaders << "<line x1=\"" << FormatTickNumber(ax) << "\" y1=\"" << FormatTickNumber(ay)
              << "\" x2=\"" << FormatTickNumber(at_x) << "\" y2=\"" << FormatTickNumber(at_y)
              << "\" stroke=\"#333\" stroke-width=\"0.8\"/>\n";
    }
    texts << "<text x=\"" << FormatTickNumber(at_x) << "\" y=\""
          << FormatTickNumber(at_y + centre_shift)
          << "\" text-anchor=\"middle\" font-weight=\"bold\" font-size=\"" << kLabelFont
          << "\" stroke=\"white\" stroke-width=\"3\" paint-order=\"stroke\""
          << LengthAttributes(l.text, kLabelFont) << " class=\"region-label\">"
          << EscapeSvgText(l.text) << "</text>\n";
  }
  s << leaders.str() << texts.str();
  if (omitted > 0) {
    s << "<text x=\"" << FormatTickNumber(frame.x0) << "\" y=\"" << spec.height - 3
      << "\" font-size=\"10\">" << omitted
      << " region label(s) omitted: no room left in the plot (all regions are in the JSON and "
         "CSV files)</text>\n";
  }
}

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
  // Marker labels first: their rows decide where the frame starts.
  std::vector<double> marker_px;
  std::vector<std::string> marker_text;
  std::vector<const RegionPlotMarker*> markers;
  for (const RegionPlotMarker& m : spec.markers) {
    if (m.x < sx.lo || m.x > sx.hi) continue;
    markers.push_back(&m);
    marker_px.push_back(sx(m.x));
    marker_text.push_back(m.text);
  }
  int marker_rows = 0;
  const std::vector<MarkerSlot> marker_slots =
      LayOutMarkerRows(marker_px, marker_text, spec.width, &marker_rows);
  // Row r has its baseline at top − kMarkerGap − r·kMarkerRow; the highest row's box must stay
  // below the title.
  const double top_needed = kTitleBottom + 1.0 + (kAscent * kMarkerFont + 1.0) + kMarkerGap +
                            kMarkerRow * std::max(0, marker_rows - 1);
  const int frame_top = std::max(kTop, static_cast<int>(std::ceil(top_needed)));
  GEARDYN_THROW_UNLESS(frame_top + 40 < spec.height - kBottom,
                       "RenderRegionSvg: " << marker_rows << " rows of marker labels leave no room "
                                           << "for the plot (height " << spec.height << " px)");

  const Scale sy{spec.y_values.front() - 0.5 * dy, spec.y_values.back() + 0.5 * dy,
                 static_cast<double>(spec.height - kBottom), static_cast<double>(frame_top)};
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
  const double left = kLeft, right = spec.width - kRight, top = frame_top,
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
  for (std::size_t k = 0; k < markers.size(); ++k) {
    const double p = marker_px[k];
    const double baseline = top - kMarkerGap - kMarkerRow * marker_slots[k].row;
    s << "<line x1=\"" << FormatTickNumber(p) << "\" y1=\"" << top << "\" x2=\""
      << FormatTickNumber(p) << "\" y2=\"" << bottom
      << "\" stroke=\"#555\" stroke-dasharray=\"4,4\"/><text x=\""
      << FormatTickNumber(marker_slots[k].x) << "\" y=\"" << FormatTickNumber(baseline)
      << "\" text-anchor=\"middle\" font-size=\"" << kMarkerFont << "\""
      << LengthAttributes(markers[k]->text, kMarkerFont) << " class=\"marker-label\">"
      << EscapeSvgText(markers[k]->text) << "</text>\n";
  }
  std::vector<const RegionPlotCurve*> legend;  // the first curve of each distinct label
  for (const RegionPlotCurve& c : spec.curves) {
    if (!c.label.empty() &&
        std::none_of(legend.begin(), legend.end(),
                     [&](const RegionPlotCurve* l) { return l->label == c.label; })) {
      legend.push_back(&c);
    }
    if (c.x.empty()) continue;
    s << "<" << (c.closed ? "polygon" : "polyline") << " fill=\"none\" stroke=\""
      << (c.colour.empty() ? "black" : EscapeSvgText(c.colour)) << "\" "
      << "stroke-width=\"1.5\" points=\"";
    for (std::size_t k = 0; k < c.x.size() && k < c.y.size(); ++k) {
      s << (k ? " " : "") << FormatTickNumber(sx(c.x[k])) << "," << FormatTickNumber(sy(c.y[k]));
    }
    s << "\"/>\n";
  }
  // Legend of the labelled curves (e.g. one colour per model level), top right inside the axes.
  for (std::size_t k = 0; k < legend.size(); ++k) {
    const double y = top + 16.0 + 16.0 * static_cast<double>(k);
    const std::string colour = legend[k]->colour.empty() ? "black" : legend[k]->colour;
    s << "<line x1=\"" << FormatTickNumber(right - 150.0) << "\" y1=\"" << FormatTickNumber(y - 4.0)
      << "\" x2=\"" << FormatTickNumber(right - 126.0) << "\" y2=\"" << FormatTickNumber(y - 4.0)
      << "\" stroke=\"" << EscapeSvgText(colour) << "\" stroke-width=\"2\"/><text x=\""
      << FormatTickNumber(right - 120.0) << "\" y=\"" << FormatTickNumber(y)
      << "\" font-size=\"12\" stroke=\"white\" stroke-width=\"3\" paint-order=\"stroke\">"
      << EscapeSvgText(legend[k]->label) << "</text>\n";
  }
  LayOutRegionLabels(spec, sx, sy, TextBox{left, top, right, bottom}, s);
  s << "</svg>\n";
  return s.str();
}

}  // namespace geardyn::app
