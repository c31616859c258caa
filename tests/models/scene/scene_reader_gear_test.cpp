// Scene reader, [[gear]] tables and unknown keys at every level: each bad input is reported as
// FILE:LINE: KEY: REASON (the base scene and the case type are in scene_reader_cases.hpp).
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "scene_reader_cases.hpp"

namespace geardyn {
namespace {

using test::BadCase;
using test::kBase;
using test::Replace;

std::vector<BadCase> GearCases() {
  const std::string base(kBase);
  const std::string helical = test::Helical();
  std::vector<BadCase> c;
  // --- gear fields -------------------------------------------------------------------------
  c.push_back({"MissingTeeth",
               Replace(base, "teeth = 40\n", ""),
               {},
               "[[gear]]  # wheel",
               R"(^t\.toml:{line}: gear\.wheel\.teeth: missing \(required: number of teeth)"});
  c.push_back({"NegativeTeeth",
               Replace(base, "teeth = 40", "teeth = -5"),
               {},
               "teeth = -5",
               R"(^t\.toml:{line}: gear\.wheel\.teeth: must be a positive integer, got -5$)"});
  c.push_back({"ZeroTeeth",
               Replace(base, "teeth = 20", "teeth = 0"),
               {},
               "teeth = 0",
               R"(^t\.toml:{line}: gear\.pinion\.teeth: must be a positive integer, got 0$)"});
  c.push_back(
      {"TeethAsFloat",
       Replace(base, "teeth = 20", "teeth = 20.0"),
       {},
       "teeth = 20.0",
       R"(^t\.toml:{line}: gear\.pinion\.teeth: must be a positive integer, got 20 \(a float\)$)"});
  c.push_back(
      {"TeethAsString",
       Replace(base, "teeth = 20", "teeth = \"20\""),
       {},
       "teeth = \"20\"",
       R"(^t\.toml:{line}: gear\.pinion\.teeth: must be a positive integer, got string "20"$)"});
  c.push_back({"TeethHuge",
               Replace(base, "teeth = 20", "teeth = 3000000000"),
               {},
               "3000000000",
               R"(^t\.toml:{line}: gear\.pinion\.teeth: must be at most 10000, got 3000000000$)"});
  c.push_back({"ModuleNan",
               Replace(base, "normal_module = 0.002", "normal_module = nan"),
               {},
               "normal_module = nan",
               R"(^t\.toml:{line}: gear\.pinion\.normal_module: must be finite, got nan$)"});
  c.push_back({"ModuleInf",
               Replace(base, "normal_module = 0.002", "normal_module = +inf"),
               {},
               "normal_module = +inf",
               R"(^t\.toml:{line}: gear\.pinion\.normal_module: must be finite, got inf$)"});
  c.push_back(
      {"ModuleInMillimetres",
       Replace(base, "normal_module = 0.002", "normal_module = 2"),
       {},
       "normal_module = 2\n",
       R"(^t\.toml:{line}: gear\.pinion\.normal_module: must be at most 0\.1 m \(lengths are in metres)"});
  c.push_back(
      {"ModuleAsString",
       Replace(base, "normal_module = 0.002", "normal_module = \"2mm\""),
       {},
       "2mm",
       R"(^t\.toml:{line}: gear\.pinion\.normal_module: must be a number, got string "2mm"$)"});
  c.push_back({"NegativeFaceWidth",
               Replace(base, "face_width = 0.02", "face_width = -0.02"),
               {},
               "face_width = -0.02",
               R"(^t\.toml:{line}: gear\.pinion\.face_width: must be > 0, got -0\.02$)"});
  c.push_back({"NegativeMass",
               Replace(base, "mass = 0.5", "mass = -0.5"),
               {},
               "mass = -0.5",
               R"(^t\.toml:{line}: gear\.pinion\.mass: must be > 0, got -0\.5$)"});
  c.push_back({"ZeroInertia",
               Replace(base, "inertia = 1e-4", "inertia = 0.0"),
               {},
               "inertia = 0.0",
               R"(^t\.toml:{line}: gear\.pinion\.inertia: must be > 0, got 0$)"});
  c.push_back({"TransverseInertiaTooSmall",
               Replace(base, "inertia = 1e-4", "inertia = 1e-4\ntransverse_inertia = 4e-5"),
               {},
               "transverse_inertia",
               R"(^t\.toml:{line}: gear\.pinion\.transverse_inertia: must be at least inertia/2)"});
  c.push_back(
      {"PressureAngleOutOfRange",
       Replace(base, "teeth = 20", "teeth = 20\nnormal_pressure_angle_deg = 60"),
       {},
       "normal_pressure_angle_deg = 60",
       R"(^t\.toml:{line}: gear\.pinion\.normal_pressure_angle_deg: must be in \(0, 45\) degrees, got 60$)"});
  c.push_back(
      {"NegativeHelix",
       Replace(helical, "helix_angle_deg = 15.0", "helix_angle_deg = -15.0"),
       {},
       "helix_angle_deg = -15.0",
       R"(^t\.toml:{line}: gear\.pinion\.helix_angle_deg: must be >= 0 \(give the direction with hand)"});
  c.push_back(
      {"HandMissingForHelical",
       Replace(helical, "hand = \"left\"\n", ""),
       {},
       "[[gear]]  # wheel",
       R"(^t\.toml:{line}: gear\.wheel\.hand: missing \(required: "right" or "left" for a helical gear)"});
  c.push_back({"HandGivenForSpur",
               Replace(base, "teeth = 40", "teeth = 40\nhand = \"left\""),
               {},
               "hand = \"left\"",
               R"(^t\.toml:{line}: gear\.wheel\.hand: must not be given for a spur gear)"});
  c.push_back(
      {"HandMisspelt",
       Replace(helical, "hand = \"left\"", "hand = \"lefft\""),
       {},
       "hand = \"lefft\"",
       R"(^t\.toml:{line}: gear\.wheel\.hand: must be "right" or "left", got "lefft" \(did you mean 'left'\?\)$)"});
  c.push_back(
      {"InternalNotBool",
       Replace(base, "teeth = 40", "teeth = 40\ninternal = \"yes\""),
       {},
       "internal = \"yes\"",
       R"(^t\.toml:{line}: gear\.wheel\.internal: must be a boolean \(true or false\), got string "yes"$)"});
  c.push_back({"MissingGearName",
               Replace(base, "name = \"wheel\"\n", ""),
               {},
               "[[gear]]  # wheel",
               R"(^t\.toml:{line}: gear\[1\]\.name: missing \(required: a unique name)"});
  c.push_back({"EmptyGearName",
               Replace(base, "name = \"wheel\"", "name = \"\""),
               {},
               "name = \"\"",
               R"(^t\.toml:{line}: gear\[1\]\.name: '' is not a valid name)"});
  c.push_back({"GearNameWithDot",
               Replace(base, "name = \"wheel\"", "name = \"wh.eel\""),
               {},
               "name = \"wh.eel\"",
               R"(^t\.toml:{line}: gear\[1\]\.name: 'wh\.eel' is not a valid name)"});
  c.push_back(
      {"DuplicateGearName",
       Replace(base, "name = \"wheel\"", "name = \"pinion\""),
       {},
       "name = \"pinion\"\nteeth = 40",
       R"(^t\.toml:{line}: gear\[1\]\.name: duplicate gear name 'pinion' \(first defined at line 3\)$)"});
  // --- unknown keys and tables at every level ------------------------------------------------
  c.push_back({"UnknownTopLevelKey",
               Replace(base, "title = \"test pair\"", "titel = \"test pair\""),
               {},
               "titel",
               R"(^t\.toml:{line}: titel: unknown key \(did you mean 'title'\?\)$)"});
  c.push_back({"UnknownTopLevelTable",
               base + "\n[gears]\nteeth = 3\n",
               {},
               "[gears]",
               R"(^t\.toml:{line}: gears: unknown key \(did you mean 'gear'\?\)$)"});
  c.push_back({"UnknownGearKey",
               Replace(base, "teeth = 40", "teeth = 40\nteth = 40"),
               {},
               "teth = 40",
               R"(^t\.toml:{line}: gear\.wheel\.teth: unknown key \(did you mean 'teeth'\?\)$)"});
  c.push_back(
      {"UnknownKeyWithoutSuggestion",
       Replace(base, "teeth = 40", "teeth = 40\ncolour = 3"),
       {},
       "colour = 3",
       R"(^t\.toml:{line}: gear\.wheel\.colour: unknown key; allowed keys: name, teeth, )"});
  c.push_back(
      {"UnknownMeshKey",
       Replace(base, "gear = \"wheel\"", "gear = \"wheel\"\ncentre_distance = 0.06"),
       {},
       "centre_distance",
       R"(^t\.toml:{line}: mesh\.pinion-wheel\.centre_distance: unknown key \(did you mean 'center_distance'\?\)$)"});
  c.push_back(
      {"UnknownBearingKey",
       Replace(base, "body = \"pinion\"", "body = \"pinion\"\nstifness = 1"),
       {},
       "stifness",
       R"(^t\.toml:{line}: bearing\.b1\.stifness: unknown key \(did you mean 'stiffness'\?\)$)"});
  c.push_back({"UnknownLoadKey",
               Replace(base, "torque = 100.0", "torque = 100.0\ntorq = 1"),
               {},
               "torq = 1",
               R"(^t\.toml:{line}: load\.brake\.torq: unknown key \(did you mean 'torque'\?\)$)"});
  c.push_back(
      {"UnknownOperatingPointKey",
       Replace(base, "speed_rpm = 3000", "speed = 3000"),
       {},
       "speed = 3000",
       R"(^t\.toml:{line}: operating_point\.speed: unknown key \(did you mean 'speed_rpm'\?\)$)"});
  c.push_back(
      {"GearAsPlainTable",
       "title = \"x\"\n\n[gear]  # plain\nname = \"pinion\"\n",
       {},
       "[gear]  # plain",
       R"(^t\.toml:{line}: gear: must be an array of tables \(\[\[gear\]\]\), got a table$)"});
  c.push_back(
      {"NoGears",
       "title = \"x\"\n",
       {},
       "",
       R"(^t\.toml: gear: the scene has no gear \(at least one \[\[gear\]\] is required\)$)"});
  c.push_back({"TitleNotString",
               Replace(base, "title = \"test pair\"", "title = 3"),
               {},
               "title = 3",
               R"(^t\.toml:{line}: title: must be a string, got 3 \(an integer\)$)"});
  return c;
}

class SceneReaderGearInputTest : public ::testing::TestWithParam<BadCase> {};

TEST_P(SceneReaderGearInputTest, ReportsFileLineKeyAndReason) {
  test::ExpectSceneError(GetParam());
}

INSTANTIATE_TEST_SUITE_P(Cases, SceneReaderGearInputTest, ::testing::ValuesIn(GearCases()),
                         test::CaseName);

TEST(SceneReaderTest, GearCasesTableNamesAreUnique) {
  const std::vector<BadCase> cases = GearCases();
  EXPECT_GE(cases.size(), 30u);
  test::ExpectUniqueNames(cases);
}

}  // namespace
}  // namespace geardyn
