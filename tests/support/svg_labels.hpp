/// @file
/// @brief The text labels of an SVG written by the geardyn plots, read back for the layout
/// tests: every `<text>` element with a class (region-label, marker-label), its position,
/// font size, textLength and the box it covers when rendered.
///
/// The box is what SVG guarantees, not what the writer estimated: `textLength` with
/// `lengthAdjust="spacingAndGlyphs"` makes the advance exactly textLength (SVG 1.1 §10.5), centred
/// on x for text-anchor="middle"; vertically the glyphs stay inside the em box, 0.8 em above the
/// baseline (capitals, parentheses ≈ 0.75 em in Helvetica/Arial) and 0.25 em below it ('_',
/// parentheses ≈ 0.2 em).
#pragma once

#include <gtest/gtest.h>

#include <regex>
#include <string>
#include <vector>

namespace geardyn::test {

/// One laid-out label of an SVG.
struct SvgLabel {
  std::string cls;   ///< class attribute
  std::string text;  ///< content (escaped as in the file)
  double x = 0.0, y = 0.0, font_size = 0.0, length = 0.0;
  double x0 = 0.0, y0 = 0.0, x1 = 0.0, y1 = 0.0;  ///< rendered box [px]
  bool Intersects(const SvgLabel& o) const {
    return x0 < o.x1 && o.x0 < x1 && y0 < o.y1 && o.y0 < y1;
  }
};

/// Every `<text>` with a class attribute; fails the test on one without textLength or that is
/// not centred (text-anchor="middle").
inline std::vector<SvgLabel> ReadSvgLabels(const std::string& svg) {
  static const std::regex text_re("<text([^>]*)>([^<]*)</text>");
  const auto attr = [](const std::string& attrs, const std::string& name) {
    const std::regex re(" " + name + "=\"([^\"]*)\"");
    std::smatch m;
    return std::regex_search(attrs, m, re) ? m[1].str() : std::string();
  };
  std::vector<SvgLabel> out;
  for (auto it = std::sregex_iterator(svg.begin(), svg.end(), text_re);
       it != std::sregex_iterator(); ++it) {
    const std::string attrs = (*it)[1].str();
    SvgLabel l;
    l.cls = attr(attrs, "class");
    if (l.cls.empty()) continue;
    l.text = (*it)[2].str();
    const std::string length = attr(attrs, "textLength");
    EXPECT_FALSE(length.empty()) << "label without textLength: " << l.text;
    EXPECT_EQ(attr(attrs, "lengthAdjust"), "spacingAndGlyphs") << l.text;
    EXPECT_EQ(attr(attrs, "text-anchor"), "middle") << l.text;
    if (length.empty()) continue;
    l.x = std::stod(attr(attrs, "x"));
    l.y = std::stod(attr(attrs, "y"));
    l.font_size = std::stod(attr(attrs, "font-size"));
    l.length = std::stod(length);
    l.x0 = l.x - 0.5 * l.length;
    l.x1 = l.x + 0.5 * l.length;
    l.y0 = l.y - 0.8 * l.font_size;
    l.y1 = l.y + 0.25 * l.font_size;
    out.push_back(l);
  }
  return out;
}

/// Fails for every pair of labels whose boxes intersect.
inline ::testing::AssertionResult NoLabelsOverlap(const std::vector<SvgLabel>& labels) {
  for (std::size_t a = 0; a < labels.size(); ++a) {
    for (std::size_t b = a + 1; b < labels.size(); ++b) {
      if (labels[a].Intersects(labels[b])) {
        return ::testing::AssertionFailure()
               << "'" << labels[a].text << "' at (" << labels[a].x << ", " << labels[a].y
               << ") overlaps '" << labels[b].text << "' at (" << labels[b].x << ", " << labels[b].y
               << ")";
      }
    }
  }
  return ::testing::AssertionSuccess();
}

}  // namespace geardyn::test
