/// @file
/// @brief Shared by the scene-reader tests (scene_reader_*_test.cpp): the base spur pair with a
/// bearing, a load and an operating point (every bad-input case edits one thing in it), its
/// helical and three-gear variants, and the bad-input case type with its check
/// (FILE:LINE: KEY: REASON).
#pragma once

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <ostream>
#include <regex>
#include <set>
#include <string>
#include <vector>

#include "geardyn/models/scene/scene_reader.hpp"
#include "support/scene_text.hpp"

namespace geardyn::test {

/// A valid spur pair (support/scene_text.hpp) with bearing b1, load brake and an operating point.
inline const std::string kBase = SpurPairScene("test pair", R"([[bearing]]  # b1
name = "b1"
body = "pinion"
stiffness = [1e9, 1e9, 1e9, 1e7, 1e7, 0]

[[load]]  # brake
name = "brake"
body = "wheel"
torque = 100.0

[operating_point]
speed_rpm = 3000
torque = 50
)");

inline constexpr const char* kSource = "t.toml";

// The base pair made helical: pinion right-handed, wheel left-handed, 15°.
inline std::string Helical() {
  std::string s = Replace(kBase, "name = \"pinion\"\n",
                          "name = \"pinion\"\nhelix_angle_deg = 15.0\nhand = \"right\"\n");
  return Replace(s, "name = \"wheel\"\n",
                 "name = \"wheel\"\nhelix_angle_deg = 15.0\nhand = \"left\"\n");
}

// A third gear meshing with both others: three external gears in a triangle cannot turn.
inline std::string Triangle() {
  std::string s = Replace(kBase, "[[mesh]]  # pinion-wheel", R"([[gear]]  # idler
name = "idler"
teeth = 30
normal_module = 0.002
face_width = 0.02
mass = 1.0
inertia = 5e-4

[[mesh]]  # pinion-idler
pinion = "pinion"
gear = "idler"

[[mesh]]  # idler-wheel
pinion = "idler"
gear = "wheel"

[[mesh]]  # pinion-wheel)");
  return s;
}

struct BadCase {
  std::string name;                    // test name suffix
  std::string text;                    // the scene
  std::vector<std::string> overrides;  // --set
  std::string line_of;                 // the expected line contains this ("" = no line)
  std::string regex;                   // what() must match; "{line}" stands for that line
};

inline std::ostream& operator<<(std::ostream& os, const BadCase& c) { return os << c.name; }

/// Parses `c` and expects a SceneError at the line `c.line_of` names whose what() matches
/// `c.regex` ("{line}" stands for that line).
inline void ExpectSceneError(const BadCase& c) {
  const int line = LineOf(c.text, c.line_of);
  const std::string regex =
      std::regex_replace(c.regex, std::regex(R"(\{line\})"), std::to_string(line));
  try {
    (void)ParseScene(c.text, kSource, c.overrides);
    ADD_FAILURE() << "no SceneError; expected " << regex;
  } catch (const SceneError& e) {
    EXPECT_THAT(std::string(e.what()), ::testing::ContainsRegex(regex));
    EXPECT_EQ(e.line(), line) << e.what();
    EXPECT_EQ(e.source(), kSource);
  }
}

/// The case names of a table are unique (they name the parameterized tests).
inline void ExpectUniqueNames(const std::vector<BadCase>& cases) {
  std::set<std::string> names;
  for (const BadCase& c : cases) EXPECT_TRUE(names.insert(c.name).second) << c.name;
}

/// gtest's parameter name: the case name.
inline std::string CaseName(const ::testing::TestParamInfo<BadCase>& param_info) {
  return param_info.param.name;
}

}  // namespace geardyn::test
