// The slice model matched to a tooth-contact mesh for `simulate --overlay-hb` (overlay_match.hpp)
// on the Kahraman–Blankenship rig (rigid teeth, Kim's law, 100 N·m). Truths: the slice model's
// mean mesh stiffness is k·b·ε_α for a spur pair (mean contact length b ε_α, ε_α from the gear
// geometry), so k = K̄_c/(b ε_α); Kim's damper at the mean pair load F/ε_α (F = T/r_b, δ from
// k_law δ^{m1}) summed over ε_α pairs gives c_m = ε_α c (F/(ε_α k_law))^{m3/m1}
// (examples/kim_qfb/kim_qfb_sweeps.py); and an independent quasi-static roll of the matched slice
// model has the contact model's mean stiffness.
#include "geardyn/overlay_match.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "geardyn/analyses/time_response.hpp"
#include "geardyn/models/contact/contact_law.hpp"
#include "geardyn/models/scene/scene_reader.hpp"
#include "geardyn/models/system/scene_system.hpp"

namespace geardyn::app {
namespace {

constexpr double kTorque = 100.0;  // [N·m]
const std::string kRig = "builtin:kahraman-blankenship-rig";

SystemModel Build(const std::vector<std::string>& extra) {
  std::vector<std::string> sets = {"operating_point.torque=100", "load.brake.torque=100"};
  sets.insert(sets.end(), extra.begin(), extra.end());
  SceneSystemOptions so;
  so.analysis = "simulate";
  so.allow_contact_meshes = true;
  return BuildSceneSystem(LoadScene(kRig, sets), so).model;
}

double MeanStiffness(const SystemModel& model) {
  QuasiStaticOptions o;
  o.samples_per_mesh = 64;
  o.sampling = QuasiStaticSampling::kMeshCycle;
  const QuasiStaticResult r = SimulateQuasiStatic(model, o);
  EXPECT_TRUE(r.summary.ok()) << r.summary.message;
  return r.meshes.at(0).stiffness.row(0).mean();
}

TEST(OverlayMatch, KimRigMatchEqualsTheSpurPairClosedForms) {
  const std::vector<std::string> contact = {"mesh.pinion-wheel.model=\"contact\""};
  const Scene scene =
      LoadScene(kRig, {"operating_point.torque=100", "load.brake.torque=100", contact[0]});
  std::vector<std::string> warnings;
  const std::vector<SliceMatch> m = MatchSlicesToContact(Build(contact), scene, Build, &warnings);
  ASSERT_EQ(m.size(), 1u);
  EXPECT_TRUE(warnings.empty());
  const GearPairGeometry& g = scene.meshes.at(0).geometry;
  const double eps = g.transverse_contact_ratio, b = g.face_width;
  const double force = kTorque / g.pinion.base_radius;
  // The contact core's mesh force is T/r_b (static torque balance of the pinion).
  EXPECT_NEAR(m[0].mean_force, force, 1e-3 * force);
  // Mean contacts n̄ ≈ ε_α: above it by the entering tooth's tip-corner contact before the
  // path's start under load (contact_xcheck_test.cpp; ≈ 4 % here), within the 1/64 sampling.
  EXPECT_GE(m[0].mean_contacts, eps - 1.0 / 64);
  EXPECT_LE(m[0].mean_contacts, 1.05 * eps + 1.0 / 64);
  const double k_closed = m[0].contact_mean_stiffness / (b * eps);
  EXPECT_NEAR(m[0].stiffness_per_length, k_closed, 0.02 * k_closed);
  // Kim's damper at the mean contact load F/n̄ summed over n̄ contacts; with n̄ = ε_α the
  // kim_qfb_sweeps.py value, larger by (n̄/ε_α)^{1 − m3/m1} ≈ 3 % here.
  const ContactLaw law = KimContactLaw();
  const auto c_closed = [&](double n) {
    return n * law.damping *
           std::pow(force / (n * law.stiffness), law.indentation_exponent / law.stiffness_exponent);
  };
  EXPECT_NEAR(m[0].damping, c_closed(m[0].mean_contacts), 1e-3 * c_closed(m[0].mean_contacts));
  EXPECT_NEAR(m[0].damping, c_closed(eps), 0.05 * c_closed(eps));
  // An independent roll of the matched slice model: the contact model's mean stiffness.
  const double ks = MeanStiffness(Build(MatchedSliceOverrides(m)));
  EXPECT_NEAR(ks, m[0].contact_mean_stiffness, 5e-3 * m[0].contact_mean_stiffness);
}

}  // namespace
}  // namespace geardyn::app
