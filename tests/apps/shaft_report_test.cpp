// Shafts in `geardyn info` and `geardyn modes`: the shaft list (mass against ρ π D²/4 L, nodes
// and DOFs against the model) and the per-shaft strain energy of each mode against the sum of
// the library's per-element fractions.
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <string>

#include "geardyn/analyses/modal.hpp"
#include "geardyn/models/scene/scene_reader.hpp"
#include "geardyn/models/system/scene_system.hpp"
#include "support/cli_run.hpp"

namespace geardyn::app {
namespace {

using test::RunJson;

// The JSON prints 17 significant digits; sums of ≤ 16 fractions.
constexpr double kTol = 1e-12;

TEST(ShaftReportTest, InfoListsTheShaftsWithMassNodesAndStations) {
  const nlohmann::json report = RunJson({"info", "builtin:geared-shafts"});
  ASSERT_EQ(report["shafts"].size(), 2u);
  const nlohmann::json& input = report["shafts"][0];
  EXPECT_EQ(input["name"], "input");
  // Solid Ø 60 mm steel cylinder of 0.5 m.
  EXPECT_NEAR(input["mass"].get<double>(), 7850.0 * M_PI / 4.0 * 0.06 * 0.06 * 0.5, 1e-12);
  EXPECT_EQ(input["nodes"], 9);
  EXPECT_EQ(input["elements"], 8);
  // DOFs: 2 shafts × 9 nodes × 6 = the model's 108 (the gears are nodes).
  EXPECT_EQ(2 * input["dofs"].get<int>(),
            MakeSystemModel(LoadScene("builtin:geared-shafts")).num_dofs());
  EXPECT_EQ(input["gears"][0]["gear"], "pinion");
  EXPECT_DOUBLE_EQ(input["gears"][0]["station"].get<double>(), 0.25);
  EXPECT_EQ(input["bearings"].size(), 2u);
  EXPECT_EQ(report["damping"]["kind"], "modal");
  EXPECT_DOUBLE_EQ(report["damping"]["modal_ratio"].get<double>(), 0.02);
}

TEST(ShaftReportTest, ModesGroupTheStrainEnergyPerShaft) {
  const nlohmann::json report =
      RunJson({"modes", "builtin:geared-shafts", "--modes", "12", "--method", "dense"});
  ModalOptions options;
  options.method = ModalMethod::kDense;
  options.num_modes = 12;
  const ModalResult direct =
      ComputeModes(MakeSystemModel(LoadScene("builtin:geared-shafts")), options);
  ASSERT_EQ(report["modes"].size(), 12u);
  for (int k = 1; k < 12; ++k) {  // mode 0 is the free rotation (no strain energy)
    const nlohmann::json& strain = report["modes"][static_cast<std::size_t>(k)]["strain"];
    double input = 0.0, total = 0.0;
    for (std::size_t c = 0; c < direct.strain_names.size(); ++c) {
      if (direct.strain_names[c].rfind("element:input.e", 0) == 0) {
        input += direct.strain_fractions(k, static_cast<Eigen::Index>(c));
      }
    }
    for (auto it = strain.begin(); it != strain.end(); ++it) {
      EXPECT_EQ(it.key().rfind("element:input.e", 0), std::string::npos) << it.key();
      total += it.value().get<double>();
    }
    EXPECT_NEAR(strain["shaft:input"].get<double>(), input, kTol) << "mode " << k;
    EXPECT_NEAR(total, 1.0, kTol) << "mode " << k;
  }
}

}  // namespace
}  // namespace geardyn::app
