// The mesh preload in the assembled system (SceneSystemOptions::mesh_preload, issue 19): a spur
// pair on soft isotropic supports against the closed form of its modes across the line of action
// (the static mesh force from the torque balance, F = T / r_b1, the strut stiffness
// κ = −F / (a_w sin α_w)), and every built-in scene against exact eigenvalue invariants of a
// symmetric perturbation ΔK: the shift of Σλ equals tr(M⁻¹ΔK), each eigenvalue moves within
// the extreme eigenvalues of M^{-1/2} ΔK M^{-1/2} (Weyl; Courant–Fischer: never up when ΔK is
// negative semi-definite), and the rigid-body modes of the unloaded system stay exact zero modes
// (the free rotation of a loaded planetary train).
#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "geardyn/analyses/modal.hpp"
#include "geardyn/common/errors.hpp"
#include "geardyn/models/scene/builtin_scenes.hpp"
#include "geardyn/models/scene/scene_reader.hpp"
#include "geardyn/models/system/scene_system.hpp"
#include "support/scene_text.hpp"

namespace geardyn {
namespace {

constexpr double kSupport = 1.0e7;  // k [N/m] of both gears' radial supports (soft)
constexpr double kTorque = 200.0;   // T [N·m] on the pinion

// The spur pair of support/scene_text.hpp (20/40, m 2 mm, masses 0.5 and 2 kg) with diagonal
// supports: radial kSupport, axial and tilt stiff, free rotation; T in, 2T out.
std::string SoftPairScene() {
  const std::string support = R"(stiffness = [
  [1.0e7, 0, 0, 0, 0, 0], [0, 1.0e7, 0, 0, 0, 0], [0, 0, 1e9, 0, 0, 0],
  [0, 0, 0, 1e7, 0, 0], [0, 0, 0, 0, 1e7, 0], [0, 0, 0, 0, 0, 0]]
)";
  return test::SpurPairScene("soft pair",
                             "[[bearing]]\nname = \"pinion-support\"\nbody = "
                             "\"pinion\"\n" +
                                 support +
                                 "\n[[bearing]]\nname = \"wheel-support\"\nbody = "
                                 "\"wheel\"\n" +
                                 support +
                                 R"(
[[load]]
name = "output"
body = "wheel"
torque = 400.0

[operating_point]
body = "pinion"
speed_rpm = 1000.0
torque = 200.0
)");
}

ModalResult AllModes(const SystemModel& model) {
  ModalOptions options;
  options.method = ModalMethod::kDense;
  options.num_modes = 0;  // all
  ModalResult r = ComputeModes(model, options);
  EXPECT_TRUE(r.summary.ok()) << r.summary.BriefReport();
  return r;
}

double NearestRelativeGap(const VectorX& frequencies, double f) {
  double best = INFINITY;
  for (double g : frequencies) best = std::min(best, std::abs(g - f) / f);
  return best;
}

TEST(MeshPreloadSystemTest, SoftPairModesAcrossTheLineOfActionAreTheClosedForm) {
  const Scene scene = ParseScene(SoftPairScene(), "soft-pair");
  const GearPairGeometry& g = scene.meshes[0].geometry;
  SceneSystemOptions options;
  options.mesh_preload = true;
  const SceneSystem built = BuildSceneSystem(scene, options);
  ASSERT_EQ(built.mesh_preloads.size(), 1u);
  // Static balance: F_η = T / r_b1 (spur), the strut κ = −F / (a_w sin α_w).
  const double force = kTorque / g.pinion.base_radius;
  const double kappa = -force / (g.center_distance * std::sin(g.operating_pressure_angle));
  EXPECT_NEAR(built.mesh_preloads[0].force, force, 1e-9 * force);
  EXPECT_NEAR(built.mesh_preloads[0].coefficient, kappa, 1e-9 * std::abs(kappa));
  EXPECT_NEAR(built.mesh_preloads[0].line_length,
              g.center_distance * std::sin(g.operating_pressure_angle), 1e-15);
  // The translations across the line of action (u) touch neither the mesh (it acts along v)
  // nor anything but the supports: m_i ü_i + k u_i + κ (u_i − u_j) = 0, likewise for the wheel.
  const double m_i = 0.5, m_j = 2.0;
  const double a = (kSupport + kappa) / m_i, d = (kSupport + kappa) / m_j;
  const double b = -kappa / m_i, c = -kappa / m_j;  // [[a, b], [c, d]] = M⁻¹K
  const double mean = 0.5 * (a + d), spread = std::sqrt(0.25 * (a - d) * (a - d) + b * c);
  const ModalResult loaded = AllModes(built.model);
  for (double lambda : {mean - spread, mean + spread}) {
    const double f = std::sqrt(lambda) / (2.0 * std::numbers::pi);
    EXPECT_LT(NearestRelativeGap(loaded.frequencies_hz, f), 1e-9) << f << " Hz";
  }
  // Without the preload those two modes sit at √(k/m) — which the loaded model no longer has
  // (κ/k ≈ 5 %: a shift of about 2.6 % in frequency).
  const ModalResult plain = AllModes(BuildSceneSystem(scene).model);
  for (double m : {m_i, m_j}) {
    const double f = std::sqrt(kSupport / m) / (2.0 * std::numbers::pi);
    EXPECT_LT(NearestRelativeGap(plain.frequencies_hz, f), 1e-9) << f << " Hz";
    EXPECT_GT(NearestRelativeGap(loaded.frequencies_hz, f), 1e-3) << f << " Hz";
  }
}

