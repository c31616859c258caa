#include "geardyn/label_layout.hpp"

namespace geardyn::app {

int CodePoints(const std::string& text) {
  int n = 0;
  for (const char c : text) {
    // Count every byte that does not continue a multi-byte sequence (10xxxxxx).
    if ((static_cast<unsigned char>(c) & 0xC0U) != 0x80U) ++n;
  }
  return n;
}

double TextWidth(const std::string& text, double font_size) {
  return kGlyphAdvance * font_size * CodePoints(text);
}

TextBox CentredTextBox(double x, double baseline, const std::string& text, double font_size,
                       double halo) {
  const double half = 0.5 * TextWidth(text, font_size) + halo;
  return {x - half, baseline - kAscent * font_size - halo, x + half,
          baseline + kDescent * font_size + halo};
}

bool LabelLayout::Fits(const TextBox& box) const {
  if (!box.Inside(bounds_)) return false;
  for (const TextBox& b : boxes_) {
    if (b.Intersects(box)) return false;
  }
  return true;
}

bool LabelLayout::Place(const TextBox& box) {
  if (!Fits(box)) return false;
  boxes_.push_back(box);
  return true;
}

}  // namespace geardyn::app
