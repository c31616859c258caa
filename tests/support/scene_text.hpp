/// @file
/// @brief Scene text shared by the scene-reader tests: the spur pair (20/40 teeth, m_n = 2 mm,
/// b = 20 mm, its [[gear]] and [[mesh]] tables) that the reader's bad-input tables and the shaft
/// tests build on, and the two text helpers they use (Replace, LineOf). Every table header line
/// carries a comment that makes it unique, so a case can name the line it expects by its text.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <string_view>

namespace geardyn::test {

/// The [[gear]] pinion and wheel and their [[mesh]], ending with the mesh's last line
/// `gear = "wheel"` and a newline.
inline constexpr std::string_view kSpurPairTables = R"([[gear]]  # pinion
name = "pinion"
teeth = 20
normal_module = 0.002
face_width = 0.02
mass = 0.5
inertia = 1e-4

[[gear]]  # wheel
name = "wheel"
teeth = 40
normal_module = 0.002
face_width = 0.02
mass = 2.0
inertia = 1.6e-3

[[mesh]]  # pinion-wheel
pinion = "pinion"
gear = "wheel"
)";

/// A scene: `title = "<title>"`, a blank line, the spur pair, a blank line, then `rest`.
inline std::string SpurPairScene(std::string_view title, std::string_view rest) {
  std::string s = "title = \"";
  s.append(title).append("\"\n\n").append(kSpurPairTables).append("\n").append(rest);
  return s;
}

/// `text` with the first occurrence of `from` replaced by `to` (which must exist).
inline std::string Replace(std::string_view text, std::string_view from, std::string_view to) {
  std::string s(text);
  const std::size_t pos = s.find(from);
  if (pos == std::string::npos) {
    ADD_FAILURE() << "test setup: '" << from << "' not found";
    return s;
  }
  return s.replace(pos, from.size(), to);
}

/// 1-based line of the first occurrence of `needle` in `text` (0 if `needle` is empty).
inline int LineOf(std::string_view text, std::string_view needle) {
  if (needle.empty()) return 0;
  const std::size_t pos = text.find(needle);
  if (pos == std::string_view::npos) {
    ADD_FAILURE() << "test setup: line '" << needle << "' not found";
    return -1;
  }
  return 1 +
         static_cast<int>(std::count(text.begin(), text.begin() + static_cast<long>(pos), '\n'));
}

}  // namespace geardyn::test