TEST(MeshPreloadSystemTest, BuiltInScenesObeyTheInvariantsOfASymmetricPerturbation) {
  int analysed = 0;
  for (const std::string& name : BuiltinSceneNames()) {
    const Scene scene = LoadScene("builtin:" + name);
    if (scene.oscillator) continue;
    SCOPED_TRACE(name);
    SceneSystemOptions plain_options;
    plain_options.transmission_error = false;
    SceneSystemOptions loaded_options = plain_options;
    loaded_options.mesh_preload = true;
    const SceneSystem plain = BuildSceneSystem(scene, plain_options);
    const SceneSystem loaded = BuildSceneSystem(scene, loaded_options);
    ASSERT_EQ(loaded.mesh_preloads.size(), scene.meshes.size());
    // K_g = the difference of the two K0 (the preload elements), M the same.
    const MatrixX Kg = loaded.model.DenseConstantStiffness() - plain.model.DenseConstantStiffness();
    const MatrixX M = plain.model.DenseMass();
    ASSERT_GT(Kg.cwiseAbs().maxCoeff(), 0.0);
    const Eigen::LLT<MatrixX> llt(M);
    const MatrixX Linv = llt.matrixL().solve(MatrixX::Identity(M.rows(), M.cols()));
    const MatrixX S = Linv * Kg * Linv.transpose();  // M^{-1/2} K_g M^{-1/2}, similar to M⁻¹K_g
    const VectorX s_eig = Eigen::SelfAdjointEigenSolver<MatrixX>(S).eigenvalues();
    const ModalResult a = AllModes(plain.model), b = AllModes(loaded.model);
    ASSERT_EQ(a.eigenvalues.size(), b.eigenvalues.size());
    // Round-off of the dense solver: ~n eps max λ per eigenvalue.
    const double lambda_max = a.eigenvalues.cwiseAbs().maxCoeff();
    const double round_off = 1e3 * static_cast<double>(M.rows()) * 2.2e-16 * lambda_max;
    const VectorX shift = b.eigenvalues - a.eigenvalues;
    EXPECT_NEAR(shift.sum(), S.trace(), 1e-6 * std::abs(S.trace()) + round_off);
    const double spread = s_eig.cwiseAbs().maxCoeff();
    for (Eigen::Index k = 0; k < shift.size(); ++k) {
      EXPECT_LE(shift(k), s_eig.maxCoeff() + 1e-9 * spread + round_off) << "mode " << k;
      EXPECT_GE(shift(k), s_eig.minCoeff() - 1e-9 * spread - round_off) << "mode " << k;
    }
    EXPECT_EQ(b.num_rigid_body_modes, a.num_rigid_body_modes);
    ++analysed;
  }
  EXPECT_GE(analysed, 4);
}

TEST(MeshPreloadSystemTest, IsRefusedOnAnOscillatorScene) {
  for (const std::string& name : BuiltinSceneNames()) {
    const Scene scene = LoadScene("builtin:" + name);
    if (!scene.oscillator) continue;
    SceneSystemOptions options;
    options.mesh_preload = true;
    EXPECT_THROW(BuildSceneSystem(scene, options), InvalidInput) << name;
  }
}

}  // namespace
}  // namespace geardyn
