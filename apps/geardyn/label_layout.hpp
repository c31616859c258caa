/// @file
/// @brief Collision-free placement of SVG text labels (region_plot): the box a label occupies
/// and a greedy layout that accepts a label only where its box meets no box placed before.
///
/// **Box of a text.** The writers give every laid-out label an explicit `textLength` with
/// `lengthAdjust="spacingAndGlyphs"`, so its rendered width is exactly TextWidth() whatever the
/// font; the height is the em box from kAscent·size above the baseline to kDescent·size below
/// (parentheses and '_' reach below the baseline), plus the white halo drawn around the glyphs.
#pragma once

#include <string>
#include <vector>

namespace geardyn::app {

/// Average advance of a sans-serif glyph [em] (Helvetica/Arial digits and lower case: 0.5–0.6).
inline constexpr double kGlyphAdvance = 0.6;
/// Extent of the em box above the baseline [em] (capitals and parentheses: ≈ 0.75).
inline constexpr double kAscent = 0.8;
/// Extent below the baseline [em] ('_', parentheses: ≈ 0.2).
inline constexpr double kDescent = 0.25;

/// Axis-aligned box in SVG pixels (y grows downwards).
struct TextBox {
  double x0 = 0.0, y0 = 0.0, x1 = 0.0, y1 = 0.0;
  /// True when the interiors overlap (boxes that only touch do not).
  bool Intersects(const TextBox& o) const {
    return x0 < o.x1 && o.x0 < x1 && y0 < o.y1 && o.y0 < y1;
  }
  /// True when this box lies inside `o` (edges included).
  bool Inside(const TextBox& o) const {
    return x0 >= o.x0 && x1 <= o.x1 && y0 >= o.y0 && y1 <= o.y1;
  }
};

/// Number of Unicode code points of UTF-8 `text` (what a glyph count means for "μ" or "λ").
int CodePoints(const std::string& text);

/// Rendered width [px] of `text` at `font_size` [px]: kGlyphAdvance·size per code point.
double TextWidth(const std::string& text, double font_size);

/// The box of `text` at font size `font_size` [px], horizontally centred on `x` (text-anchor
/// "middle"), baseline at `baseline` [px], grown by `halo` [px] on every side.
TextBox CentredTextBox(double x, double baseline, const std::string& text, double font_size,
                       double halo);

/// Greedy layout: Place() accepts a box only if it is inside the bounds and meets no accepted
/// box.
class LabelLayout {
 public:
  explicit LabelLayout(const TextBox& bounds) : bounds_(bounds) {}
  /// Adds `box` and returns true when it fits; leaves the layout unchanged otherwise.
  bool Place(const TextBox& box);
  /// True when `box` would fit (inside the bounds, meeting no accepted box).
  bool Fits(const TextBox& box) const;
  const std::vector<TextBox>& boxes() const { return boxes_; }

 private:
  TextBox bounds_;
  std::vector<TextBox> boxes_;
};

}  // namespace geardyn::app
