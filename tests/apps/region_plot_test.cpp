// RenderRegionSvg's label layout (region_plot.hpp): on a chart with many narrow regions, each
// labelled and each with a resonance marker, no two label boxes intersect, every label is placed
// (none omitted), region labels stay inside the frame and marker labels above it. The boxes are
// read back from the SVG (textLength fixes the rendered width; tests/support/svg_labels.hpp).
#include "geardyn/region_plot.hpp"

#include <gtest/gtest.h>

#include <string>

#include "support/svg_labels.hpp"

namespace geardyn {
namespace {

using test::NoLabelsOverlap;
using test::ReadSvgLabels;
using test::SvgLabel;

// nx × ny grid over [0, 1]²; `stripes` unstable stripes, each 2 columns wide and full height
// (the tongues of a chart over speed × excitation, narrow at this resolution), labelled with
// long combination-resonance labels, a marker at every stripe, all peaks in the top row.
app::RegionPlotSpec NarrowStripes(int nx, int ny, int stripes) {
  app::RegionPlotSpec spec;
  spec.title = "many narrow regions";
  spec.x_label = "operating_point.speed_rpm";
  spec.y_label = "mesh.pinion-wheel.parameters.stiffness.1";
  for (int i = 0; i < nx; ++i) spec.x_values.push_back(static_cast<double>(i) / (nx - 1));
  for (int i = 0; i < ny; ++i) spec.y_values.push_back(static_cast<double>(i) / (ny - 1));
  spec.max_abs_multiplier.assign(nx * ny, 0.99);
  spec.stable.assign(nx * ny, 1);
  spec.ok.assign(nx * ny, 1);
  const int pitch = nx / stripes;
  for (int s = 0; s < stripes; ++s) {
    // Columns ix and ix + 1 of the stripe stay inside its pitch (with pitch / 2 the last stripe
    // of a pitch-2 grid wrote one column past the end: ASan, heap-buffer-overflow).
    const int ix = s * pitch + (pitch - 1) / 2;
    app::RegionPlotLabel label{spec.x_values[ix],
                               spec.y_values[ny - 1],
                               "(f_" + std::to_string(s) + "+f_" + std::to_string(s + 10) + ")/2",
                               {}};
    for (int iy = ny - 1; iy >= 0; --iy) {
      for (int c = ix; c <= ix + 1; ++c) {
        spec.stable[iy * nx + c] = 0;
        spec.max_abs_multiplier[iy * nx + c] = 1.0 + 0.01 * iy;
        if (!(c == ix && iy == ny - 1))
          label.anchors.push_back({spec.x_values[c], spec.y_values[iy]});
      }
    }
    spec.markers.push_back({spec.x_values[ix], label.text});
    spec.labels.push_back(std::move(label));
  }
  return spec;
}

// The frame rectangle of the plot: the <rect fill="none" stroke="black"/> after the cells.
struct Frame {
  double x0, y0, x1, y1;
};
Frame ReadFrame(const std::string& svg) {
  const std::string key = "fill=\"none\" stroke=\"black\"/>";
  const std::size_t end = svg.find(key);
  const std::size_t start = svg.rfind("<rect", end);
  const std::string r = svg.substr(start, end - start);
  const auto num = [&r](const std::string& name) {
    const std::size_t p = r.find(" " + name + "=\"") + name.size() + 3;
    return std::stod(r.substr(p));
  };
  return {num("x"), num("y"), num("x") + num("width"), num("y") + num("height")};
}

int CodePoints(const std::string& s) {
  int n = 0;
  for (const char c : s) n += (static_cast<unsigned char>(c) & 0xC0U) != 0x80U;
  return n;
}

TEST(RegionPlot, ManyNarrowRegionsGetEveryLabelWithoutOverlap) {
  for (const int stripes : {3, 12, 30}) {
    const std::string svg = app::RenderRegionSvg(NarrowStripes(150, 24, stripes));
    const std::vector<SvgLabel> labels = ReadSvgLabels(svg);
    int regions = 0, markers = 0;
    const Frame f = ReadFrame(svg);
    for (const SvgLabel& l : labels) {
      // The laid-out width is a plausible sans-serif advance (0.5–0.7 em per glyph), so the
      // text is neither squeezed nor stretched much.
      const double em_per_glyph = l.length / (l.font_size * CodePoints(l.text));
      EXPECT_GT(em_per_glyph, 0.5);
      EXPECT_LT(em_per_glyph, 0.7);
      if (l.cls == "region-label") {
        ++regions;
        EXPECT_TRUE(l.x0 >= f.x0 && l.x1 <= f.x1 && l.y0 >= f.y0 && l.y1 <= f.y1)
            << l.text << " outside the frame";
      } else {
        ASSERT_EQ(l.cls, "marker-label");
        ++markers;
        EXPECT_LE(l.y1, f.y0) << l.text << " reaches into the frame";
        EXPECT_GE(l.y0, 30.0) << l.text << " reaches into the title";
        EXPECT_GE(l.x0, 0.0);
        EXPECT_LE(l.x1, 900.0);
      }
    }
    EXPECT_EQ(regions, stripes);
    EXPECT_EQ(markers, stripes);
    EXPECT_TRUE(NoLabelsOverlap(labels)) << stripes << " stripes";
    EXPECT_EQ(svg.find("omitted"), std::string::npos);
  }
}

TEST(RegionPlot, LabelsThatCannotFitAreOmittedWithANote) {
  // 400 regions on a 900 × 620 figure: a frame of 780 × 510 px holds about 8 × 30 labels of
  // this length, so some must go; the ones shown still do not overlap.
  app::RegionPlotSpec spec = NarrowStripes(800, 10, 400);
  spec.markers.clear();
  const std::string svg = app::RenderRegionSvg(spec);
  const std::vector<SvgLabel> labels = ReadSvgLabels(svg);
  EXPECT_LT(labels.size(), 400u);
  EXPECT_GT(labels.size(), 100u);
  EXPECT_TRUE(NoLabelsOverlap(labels));
  EXPECT_NE(svg.find(std::to_string(400 - labels.size()) + " region label(s) omitted"),
            std::string::npos);
}

}  // namespace
}  // namespace geardyn
