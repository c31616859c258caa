// Scene reader, [[bearing]], [[load]] and [operating_point] tables: each bad input is reported
// as FILE:LINE: KEY: REASON.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "scene_reader_cases.hpp"

namespace geardyn {
namespace {

using test::BadCase;
using test::kBase;
using test::Replace;

std::vector<BadCase> BearingLoadCases() {
  const std::string base(kBase);
  std::vector<BadCase> c;
  // --- bearings ------------------------------------------------------------------------------
  c.push_back(
      {"BearingFiveStiffnessEntries",
       Replace(base, "[1e9, 1e9, 1e9, 1e7, 1e7, 0]", "[1e9, 1e9, 1e9, 1e7, 1e7]"),
       {},
       "stiffness = ",
       R"(^t\.toml:{line}: bearing\.b1\.stiffness: must have 6 entries \(diagonal\) or 6 rows of 6 \(full matrix\), got 5 entries$)"});
  c.push_back(
      {"BearingNegativeDiagonal",
       Replace(base, "[1e9, 1e9, 1e9, 1e7, 1e7, 0]", "[1e9, -1e9, 1e9, 1e7, 1e7, 0]"),
       {},
       "stiffness = ",
       R"(^t\.toml:{line}: bearing\.b1\.stiffness: diagonal entry 1 \(y\) must be >= 0, got -1e\+09$)"});
  c.push_back(
      {"BearingAsymmetric",
       Replace(base, "stiffness = [1e9, 1e9, 1e9, 1e7, 1e7, 0]", R"(stiffness = [
  [1e9, 0, 0, 0, 1e6, 0],
  [0, 1e9, 0, 0, 0, 0],
  [0, 0, 1e9, 0, 0, 0],
  [0, 0, 0, 1e7, 0, 0],
  [2e6, 0, 0, 0, 1e7, 0],  # row 4
  [0, 0, 0, 0, 0, 0],
])"),
       {},
       "# row 4",
       R"(^t\.toml:{line}: bearing\.b1\.stiffness: not symmetric: \[0\]\[4\] \(x,ry\) = 1e\+06 but \[4\]\[0\] = 2e\+06$)"});
  c.push_back(
      {"BearingNotPsd",
       Replace(base, "stiffness = [1e9, 1e9, 1e9, 1e7, 1e7, 0]", R"(stiffness = [
  [1e9, 0, 0, 0, 1e9, 0],
  [0, 1e9, 0, 0, 0, 0],
  [0, 0, 1e9, 0, 0, 0],
  [0, 0, 0, 1e7, 0, 0],
  [1e9, 0, 0, 0, 1e7, 0],
  [0, 0, 0, 0, 0, 0],
])"),
       {},
       "stiffness = [\n",
       R"(^t\.toml:{line}: bearing\.b1\.stiffness: not positive semi-definite: the diagonally scaled matrix has eigenvalue -9)"});
  c.push_back(
      {"BearingShortRow",
       Replace(base, "stiffness = [1e9, 1e9, 1e9, 1e7, 1e7, 0]", R"(stiffness = [
  [1e9, 0, 0, 0, 0, 0],
  [0, 1e9, 0, 0, 0],  # short
  [0, 0, 1e9, 0, 0, 0],
  [0, 0, 0, 1e7, 0, 0],
  [0, 0, 0, 0, 1e7, 0],
  [0, 0, 0, 0, 0, 0],
])"),
       {},
       "# short",
       R"(^t\.toml:{line}: bearing\.b1\.stiffness: row 1 \(y\) must have 6 entries, got 5$)"});
  c.push_back(
      {"BearingDampingNan",
       Replace(base, "body = \"pinion\"", "body = \"pinion\"\ndamping = [1, 1, 1, 1, 1, nan]"),
       {},
       "damping",
       R"(^t\.toml:{line}: bearing\.b1\.damping: entry 5 \(rz\) must be finite, got nan$)"});
  c.push_back(
      {"BearingUnknownBody",
       Replace(base, "body = \"pinion\"", "body = \"pinon\""),
       {},
       "body = \"pinon\"",
       R"(^t\.toml:{line}: bearing\.b1\.body: no gear named 'pinon' \(did you mean 'pinion'\?\))"});
  c.push_back({"BearingOtherIsBody",
               Replace(base, "body = \"pinion\"", "body = \"pinion\"\nother = \"pinion\""),
               {},
               "other = ",
               R"(^t\.toml:{line}: bearing\.b1\.other: must differ from body)"});
  c.push_back({"BearingMissingStiffness",
               Replace(base, "stiffness = [1e9, 1e9, 1e9, 1e7, 1e7, 0]\n", ""),
               {},
               "[[bearing]]",
               R"(^t\.toml:{line}: bearing\.b1\.stiffness: missing)"});
  // --- loads and operating point -------------------------------------------------------------
  c.push_back({"LoadMissingTorque",
               Replace(base, "torque = 100.0\n", ""),
               {},
               "[[load]]",
               R"(^t\.toml:{line}: load\.brake\.torque: missing)"});
  c.push_back({"LoadTorqueInf",
               Replace(base, "torque = 100.0", "torque = -inf"),
               {},
               "torque = -inf",
               R"(^t\.toml:{line}: load\.brake\.torque: must be finite, got -inf$)"});
  c.push_back({"OperatingPointMissing",
               Replace(base, "[operating_point]\nspeed_rpm = 3000\ntorque = 50\n", ""),
               {},
               "",
               R"(^t\.toml: operating_point: missing \(required: an \[operating_point\] table)"});
  c.push_back({"OperatingPointMissingSpeed",
               Replace(base, "speed_rpm = 3000\n", ""),
               {},
               "[operating_point]",
               R"(^t\.toml:{line}: operating_point\.speed_rpm: missing)"});
  c.push_back({"OperatingPointNegativeSpeed",
               Replace(base, "speed_rpm = 3000", "speed_rpm = -100"),
               {},
               "speed_rpm = -100",
               R"(^t\.toml:{line}: operating_point\.speed_rpm: must be >= 0, got -100$)"});
  c.push_back({"OperatingPointUnknownBody",
               Replace(base, "speed_rpm = 3000", "speed_rpm = 3000\nbody = \"motor\""),
               {},
               "body = \"motor\"",
               R"(^t\.toml:{line}: operating_point\.body: no gear named 'motor')"});
  return c;
}

class SceneReaderBearingLoadInputTest : public ::testing::TestWithParam<BadCase> {};

TEST_P(SceneReaderBearingLoadInputTest, ReportsFileLineKeyAndReason) {
  test::ExpectSceneError(GetParam());
}

INSTANTIATE_TEST_SUITE_P(Cases, SceneReaderBearingLoadInputTest,
                         ::testing::ValuesIn(BearingLoadCases()), test::CaseName);

TEST(SceneReaderTest, BearingLoadCasesTableNamesAreUnique) {
  const std::vector<BadCase> cases = BearingLoadCases();
  EXPECT_GE(cases.size(), 15u);
  test::ExpectUniqueNames(cases);
}

}  // namespace
}  // namespace geardyn
