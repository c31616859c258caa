// [[shaft]] and [damping] tables of the scene reader: what they read (SI, node placement) and
// every rejection, located FILE:LINE: KEY: REASON.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "geardyn/models/scene/scene_reader.hpp"
#include "support/scene_text.hpp"

namespace geardyn {
namespace {

// The spur pair of support/scene_text.hpp on two shafts (one of two sections), bearings at
// stations, a torsional coupling from the input shaft to a motor shaft, and system damping. Every
// table header line is unique.
const std::string kBase = test::SpurPairScene("shafts", R"([[shaft]]  # input
name = "input"
youngs_modulus = 2.1e11
poisson_ratio = 0.3
density = 7850
sections = [
  { length = 0.1, outer_diameter = 0.03, elements = 2 },
  { length = 0.2, outer_diameter = 0.04, inner_diameter = 0.01, elements = 3 },
]
gears = [{ gear = "pinion", station = 0.15 }]

[[shaft]]  # output
name = "output"
youngs_modulus = 2.1e11
shear_modulus = 8.0e10
density = 7850
max_element_length = 0.05
sections = [{ length = 0.2, outer_diameter = 0.05 }]
gears = [{ gear = "wheel", station = 0.1 }]

[[shaft]]  # motor
name = "motor"
youngs_modulus = 2.1e11
poisson_ratio = 0.3
density = 7850
sections = [{ length = 0.1, outer_diameter = 0.03, elements = 1 }]

[[bearing]]  # b1
name = "b1"
body = "input"
station = 0.0
stiffness = [1e9, 1e9, 1e9, 0, 0, 0]

[[bearing]]  # b2
name = "b2"
body = "output"
station = 0.2
stiffness = [1e9, 1e9, 1e9, 0, 0, 0]

[[bearing]]  # coupling
name = "coupling"
body = "motor"
station = 0.1
other = "input"
other_station = 0.0
stiffness = [0, 0, 0, 0, 0, 1e4]

[operating_point]
speed_rpm = 3000
torque = 50

[damping]
modal_ratio = 0.02
)");

using test::LineOf;
using test::Replace;

TEST(ShaftReaderTest, ReadsSectionsMaterialStationsAndNodes) {
  const Scene s = ParseScene(kBase, "t.toml");
  ASSERT_EQ(s.shafts.size(), 3u);
  const ShaftDef& in = s.shafts[0];
  EXPECT_DOUBLE_EQ(in.length(), 0.3);
  EXPECT_DOUBLE_EQ(in.sections[1].section.inner_diameter, 0.01);
  // G = E / (2 (1 + ν)).
  EXPECT_DOUBLE_EQ(in.material.shear_modulus, 2.1e11 / 2.6);
  EXPECT_DOUBLE_EQ(s.shafts[1].material.shear_modulus, 8.0e10);
  // Nodes: section ends 0, 0.1, 0.3, the gear at 0.15 and the coupling at 0; elements no longer
  // than 0.05 in the first section and 0.2/3 in the second: 0, 0.05, 0.1 | 0.15 | 0.2, 0.25, 0.3.
  const std::vector<double> expected = {0.0, 0.05, 0.1, 0.15, 0.2, 0.25, 0.3};
  ASSERT_EQ(in.nodes.size(), expected.size());
  for (std::size_t k = 0; k < expected.size(); ++k) EXPECT_NEAR(in.nodes[k], expected[k], 1e-15);
  EXPECT_EQ(s.shafts[1].nodes.size(), 5u);  // 0.2 m at ≤ 0.05 m
  ASSERT_TRUE(s.bearings[2].station && s.bearings[2].other_station);
  EXPECT_DOUBLE_EQ(*s.bearings[2].station, 0.1);
  // Gears on one shaft turn together; the coupling carries the motor along.
  EXPECT_DOUBLE_EQ(s.GearSpeed("wheel"), -0.5 * s.GearSpeed("pinion"));
  ASSERT_TRUE(s.damping.modal_ratio.has_value());
  EXPECT_DOUBLE_EQ(*s.damping.modal_ratio, 0.02);
  EXPECT_FALSE(s.damping.has_rayleigh());
}

struct Case {
  std::string name, from, to, line_of, regex;
};

std::ostream& operator<<(std::ostream& os, const Case& c) { return os << c.name; }

class ShaftReaderBadInputTest : public ::testing::TestWithParam<Case> {};

TEST_P(ShaftReaderBadInputTest, ReportsFileLineKeyAndReason) {
  const Case& c = GetParam();
  const std::string text = Replace(kBase, c.from, c.to);
  try {
    (void)ParseScene(text, "t.toml");
    ADD_FAILURE() << "no SceneError; expected " << c.regex;
  } catch (const SceneError& e) {
    EXPECT_THAT(std::string(e.what()), ::testing::ContainsRegex(c.regex));
    EXPECT_EQ(e.line(), LineOf(text, c.line_of)) << e.what();
  }
}

std::vector<Case> Cases() {
  return {
      {"ZeroDiameter", "length = 0.2, outer_diameter = 0.05", "length = 0.2, outer_diameter = 0",
       "outer_diameter = 0 }",
       R"(^t\.toml:[0-9]+: shaft\.output\.sections\[0\]\.outer_diameter: must be > 0)"},
      {"InnerNotBelowOuter", "inner_diameter = 0.01", "inner_diameter = 0.04",
       "inner_diameter = 0.04",
       R"(shaft\.input\.sections\[1\]\.inner_diameter: must be less than outer_diameter = 0\.04)"},
      {"StationOutsideShaft", "station = 0.15", "station = 0.35", "station = 0.35",
       R"(shaft\.input\.gears\[0\]\.station: station 0\.35 m is outside shaft 'input' \(length 0\.3 m\))"},
      {"BearingStationOutsideShaft", "station = 0.2\n", "station = -0.1\n", "station = -0.1",
       R"(bearing\.b2\.station: station -0\.1 m is outside shaft 'output')"},
      {"GearOnTwoShafts", "gear = \"wheel\", station = 0.1", "gear = \"pinion\", station = 0.1",
       "\"pinion\", station = 0.1 }",
       R"(shaft\.output\.gears\[0\]\.gear: 'pinion' is already on shaft 'input')"},
      {"BearingStationMissing", "station = 0.2\n", "\n", "[[bearing]]  # b2",
       R"(bearing\.b2\.station: missing \(required: axial position on shaft 'output')"},
      {"StationOnAGear", "body = \"input\"\nstation = 0.0", "body = \"pinion\"\nstation = 0.0",
       "station = 0.0\nstiffness = [1e9",
       R"(bearing\.b1\.station: only a bearing on a \[\[shaft\]\] has a station)"},
      {"UnknownBody", "body = \"output\"", "body = \"outptu\"", "body = \"outptu\"",
       R"(bearing\.b2\.body: no gear or shaft named 'outptu' \(did you mean 'output'\?\))"},
      {"NoElementCount", "length = 0.1, outer_diameter = 0.03, elements = 1 }",
       "length = 0.1, outer_diameter = 0.03 }",
       "sections = [{ length = 0.1, outer_diameter = 0.03 }]",
       R"(shaft\.motor\.sections\[0\]\.elements: missing \(required: number of beam elements)"},
      {"TooManyElements", "max_element_length = 0.05", "max_element_length = 1e-5",
       "max_element_length = 1e-5",
       R"(shaft\.output\.max_element_length: gives 20000 elements, more than 5000 per shaft)"},
      {"NoMaterial", "youngs_modulus = 2.1e11\nshear_modulus", "shear_modulus",
       "[[shaft]]  # output", R"(shaft\.output\.youngs_modulus: missing)"},
      {"BothNuAndG", "shear_modulus = 8.0e10", "shear_modulus = 8.0e10\npoisson_ratio = 0.3",
       "shear_modulus = 8.0e10",
       R"(shaft\.output\.shear_modulus: give shear_modulus or poisson_ratio, not both)"},
      {"ShaftNamedLikeAGear", "name = \"motor\"", "name = \"wheel\"", "name = \"wheel\"\nyoungs",
       R"(shaft\.wheel\.name: 'wheel' is already a gear's name)"},
      {"UnknownShaftKey", "density = 7850\nsections = [{ length = 0.1",
       "density = 7850\ndiameter = 3\nsections = [{ length = 0.1", "diameter = 3",
       R"(shaft\.motor\.diameter: unknown key)"},
      {"PlanarWithShafts", "title = \"shafts\"", "title = \"shafts\"\nplanar = true",
       "planar = true", R"(planar: a scene with \[\[shaft\]\] cannot be planar)"},
      {"DampingRatioOne", "modal_ratio = 0.02", "modal_ratio = 1.0", "modal_ratio = 1.0",
       R"(damping\.modal_ratio: must be a damping ratio in \[0, 1\), got 1$)"},
      {"DampingBothKinds", "modal_ratio = 0.02", "modal_ratio = 0.02\nrayleigh_beta = 1e-5",
       "rayleigh_beta = 1e-5", R"(damping\.rayleigh_beta: give either modal damping)"},
      {"DampingNegativeAlpha", "modal_ratio = 0.02", "rayleigh_alpha = -1", "rayleigh_alpha = -1",
       R"(damping\.rayleigh_alpha: must be >= 0)"},
      {"DampingListEntry", "modal_ratio = 0.02", "modal_ratios = [0.01, 2.0]",
       "modal_ratios = [0.01, 2.0]",
       R"(damping\.modal_ratios: entry 1 must be a damping ratio in \[0, 1\), got 2$)"},
  };
}

INSTANTIATE_TEST_SUITE_P(Cases, ShaftReaderBadInputTest, ::testing::ValuesIn(Cases()),
                         [](const ::testing::TestParamInfo<Case>& param_info) {
                           return param_info.param.name;
                         });

}  // namespace
}  // namespace geardyn
