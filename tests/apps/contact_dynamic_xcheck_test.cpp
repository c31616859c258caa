// Dynamic cross-check 1 of the tooth-contact model (issue 14, "Must show"): a full-contact case
// of the rig integrated to steady state (`geardyn simulate`) against the linear HB of the LTV
// mesh built from the contact model's own quasi-static mode (`simulate --quasi-static` →
// [mesh.parameters] table, 2048 samples, read back through the scene reader): RMS DTE within
// 2 % at 13 mesh frequencies 1500–6300 Hz across the mesh resonance (peak near 3500 Hz).
//
// What is compared and why (docs/design.md, "Contact simulator: cross-checks"):
// * the loaded DTE δ_η = g q (Kim Eq. 14: the approach of the gear bodies along the tooth
//   normal), which is the contact model's DTE (a contact mesh has no ε). The LTV's own DTE is
//   δ_η − ε_η (probes.hpp) with the exported ε = δ − F/K(θ) (an equivalent unloaded TE that
//   makes the LTV's static deflection the contact model's): where ε ≠ 0 (relief zones,
//   tip-corner windows) the two DTEs differ by ε for the same motion — above the resonance,
//   where the bodies no longer follow the STE, ε dominates the LTV DTE. So the LTV's δ_η is
//   formed from its HB harmonics, δ_η,k = g Q_k;
// * damping: the contact law's damper c acts per loaded contact (a mesh damping c·n(θ)), which
//   the exported table cannot carry (an LTV mesh has one constant c_m), so c = 0 (the linear
//   law's default) and no mesh damping in either model; both get the same bearing dampers, the
//   rz entries 120 N·m·s/rad (c/(2 r_b²) ≈ 1.2e4 N·s/m along the line of action, ζ ≈ 0.27 of
//   the mesh mode: K̄ = 6.27e8 N/m, torsional m_e = 0.785 kg), and the same torsional support
//   of the wheel (1e6 N·m/rad) that holds the rigid-body rotation;
// * the case in which the LTV model is the small-amplitude limit of the contact model: rigid
//   teeth (period 1 mesh cycle), the linear law (every loaded pair at the same δ, K(θ) = k n(θ)),
//   and linear tip relief on both gears (40 µm over 1 mm), which removes the sharp tip-corner
//   contact before the start of the path (its window grows as √δ; tip_corner_contact.hpp). A
//   relieved pair enters and leaves with zero force (f = k (δ − r)⁺ is continuous), so a dynamic
//   change x of the approach only moves the switch by x·L/C (25 µm of roll per µm, 0.3 % of p_b):
//   a second-order change of the force, which the LTV drops — the residual (measured ≤ 0.8 %;
//   1.5 % with C = 20 µm, 2.5 % and a little contact loss with ζ ≈ 0.1) shrinks with L/C and
//   with the amplitude. The static approach (≤ 3.5 µm at 100 N·m) stays inside the relief.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "geardyn/analyses/harmonic_balance.hpp"
#include "geardyn/cli.hpp"
#include "geardyn/models/scene/scene_reader.hpp"
#include "geardyn/models/system/scene_system.hpp"
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

/// RMS of the alternating part of the loaded DTE δ_η = g q of mesh 0 from the HB harmonics:
/// q(t) = Σ_k Q_k e^{ikΩt} (k = −K … K, Q_−k = conj Q_k), so RMS² = Σ_{k≥1} 2 |g Q_k|².
double LoadedDteRms(const SystemModel& model, const HbResult& hb) {
  const SystemMesh& mesh = model.meshes().at(0);
  double sum = 0.0;
  for (Eigen::Index k = 1; k < hb.response_harmonics.cols(); ++k) {
    std::complex<double> y = 0.0;
    for (int a = 0; a < 12; ++a) {
      if (mesh.dofs[a] >= 0) y += mesh.G(0, a) * hb.response_harmonics(mesh.dofs[a], k);
    }
    sum += 2.0 * std::norm(y);
  }
  return std::sqrt(sum);
}

struct Case {
  // The parameters of the case (as --set values).
  std::string torque = "100";
  std::string relief = "40e-6";        // tip relief C on both gears [m] ("" = none)
  std::string relief_length = "1e-3";  // L [m]
  std::string rz_damping = "120";      // bearing rz dampers [N·m·s/rad]
  std::string stiffness = "4e8";       // k of the linear law [N/m]
  std::string range = "1500:6300:13";
};

