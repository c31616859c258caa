// [[planetary]] scene tables: expansion into gears, meshes and planet bearings, Willis speeds,
// mesh frequency, the sun–ring phase of standard gears, and table-driven bad input
// (`FILE:LINE: KEY: REASON`, docs/scene-format.md).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <regex>
#include <set>
#include <string>
#include <vector>

#include "geardyn/models/scene/planetary.hpp"
#include "geardyn/models/scene/scene_reader.hpp"
#include "models/system/planetary_scene.hpp"

namespace geardyn {
namespace {

using testing::PlanetaryFixture;
using testing::PlanetarySceneText;

constexpr double kPi = std::numbers::pi;
constexpr double kTol = 1e-12;  // closed forms of exact tooth counts and angles

std::string Replace(std::string text, const std::string& from, const std::string& to) {
  const std::size_t pos = text.find(from);
  EXPECT_NE(pos, std::string::npos) << "test setup: '" << from << "' not found";
  if (pos != std::string::npos) text.replace(pos, from.size(), to);
  return text;
}

int LineOf(const std::string& text, const std::string& needle) {
  if (needle.empty()) return 0;
  const std::size_t pos = text.find(needle);
  EXPECT_NE(pos, std::string::npos) << "test setup: line '" << needle << "' not found";
  return 1 +
         static_cast<int>(std::count(text.begin(), text.begin() + static_cast<long>(pos), '\n'));
}

TEST(PlanetaryReaderTest, ExpandsPlanetsMeshesAndBearings) {
  PlanetaryFixture f;
  f.planets = 4;
  const Scene s = ParseScene(PlanetarySceneText(f), "t.toml");
  ASSERT_EQ(s.planetaries.size(), 1u);
  const PlanetaryDef& p = s.planetaries[0];
  EXPECT_EQ(p.planets, (std::vector<std::string>{"planet_1", "planet_2", "planet_3", "planet_4"}));
  EXPECT_EQ(p.sun_meshes[2], "sun-planet_3");
  EXPECT_EQ(p.ring_meshes[2], "planet-ring_3");
  EXPECT_EQ(p.planet_bearings[0], "planet_1-carrier");
  EXPECT_TRUE(p.equally_spaced);
  // Gears: sun, ring, 4 planets, carrier (the template planet is gone); 8 meshes; 3 + 4 bearings.
  EXPECT_EQ(s.gears.size(), 7u);
  EXPECT_THROW((void)s.gear("planet"), InvalidInput);
  EXPECT_EQ(s.gear("carrier").blank.teeth, 0);
  EXPECT_EQ(s.meshes.size(), 8u);
  EXPECT_EQ(s.bearings.size(), 7u);
  // a_w = m (z_s + z_p)/2 = 0.002 · 60 / 2 (standard gears).
  EXPECT_NEAR(p.center_distance, 0.060, kTol);
  for (int n = 0; n < 4; ++n) EXPECT_NEAR(p.planet_angles[n], n * kPi / 2.0, kTol);
  // Planet bearing n: the local (radial, tangential) stiffness rotated by ψ_n = 90°: the radial
  // 2e8 and tangential 2e8 are equal, so only the axial/tilt layout is checked here; planet 2
  // (ψ = 90°) of an anisotropic bearing below.
  const BearingDef& b1 = s.bearings[3 + 1];
  EXPECT_EQ(b1.body, "planet_2");
  EXPECT_EQ(b1.other, "carrier");
  EXPECT_NEAR(b1.stiffness(0, 0), 2e8, 1e-6);
  EXPECT_NEAR(b1.stiffness(5, 5), 0.0, 1e-9);
}

TEST(PlanetaryReaderTest, PlanetBearingIsGivenInThePlanetFrame) {
  PlanetaryFixture f;
  f.planets = 4;
  const std::string text = Replace(PlanetarySceneText(f), "[2e8, 2e8, 1e8, 1e6, 1e6, 0]",
                                   "[3e8, 1e8, 1e8, 2e6, 1e6, 0]");
  const Scene s = ParseScene(text, "t.toml");
  // Planet 2 at ψ = 90°: its radial direction is +y, tangential −x.
  const BearingDef& b = s.bearings[3 + 1];
  EXPECT_NEAR(b.stiffness(0, 0), 1e8, 1e-4);
  EXPECT_NEAR(b.stiffness(1, 1), 3e8, 1e-4);
  EXPECT_NEAR(b.stiffness(0, 1), 0.0, 1e-4);
  EXPECT_NEAR(b.stiffness(3, 3), 1e6, 1e-6);
  EXPECT_NEAR(b.stiffness(4, 4), 2e6, 1e-6);
}

TEST(PlanetaryReaderTest, SpeedsFollowWillis) {
  // Ring fixed, sun input: Ω_c = Ω_s z_s/(z_s + z_r), Ω_p − Ω_c = −(z_s/z_p)(Ω_s − Ω_c).
  PlanetaryFixture f;
  const Scene s = ParseScene(PlanetarySceneText(f), "t.toml");
  const double ws = 1500.0 * 2.0 * kPi / 60.0;
  const double wc = ws * 40.0 / 120.0;
  EXPECT_NEAR(s.GearSpeed("sun"), ws, kTol * ws);
  EXPECT_NEAR(s.GearSpeed("carrier"), wc, kTol * ws);
  EXPECT_NEAR(s.GearSpeed("ring"), 0.0, kTol * ws);
  EXPECT_NEAR(s.GearSpeed("planet_2"), wc - 2.0 * (ws - wc), kTol * ws);
  // Every planetary mesh: f_m = |Ω_s − Ω_c| z_s / 2π = z_s z_r Ω_s / ((z_s + z_r) 2π).
  const double fm = 40.0 * 80.0 / 120.0 * ws / (2.0 * kPi);
  for (const MeshDef& m : s.meshes) EXPECT_NEAR(s.MeshFrequencyHz(m), fm, kTol * fm) << m.name;

  // Carrier fixed (star): Ω_r = −Ω_s z_s/z_r.
  f.fixed = "carrier";
  const Scene star = ParseScene(PlanetarySceneText(f), "t.toml");
  EXPECT_NEAR(star.GearSpeed("ring"), -ws * 40.0 / 80.0, kTol * ws);
  EXPECT_NEAR(star.GearSpeed("carrier"), 0.0, kTol * ws);
}

TEST(PlanetaryReaderTest, SunRingPhaseOfStandardGearsFollowsPlanetParity) {
  // x = 0 and α_w = α_t: Δ = π (z_p − 1) mod 2π — a tooth faces a tooth across an even planet.
  PlanetaryFixture f;
  const Scene even = ParseScene(PlanetarySceneText(f), "t.toml");  // z_p = 20
  EXPECT_NEAR(even.planetaries[0].sun_ring_phase, kPi, 1e-9);
  const std::string odd_text =
      Replace(Replace(Replace(PlanetarySceneText(f), "teeth = 20", "teeth = 21"), "teeth = 80",
                      "teeth = 82"),
              "teeth = 40", "teeth = 40");  // 40 + 2·21 = 82; (40 + 82)/3 is not an integer → N = 2
  const Scene odd = ParseScene(Replace(odd_text, "planets = 3", "planets = 2"), "t.toml");
  EXPECT_NEAR(odd.planetaries[0].sun_ring_phase, 0.0, 1e-9);
}

TEST(PlanetaryReaderTest, PlanarKeyAndOverrides) {
  PlanetaryFixture f;
  const Scene s =
      ParseScene(PlanetarySceneText(f), "t.toml", {"planar=true", "planetary.stage.planets=4"});
  EXPECT_TRUE(s.planar);
  EXPECT_EQ(s.planetaries[0].planets.size(), 4u);
}

TEST(PlanetaryReaderTest, BuiltinPlanetaryScenesLoad) {
  const Scene lp = LoadScene("builtin:planetary-lin-parker");
  EXPECT_EQ(lp.planetaries.at(0).planets.size(), 4u);
  // Σ T Ω = 0 for the stated torques (T_c = −(1 + z_r/z_s) T_s).
  const double power = lp.operating_point.torque * lp.GearSpeed("sun") +
                       lp.loads.at(0).torque * lp.GearSpeed(lp.loads.at(0).body);
  EXPECT_NEAR(power, 0.0, 1e-9 * 500.0 * lp.operating_point.speed);
  const Scene wt = LoadScene("builtin:planetary-wind-turbine");
  EXPECT_EQ(wt.planetaries.at(0).planets.size(), 3u);
  const double wt_power = wt.operating_point.torque * wt.GearSpeed("carrier") +
                          wt.loads.at(0).torque * wt.GearSpeed("sun");
  EXPECT_NEAR(wt_power, 0.0, 1e-3 * wt.operating_point.torque * wt.operating_point.speed);
}

// --- bad input -----------------------------------------------------------------------------------

struct BadCase {
  std::string name;
  std::string text;
  std::vector<std::string> overrides;
  std::string line_of;  // the expected line contains this ("" = no line)
  std::string regex;    // "{line}" stands for that line
};

std::ostream& operator<<(std::ostream& os, const BadCase& c) { return os << c.name; }

std::vector<BadCase> BadCases() {
  PlanetaryFixture f;
  const std::string base = PlanetarySceneText(f);
  const std::string stage = "[[planetary]]  # stage";
  std::vector<BadCase> c;
  c.push_back({"RingNotInternal",
               Replace(base, "internal = true\n", ""),
               {},
               "ring = \"ring\"\n",
               R"(^t\.toml:{line}: planetary\.stage\.ring: 'ring' must be an internal gear)"});
  c.push_back({"RingIsTheSun",
               Replace(base, "ring = \"ring\"\n", "ring = \"sun\"\n"),
               {},
               "ring = \"sun\"",
               R"(^t\.toml:{line}: planetary\.stage\.ring: 'sun' must be an internal gear)"});
  c.push_back({"AssemblyConditionEqualSpacing",
               Replace(base, "planets = 3", "planets = 7"),
               {},
               "planets = 7",
               R"(^t\.toml:{line}: planetary\.stage\.planets: 7 equally spaced planets cannot be )"
               R"(assembled: \(z_s \+ z_r\)/N = \(40 \+ 80\)/7 = 17\.14)"});
  c.push_back({"AssemblyConditionAngles",
               Replace(base, "planets = 3", "planet_angles_deg = [0, 100, 240]"),
               {},
               "planet_angles_deg",
               R"(^t\.toml:{line}: planetary\.stage\.planet_angles_deg: planet 1 at 100 deg )"
               R"(cannot be assembled: .* = 33\.3+\d* is not an integer \(nearest )"
               R"(assemblable angle: 99 deg\)$)"});
  c.push_back({"AnglesCountMismatch",
               Replace(base, "planets = 3", "planets = 3\nplanet_angles_deg = [0, 120]"),
               {},
               "planet_angles_deg",
               R"(^t\.toml:{line}: planetary\.stage\.planet_angles_deg: has 2 entries but )"
               R"(planets = 3$)"});
  c.push_back({"NoPlanetCount",
               Replace(base, "planets = 3\n", ""),
               {},
               stage,
               R"(^t\.toml:{line}: planetary\.stage\.planets: missing)"});
  c.push_back({"PlanetsOverlap",
               Replace(base, "planets = 3", "planets = 10"),
               {},
               "planets = 10",
               R"(^t\.toml:{line}: planetary\.stage\.planets: neighbouring planets overlap)"});
  c.push_back({"CentreDistancesDiffer",
               Replace(base, "teeth = 80", "teeth = 81\nprofile_shift = 0.0"),
               {"planetary.stage.planets=1"},
               stage,
               R"(^t\.toml:{line}: planetary\.stage: the sun-planet centre distance 0\.06 m .* )"
               R"(standard gears need z_r = z_s \+ 2 z_p \(here 81 vs 80\))"});
  c.push_back(
      {"NoSunMesh",
       Replace(base,
               "[[mesh]]  # sun-planet\npinion = \"sun\"\ngear = \"planet\"\nmodel = \"lti\"\n",
               ""),
       {},
       stage,
       R"(^t\.toml:{line}: planetary\.stage: no \[\[mesh\]\] between the sun 'sun' and )"
       R"(the planet 'planet')"});
  c.push_back(
      {"SunNotPinion",
       Replace(base, "pinion = \"sun\"\ngear = \"planet\"", "pinion = \"planet\"\ngear = \"sun\""),
       {},
       stage,
       R"(^t\.toml:{line}: planetary\.stage: mesh 'planet-sun': the sun 'sun' )"
       R"(must be its pinion)"});
  c.push_back(
      {"BearingRz",
       Replace(base, "[2e8, 2e8, 1e8, 1e6, 1e6, 0]", "[2e8, 2e8, 1e8, 1e6, 1e6, 5]"),
       {},
       "planet_bearing_stiffness",
       R"(^t\.toml:{line}: planetary\.stage\.planet_bearing_stiffness: the rz entry must be )"
       R"(0 \(a planet turns freely on its bearing\), got 5$)"});
  c.push_back({"NoCarrier",
               Replace(base,
                       "carrier = { name = \"carrier\", mass = 3.0, inertia = 0.02, "
                       "transverse_inertia = 0.012 }\n",
                       ""),
               {},
               stage,
               R"(^t\.toml:{line}: planetary\.stage\.carrier: missing)"});
  c.push_back({"CarrierNegativeMass",
               base,
               {"planetary.stage.carrier.mass=-3"},
               "",
               R"(planetary\.stage\.carrier\.mass: must be > 0)"});
  c.push_back({"UnknownKey",
               Replace(base, "planets = 3", "planets = 3\nplanet_count = 3"),
               {},
               "planet_count",
               R"(^t\.toml:{line}: planetary\.stage\.planet_count: unknown key)"});
  c.push_back(
      {"BadFixed",
       Replace(base, "fixed = \"ring\"", "fixed = \"rign\""),
       {},
       "fixed = \"rign\"",
       R"(^t\.toml:{line}: planetary\.stage\.fixed: must be "ring", "carrier" or "sun", got )"
       R"("rign" \(did you mean 'ring'\?\)$)"});
  c.push_back(
      {"ReferenceIsFixed",
       Replace(base, "fixed = \"ring\"", "fixed = \"sun\""),
       {},
       "fixed = \"sun\"",
       R"(^t\.toml:{line}: planetary\.stage\.fixed: 'sun' is held fixed \(zero speed\) but )"
       R"(it is the operating point's body)"});
  c.push_back({"PlanetMeshesElsewhere",
               Replace(base, stage,
                       "[[gear]]  # idler\nname = \"idler\"\nteeth = 20\nnormal_module = 0.002\n"
                       "face_width = 0.02\nmass = 0.3\ninertia = 6e-5\n\n[[mesh]]  # idler\n"
                       "pinion = \"planet\"\ngear = \"idler\"\n\n" +
                           stage),
               {},
               stage,
               R"(^t\.toml:{line}: planetary\.stage: mesh 'planet-idler' meshes the planet )"
               R"(template 'planet' with another gear)"});
  return c;
}

class PlanetaryBadInputTest : public ::testing::TestWithParam<BadCase> {};

TEST_P(PlanetaryBadInputTest, ReportsFileLineKeyAndReason) {
  const BadCase& c = GetParam();
  const int line = LineOf(c.text, c.line_of);
  const std::string regex =
      std::regex_replace(c.regex, std::regex(R"(\{line\})"), std::to_string(line));
  try {
    (void)ParseScene(c.text, "t.toml", c.overrides);
    ADD_FAILURE() << "no SceneError; expected " << regex;
  } catch (const SceneError& e) {
    EXPECT_THAT(std::string(e.what()), ::testing::ContainsRegex(regex));
  }
}

INSTANTIATE_TEST_SUITE_P(Cases, PlanetaryBadInputTest, ::testing::ValuesIn(BadCases()),
                         [](const ::testing::TestParamInfo<BadCase>& param_info) {
                           return param_info.param.name;
                         });

}  // namespace
}  // namespace geardyn
