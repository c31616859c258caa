// The scene's [damping] table through MakeSystemModel: modal damping against the closed-form
// complex eigenvalues of a viscously damped mode, Rayleigh damping against ζ = α/(2ω) + βω/2,
// the per-mode list, and the planar restriction (damping built on the planar model's own modes).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <string>
#include <vector>

#include "geardyn/analyses/modal.hpp"
#include "geardyn/models/scene/scene_reader.hpp"
#include "geardyn/models/system/scene_system.hpp"

namespace geardyn {
namespace {

// Damped and undamped modes are both computed by ComputeModes; the truth is the closed form
// linking them, λ_r = −ζ_r ω_r ± i ω_r √(1 − ζ_r²) (classical damping, Φᵀ C Φ diagonal).
constexpr double kTol = 1e-7;  // relative; dense state-space QR on 24 states, ‖A‖ ~ ω_max

ModalResult Modes(const SystemModel& model, bool damped) {
  ModalOptions o;
  o.method = ModalMethod::kDense;
  o.compute_damped = damped;
  o.compute_energy_fractions = false;
  const ModalResult r = ComputeModes(model, o);
  EXPECT_TRUE(r.summary.ok()) << r.summary.message;
  return r;
}

// The damped eigenvalue (Im ≥ 0) nearest `target`.
std::complex<double> Nearest(const ModalResult& r, std::complex<double> target) {
  std::complex<double> best = r.damped_modes.front().eigenvalue;
  for (const DampedMode& d : r.damped_modes) {
    if (std::abs(d.eigenvalue - target) < std::abs(best - target)) best = d.eigenvalue;
  }
  return best;
}

// Every flexible undamped mode ω_r has its damped pair at −ζ_r ω_r + i ω_r √(1 − ζ_r²).
void ExpectClosedFormPairs(const Scene& undamped_scene, const std::vector<std::string>& overrides,
                           const std::vector<double>& zeta_of_mode) {
  const ModalResult plain = Modes(MakeSystemModel(undamped_scene), false);
  const Scene damped_scene = LoadScene(undamped_scene.source, overrides);
  const ModalResult damped = Modes(MakeSystemModel(damped_scene), true);
  int flexible = 0;
  for (int r = 0; r < plain.frequencies_hz.size(); ++r) {
    const double w = 2.0 * M_PI * plain.frequencies_hz(r);
    if (w == 0.0) continue;  // rigid-body mode: no damping
    const double z = zeta_of_mode[std::min<std::size_t>(flexible++, zeta_of_mode.size() - 1)];
    const std::complex<double> expected(-z * w, w * std::sqrt(1.0 - z * z));
    EXPECT_LT(std::abs(Nearest(damped, expected) - expected), kTol * w) << "mode " << r;
  }
  EXPECT_GT(flexible, 0);
}

TEST(SceneDampingTest, ModalRatioDampsEveryFlexibleModeByTheClosedForm) {
  ExpectClosedFormPairs(LoadScene("builtin:helical-pair"), {"damping.modal_ratio=0.05"}, {0.05});
}

TEST(SceneDampingTest, PerModeRatiosApplyInAscendingFrequencyThenTheCommonRatio) {
  // Modes 1–3 (flexible, ascending) get 0.01, 0.02, 0.03; the others modal_ratio = 0.04.
  ExpectClosedFormPairs(LoadScene("builtin:helical-pair"),
                        {"damping.modal_ratios=[0.01, 0.02, 0.03]", "damping.modal_ratio=0.04"},
                        {0.01, 0.02, 0.03, 0.04});
}

TEST(SceneDampingTest, RigidBodyModeStaysUndamped) {
  // The helical pair turns freely (no torsional support): one rigid mode r, and C r = 0.
  const Scene scene = LoadScene("builtin:helical-pair", {"damping.modal_ratio=0.1"});
  const SystemModel model = MakeSystemModel(scene);
  ModalOptions o;
  o.method = ModalMethod::kDense;
  o.compute_shapes = true;
  const ModalResult r = ComputeModes(model, o);
  ASSERT_EQ(r.num_rigid_body_modes, 1);
  const MatrixX C = model.DenseConstantDamping();
  const VectorX rigid = r.shapes.col(0);
  EXPECT_LT((C * rigid).norm(), 1e-10 * C.norm() * rigid.norm());
  // …while the flexible modes are damped: C φ_1 ≠ 0.
  EXPECT_GT((C * r.shapes.col(1)).norm(), 1e-3 * C.norm() * r.shapes.col(1).norm());
}

TEST(SceneDampingTest, RayleighGivesAlphaOverTwoOmegaPlusBetaOmegaOverTwo) {
  const double alpha = 20.0, beta = 2e-6;  // [1/s], [s]
  const Scene scene = LoadScene("builtin:helical-pair");
  const ModalResult plain = Modes(MakeSystemModel(scene), false);
  const ModalResult damped =
      Modes(MakeSystemModel(LoadScene("builtin:helical-pair",
                                      {"damping.rayleigh_alpha=20", "damping.rayleigh_beta=2e-6"})),
            true);
  for (int r = 1; r < plain.frequencies_hz.size(); ++r) {
    const double w = 2.0 * M_PI * plain.frequencies_hz(r);
    const double z = alpha / (2.0 * w) + beta * w / 2.0;
    if (z >= 1.0) continue;  // overdamped: no oscillating pair
    const std::complex<double> expected(-z * w, w * std::sqrt(1.0 - z * z));
    EXPECT_LT(std::abs(Nearest(damped, expected) - expected), kTol * w) << "mode " << r;
  }
}

TEST(SceneDampingTest, PlanarSceneIsDampedOnItsOwnModes) {
  // After RestrictToPlanar the modes differ from the 3-D ones: the ratio must hold for them.
  ExpectClosedFormPairs(LoadScene("builtin:helical-pair", {"planar=true"}),
                        {"planar=true", "damping.modal_ratio=0.03"}, {0.03});
}

}  // namespace
}  // namespace geardyn
