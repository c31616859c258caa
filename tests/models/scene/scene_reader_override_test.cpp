// Scene reader, TOML syntax and --set overrides: bad input reported as FILE:LINE: KEY: REASON
// (or FILE: --set K=V: ...), and what valid overrides change.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "scene_reader_cases.hpp"
#include "support/expect_throws.hpp"

namespace geardyn {
namespace {

using test::BadCase;
using test::Helical;
using test::kBase;
using test::kSource;
using test::Replace;

std::vector<BadCase> OverrideCases() {
  const std::string base(kBase);
  std::vector<BadCase> c;
  // --- TOML syntax ---------------------------------------------------------------------------
  c.push_back({"TomlSyntaxError",
               Replace(base, "teeth = 40", "teeth = = 40"),
               {},
               "teeth = = 40",
               R"(^t\.toml:{line}: TOML syntax error: )"});
  c.push_back({"TomlDuplicateKey",
               Replace(base, "teeth = 40", "teeth = 40\nteeth = 41"),
               {},
               "teeth = 41",
               R"(^t\.toml:{line}: TOML syntax error: )"});
  // --- overrides -----------------------------------------------------------------------------
  c.push_back(
      {"OverrideWithoutEquals",
       base,
       {"gear.pinion.teeth"},
       "",
       R"(^t\.toml: --set gear\.pinion\.teeth: malformed override: expected PATH=VALUE \(no '='\)$)"});
  c.push_back({"OverrideEmptyPath",
               base,
               {" = 3"},
               "",
               R"(^t\.toml: --set  = 3: malformed override: empty path)"});
  c.push_back(
      {"OverrideEmptySegment",
       base,
       {"gear..teeth=3"},
       "",
       R"(^t\.toml: --set gear\.\.teeth=3: gear\.\.teeth: malformed override: empty path segment)"});
  c.push_back(
      {"OverrideUnknownElement",
       base,
       {"gear.pinon.teeth=23"},
       "",
       R"(^t\.toml: --set gear\.pinon\.teeth=23: gear\.pinon: no element of 'gear' is named 'pinon' \(did you mean 'pinion'\?\))"});
  c.push_back(
      {"OverrideIndexOutOfRange",
       base,
       {"gear.5.teeth=23"},
       "",
       R"(^t\.toml: --set gear\.5\.teeth=23: gear\.5: no element 5 \('gear' has 2 elements)"});
  c.push_back(
      {"OverrideThroughNonTable",
       base,
       {"title.x=1"},
       "",
       R"(^t\.toml: --set title\.x=1: title\.x: cannot descend into 'title': it is string "test pair", not a table$)"});
  c.push_back(
      {"OverrideThroughValueDeeper",
       base,
       {"gear.pinion.teeth.x.y=1"},
       "",
       R"(^t\.toml: --set gear\.pinion\.teeth\.x\.y=1: gear\.pinion\.teeth\.x: cannot descend into 'gear\.pinion\.teeth': it is 20 \(an integer\), not a table$)"});
  c.push_back(
      {"OverrideBadValue",
       base,
       {"gear.pinion.teeth=0"},
       "",
       R"(^t\.toml: --set gear\.pinion\.teeth=0: gear\.pinion\.teeth: must be a positive integer, got 0$)"});
  c.push_back({"OverrideAddsUnknownKey",
               base,
               {"gear.pinion.colour=red"},
               "",
               R"(^t\.toml: --set gear\.pinion\.colour=red: gear\.pinion\.colour: unknown key)"});
  c.push_back(
      {"OverrideBareStringWhereNumber",
       base,
       {"operating_point.torque=lots"},
       "",
       R"(^t\.toml: --set operating_point\.torque=lots: operating_point\.torque: must be a number, got string "lots"$)"});
  c.push_back({"OverrideLaterOneReported",
               base,
               {"gear.0.teeth=21", "gear.1.mass=-1"},
               "",
               R"(^t\.toml: --set gear\.1\.mass=-1: gear\.wheel\.mass: must be > 0, got -1$)"});
  return c;
}

class SceneReaderOverrideInputTest : public ::testing::TestWithParam<BadCase> {};

TEST_P(SceneReaderOverrideInputTest, ReportsFileLineKeyAndReason) {
  test::ExpectSceneError(GetParam());
}

INSTANTIATE_TEST_SUITE_P(Cases, SceneReaderOverrideInputTest, ::testing::ValuesIn(OverrideCases()),
                         test::CaseName);

TEST(SceneReaderTest, OverrideCasesTableNamesAreUnique) {
  const std::vector<BadCase> cases = OverrideCases();
  EXPECT_GE(cases.size(), 8u);
  test::ExpectUniqueNames(cases);
}

// --- Overrides ----------------------------------------------------------------------------------

TEST(OverrideTest, ChangesValuesByNameAndIndex) {
  const Scene s =
      ParseScene(kBase, kSource,
                 {"gear.pinion.teeth=23", "gear.1.mass=3.5", "operating_point.torque=200",
                  "title=\"x\"", "load.brake.torque = -7"});
  EXPECT_EQ(s.gear("pinion").blank.teeth, 23);
  EXPECT_EQ(s.meshes[0].geometry.pinion.teeth, 23);
  EXPECT_EQ(s.gear("wheel").mass, 3.5);
  EXPECT_EQ(s.operating_point.torque, 200.0);
  EXPECT_EQ(s.title, "x");
  EXPECT_EQ(s.loads[0].torque, -7.0);
}

TEST(OverrideTest, BareWordsAreStringsAndTomlValuesKeepTheirType) {
  const Scene s = ParseScene(Helical(), kSource, {"gear.0.hand=left", "gear.wheel.hand=right"});
  EXPECT_EQ(s.gear("pinion").hand, HelixHand::kLeft);
  EXPECT_EQ(s.gear("wheel").hand, HelixHand::kRight);
  EXPECT_THROWS_MESSAGE(ParseScene(kBase, kSource, {"gear.pinion.teeth=23.0"}), SceneError,
                        R"(got 23 \(a float\)$)");
  EXPECT_THROWS_MESSAGE(ParseScene(kBase, kSource, {"gear.pinion.teeth=\"23\""}), SceneError,
                        R"(got string "23"$)");
}

TEST(OverrideTest, AddsKeysAndTables) {
  const Scene s = ParseScene(kBase, kSource,
                             {"gear.wheel.transverse_inertia=1e-3", "operating_point.body=wheel"});
  EXPECT_EQ(s.gear("wheel").transverse_inertia, 1e-3);
  EXPECT_EQ(s.operating_point.body, "wheel");
  // A whole missing table is created on the way.
  const std::string no_op =
      Replace(kBase, "[operating_point]\nspeed_rpm = 3000\ntorque = 50\n", "");
  const Scene t =
      ParseScene(no_op, kSource, {"operating_point.speed_rpm=1000", "operating_point.torque=5"});
  EXPECT_NEAR(t.operating_point.speed, 1000.0 * 2.0 * std::acos(-1.0) / 60.0, 1e-12);
  EXPECT_THROWS_MESSAGE(ParseScene(no_op, kSource, {"operating_point.torque=5"}), SceneError,
                        R"(^t\.toml: --set operating_point\.torque=5: operating_point\.speed_rpm: )"
                        R"(missing)");
}

TEST(OverrideTest, ArrayElementsAndLaterOverridesWin) {
  const Scene s = ParseScene(
      kBase, kSource,
      {"bearing.b1.stiffness.5=3e4", "operating_point.torque=1", "operating_point.torque=2"});
  EXPECT_EQ(s.bearings[0].stiffness(5, 5), 3e4);
  EXPECT_EQ(s.bearings[0].stiffness(0, 0), 1e9);
  EXPECT_EQ(s.operating_point.torque, 2.0);
}

TEST(OverrideTest, OverrideErrorsWinOverLaterFileErrors) {
  // The override's value is wrong; the file is fine: the error names the override, not a line.
  EXPECT_THROWS_MESSAGE(
      ParseScene(kBase, kSource, {"gear.wheel.normal_module=inf"}), SceneError,
      R"(^t\.toml: --set gear\.wheel\.normal_module=inf: gear\.wheel\.normal_module: )"
      R"(must be finite, got inf$)");
}

TEST(OverrideTest, ReplacesAWholeElement) {
  const Scene s =
      ParseScene(kBase, kSource, {R"(load.0={name="drag", body="pinion", torque=3.0})"});
  ASSERT_EQ(s.loads.size(), 1u);
  EXPECT_EQ(s.loads[0].name, "drag");
  EXPECT_EQ(s.loads[0].body, "pinion");
}

}  // namespace
}  // namespace geardyn
