// Dynamic cross-check 1 of the tooth-contact model (issue 14): a full-contact case of the rig
// (rigid teeth, linear law k = 4e8 N/m, 300 N·m) integrated to steady state against the linear
// HB of the LTV mesh built from the contact model's own quasi-static mode (`simulate
// --quasi-static` → [mesh.parameters] table, 2048 samples, read back through the scene reader).
// Damping match: no mesh damping in either model (the contact law's damper acts per contact, so
// its total follows the number of pairs, which an LTV damper cannot); instead the same bearing
// dampers in both scenes (ζ ≈ 0.05 of the mesh mode through the rz entries, the translations
// and tilts damped alike), and a soft torsional support of the wheel (1e4 N·m/rad, 180 Hz) so
// that the rigid-body rotation settles (without it the contact model's state drifts slowly and
// is never steady, though its DTE is).
//
// KNOWN FAILURE (disabled; docs/design.md, "Contact simulator: cross-checks"): measured RMS DTE
// [µm], contact model vs LTV HB: 1500 Hz 3.541 vs 3.439 (+3 %), 2500 Hz 1.663 vs 2.584 (−36 %),
// 3500 Hz 1.555 vs 1.787 (−13 %), 4500 Hz 4.184 vs 4.220 (−1 %), 5500 Hz 0.888 vs 2.191, 6500 Hz
// 0.312 vs 1.434, 7500 Hz 0.147 vs 1.224. The LTV side is confirmed by its own time integration
// (simulate of the table scene: 3.446, 2.556, 1.779, 4.221, 2.140, 1.380, 1.171) and the contact
// side does not move with a 1000× finer tolerance, so the two MODELS differ: the contact
// model's entering tooth touches with its sharp tip corner before A over a window that grows
// with the instantaneous approach (0.62 mm of roll at the static 100 N·m approach, confirmed by
// independent geometry in TipCornerWindowsEqualTheCornerGeometry), i.e. a stiffness that
// depends on the state, which the quasi-static LTV freezes at the static approach. The energy
// balance of these runs (1.4e-4 and 2.3e-4 at 6500 and 7500 Hz before) was an uncontrolled
// quadrature error at the involute → tip-corner hand-overs, fixed by the rk8pd error control of
// ∫P and ∫D (docs/design.md, "Time integration"): 1.1e-5 at 6500 Hz, rtol 1e-8, 24 periods
// (docs/benchmarks.md, "Energy balance of contact runs"); its assertion below stays.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "geardyn/cli.hpp"
#include "support/cli_run.hpp"

namespace geardyn::app {
namespace {

using test::RunJson;

const std::string kRig = "builtin:kahraman-blankenship-rig";

std::vector<std::string> With(std::vector<std::string> args, const std::vector<std::string>& sets) {
  for (const std::string& s : sets) {
    args.push_back("--set");
    args.push_back(s);
  }
  return args;
}

const std::vector<std::string> kCommon = {
    "bearing.pinion-support.damping=[16600,16600,5260,63,63,24]",
    "bearing.wheel-support.damping=[16600,16600,5260,63,63,24]",
    "bearing.wheel-support.stiffness=[1e10,1e10,1e9,1e8,1e8,1e4]", "operating_point.torque=300",
    "load.brake.torque=300"};

TEST(ContactDynamicCrossCheck, DISABLED_FullContactSweepEqualsLinearHbOfTheQuasiStaticLtv) {
  std::vector<std::string> contact = kCommon;
  contact.push_back("mesh.pinion-wheel.model=\"contact\"");
  contact.push_back("mesh.pinion-wheel.contact={law=\"linear\",stiffness=4e8}");
  const std::filesystem::path dir =
      std::filesystem::path(GEARDYN_BINARY_DIR) / "test_output" / "contact_dynamic_xcheck";
  std::filesystem::remove_all(dir);
  const nlohmann::json qs = RunJson(With(
      {"simulate", kRig, "--quasi-static", "--samples-per-period", "2048", "--out", dir.string()},
      contact));
  ASSERT_EQ(qs["status"], "success");
  std::ifstream in(dir / "mesh_parameters_set.txt");
  std::string table;
  std::getline(in, table);
  ASSERT_EQ(table.rfind("mesh.pinion-wheel.parameters={form=\"table\"", 0), 0u);
  std::vector<std::string> ltv = kCommon;
  ltv.push_back(table);

  const std::string range = "1500:7500:7";
  const nlohmann::json sim =
      RunJson(With({"simulate", kRig, "--mesh-frequency", range, "--max-periods", "600",
                    "--threads", "2", "--out", (dir / "sim").string()},
                   contact));
  const nlohmann::json hb =
      RunJson(With({"hb", kRig, "--mesh-frequency", range, "--stability", "none"}, ltv));
  ASSERT_EQ(sim["points"].size(), 7u);
  ASSERT_EQ(hb["points"].size(), 7u);
  for (std::size_t i = 0; i < 7; ++i) {
    const auto& p = sim["points"][i];
    const double f = p["mesh_frequency_hz"].get<double>();
    const double a = p["meshes"][0]["rms_dte_m"].get<double>();
    const double b = hb["points"][i]["meshes"][0]["rms_dte_m"].get<double>();
    std::printf("%.0f Hz: contact %.6g, LTV HB %.6g (%+.1f %%), loss %.3f, energy %.2g\n", f, a, b,
                100 * (a / b - 1), p["meshes"][0]["contact_loss_fraction"].get<double>(),
                p["max_energy_error"].get<double>());
    EXPECT_EQ(p["steady"], "steady") << f;
    EXPECT_EQ(p["meshes"][0]["contact_loss_fraction"].get<double>(), 0.0) << f;  // full contact
    EXPECT_NEAR(a, b, 0.02 * b) << f << " Hz";
    EXPECT_LT(p["max_energy_error"].get<double>(), 1e-4) << f << " Hz";
  }
}

}  // namespace
}  // namespace geardyn::app
