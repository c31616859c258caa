// Reading [oscillator] scenes: the values, the defaults, `--set` overrides of the level, the
// built-in scenes, and the FILE:LINE: KEY: REASON errors of bad input.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include "geardyn/models/scene/scene_reader.hpp"

namespace geardyn {
namespace {

constexpr const char* kText = R"(title = "osc"
[oscillator]
zeta = 0.04
alpha = 0.3
mean_force = 0.2
alternating_force = 0.05
force_phase_deg = 90.0
back_contact = false
frequency_ratio = 1.7
)";

TEST(OscillatorReaderTest, ReadsEveryKey) {
  const Scene s = ParseScene(kText, "osc.toml");
  ASSERT_TRUE(s.oscillator.has_value());
  const OscillatorDef& o = *s.oscillator;
  EXPECT_EQ(o.zeta, 0.04);
  EXPECT_EQ(o.alpha, 0.3);
  EXPECT_EQ(o.mean_force, 0.2);
  EXPECT_EQ(o.alternating_force, 0.05);
  EXPECT_NEAR(o.force_phase, std::numbers::pi / 2.0, 1e-15);
  EXPECT_TRUE(o.backlash);
  EXPECT_FALSE(o.back_contact);
  EXPECT_EQ(o.model, OscillatorModel::kSlices);
  EXPECT_EQ(o.line, 2);
  EXPECT_EQ(s.NominalMeshFrequencyHz(), 1.7);
  EXPECT_TRUE(s.gears.empty());
  EXPECT_TRUE(s.meshes.empty());
}

TEST(OscillatorReaderTest, LevelDefaultsAndOverrides) {
  EXPECT_EQ(ParseScene("[oscillator]\nbacklash = false\n", "a.toml").oscillator->model,
            OscillatorModel::kTorsional);
  EXPECT_EQ(ParseScene(kText, "a.toml", {"oscillator.model=lti"}).oscillator->model,
            OscillatorModel::kLti);
  EXPECT_EQ(ParseScene(kText, "a.toml", {"oscillator.model=torsional"}).oscillator->model,
            OscillatorModel::kTorsional);
}

TEST(OscillatorReaderTest, BuiltinScenesLoad) {
  const Scene ks = LoadScene("builtin:kahraman-singh-oscillator");
  ASSERT_TRUE(ks.oscillator.has_value());
  EXPECT_EQ(ks.oscillator->alpha, 0.0);
  const Scene bk = LoadScene("builtin:blankenship-kahraman-oscillator");
  ASSERT_TRUE(bk.oscillator.has_value());
  EXPECT_NE(bk.oscillator->alpha, 0.0);
}

// The error of `text` (with `overrides`): its line, key and a piece of its reason.
void ExpectError(const std::string& text, int line, const std::string& key,
                 const std::string& reason_part, const std::vector<std::string>& overrides = {}) {
  try {
    (void)ParseScene(text, "bad.toml", overrides);
    FAIL() << "no error for " << text;
  } catch (const SceneError& e) {
    EXPECT_EQ(e.source(), "bad.toml");
    EXPECT_EQ(e.line(), line) << e.what();
    EXPECT_EQ(e.key(), key) << e.what();
    EXPECT_NE(e.reason().find(reason_part), std::string::npos) << e.what();
  }
}

TEST(OscillatorReaderTest, BadInputNamesFileLineKeyAndReason) {
  ExpectError("[oscillator]\nzeta = -0.1\n", 2, "oscillator.zeta", ">= 0");
  ExpectError("[oscillator]\nalpha = 1.0\n", 2, "oscillator.alpha", "|alpha| < 1");
  ExpectError("[oscillator]\nalpha = -1.5\n", 2, "oscillator.alpha", "|alpha| < 1");
  ExpectError("[oscillator]\nmean_force = inf\n", 2, "oscillator.mean_force", "finite");
  ExpectError("[oscillator]\nzetta = 0.1\n", 2, "oscillator.zetta", "zeta");
  ExpectError("[oscillator]\nfrequency_ratio = 0\n", 2, "oscillator.frequency_ratio", "> 0");
  ExpectError("[oscillator]\nbacklash = false\nmodel = \"slices\"\n", 3, "oscillator.model",
              "backlash = false");
  ExpectError("[oscillator]\nmodel = \"slice\"\n", 2, "oscillator.model", "did you mean");
  ExpectError("planar = true\n[oscillator]\n", 1, "planar", "oscillator scene");
  ExpectError("[oscillator]\n", 0, "oscillator.alpha", "|alpha| < 1", {"oscillator.alpha=2"});
}

}  // namespace
}  // namespace geardyn