// Runs the case: quasi-static export, contact sweep, LTV HB; asserts RMS δ_η within `tolerance`,
// full contact, steady state and the energy balance at every point.
void RunCase(const Case& cs, const std::string& name, double tolerance) {
  const std::string d = "[16600,16600,5260,63,63," + cs.rz_damping + "]";
  const std::vector<std::string> common = {
      "bearing.pinion-support.damping=" + d, "bearing.wheel-support.damping=" + d,
      "bearing.wheel-support.stiffness=[1e10,1e10,1e9,1e8,1e8,1e6]",
      "operating_point.torque=" + cs.torque, "load.brake.torque=" + cs.torque};
  std::vector<std::string> contact = common;
  contact.push_back("mesh.pinion-wheel.model=\"contact\"");
  contact.push_back("mesh.pinion-wheel.contact={law=\"linear\",stiffness=" + cs.stiffness + "}");
  if (!cs.relief.empty()) {
    contact.push_back("mesh.pinion-wheel.modifications={pinion_tip_relief=" + cs.relief +
                      ",pinion_tip_relief_length=" + cs.relief_length + ",gear_tip_relief=" +
                      cs.relief + ",gear_tip_relief_length=" + cs.relief_length + "}");
  }
  const std::filesystem::path dir = std::filesystem::path(GEARDYN_BINARY_DIR) / "test_output" /
                                    ("contact_dynamic_xcheck_" + name);
  std::filesystem::remove_all(dir);
  const nlohmann::json qs = RunJson(With(
      {"simulate", kRig, "--quasi-static", "--samples-per-period", "2048", "--out", dir.string()},
      contact));
  ASSERT_EQ(qs["status"], "success");
  std::ifstream in(dir / "mesh_parameters_set.txt");
  std::string table;
  std::getline(in, table);
  ASSERT_EQ(table.rfind("mesh.pinion-wheel.parameters={form=\"table\"", 0), 0u);
  std::vector<std::string> ltv_sets = common;
  ltv_sets.push_back(table);
  const SystemModel ltv = BuildSceneSystem(LoadScene(kRig, ltv_sets)).model;

  const nlohmann::json sim =
      RunJson(With({"simulate", kRig, "--mesh-frequency", cs.range, "--max-periods", "600",
                    "--threads", "2", "--out", (dir / "sim").string()},
                   contact));
  ASSERT_EQ(sim["points"].size(), 13u);
  HbOptions o;
  o.harmonics = 64;
  o.keep_harmonics = true;
  for (const auto& p : sim["points"]) {
    const double f = p["mesh_frequency_hz"].get<double>();
    const HbResult hb = SolveHarmonicBalance(ltv, o, f);
    ASSERT_TRUE(hb.summary.ok()) << hb.summary.BriefReport();
    const double a = p["meshes"][0]["rms_dte_m"].get<double>();
    const double b = LoadedDteRms(ltv, hb);
    std::printf(
        "%.0f Hz: contact %.6g, LTV HB loaded DTE %.6g (%+.2f %%; LTV DTE δ−ε %.6g), loss %.3f, "
        "energy %.2g, %d periods, %s\n",
        f, a, b, 100 * (a / b - 1), hb.meshes[0].rms_dte,
        p["meshes"][0]["contact_loss_fraction"].get<double>(), p["max_energy_error"].get<double>(),
        p["periods"].get<int>(), p["steady"].get<std::string>().c_str());
    EXPECT_EQ(p["steady"], "steady") << f;
    EXPECT_EQ(p["meshes"][0]["contact_loss_fraction"].get<double>(), 0.0) << f;  // full contact
    EXPECT_NEAR(a, b, tolerance * b) << f << " Hz";
    EXPECT_LT(p["max_energy_error"].get<double>(), 1e-4) << f << " Hz";
  }
}

TEST(ContactDynamicCrossCheck, FullContactSweepEqualsLinearHbOfTheQuasiStaticLtv) {
  RunCase(Case{}, "relief", 0.02);
}

}  // namespace
}  // namespace geardyn::app
