// The exact-steps error estimate must cover its round-off at low speed (issue 12, found by trying
// `geardyn hb builtin:kahraman-blankenship-rig --mesh-frequency 0.2:3000:30`): at f_m = 0.2 Hz
// the undamped rig's product read max|λ| = 1 + 6.4e-12 against an estimate of 1.5e-13 and was
// called "unstable". The scaling and squaring of each expm(AΔt) loses about ε‖AΔt‖, and ‖A‖T is
// 8e5 there. Truth: the same step product in extended precision (long double, ε = 1.1e-19), an
// independent evaluation whose own round-off is ~1e-13 at these ‖A‖T.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <numbers>
#include <unsupported/Eigen/MatrixFunctions>

#include "geardyn/analyses/floquet.hpp"
#include "geardyn/models/scene/scene_reader.hpp"
#include "geardyn/models/system/scene_system.hpp"
#include "geardyn/system/system_steps.hpp"
#include "geardyn/system/workspace.hpp"

namespace geardyn::test {
namespace {

using LongMatrix = Eigen::Matrix<long double, Eigen::Dynamic, Eigen::Dynamic>;

// max|λ| of the flexible part of M q'' + C q' + K(θ) q = 0 over one mesh cycle at f_m, by the step
// product in long double on modal coordinates of the mean system (rigid modes dropped: K and C
// annihilate them at every θ), state z = [η; η̇/ω_s] with ω_s the highest mean-system frequency.
long double ExtendedPrecisionMaxAbs(const SystemModel& model, double mesh_hz) {
  SystemWorkspace ws(model);
  const SystemSteps steps = CollectSystemSteps(model);
  const double omega_m = 2.0 * std::numbers::pi * mesh_hz;
  const int n = model.num_dofs();
  MatrixX K_mean = MatrixX::Zero(n, n);
  for (int k = 0; k < steps.num_intervals(); ++k) {
    K_mean += AssembleStiffness(model, ws, steps.interval_midpoint(k)) *
              (steps.interval_width(k) / (2.0 * std::numbers::pi));
  }
  const Eigen::GeneralizedSelfAdjointEigenSolver<MatrixX> eig(K_mean, model.DenseMass());
  const VectorX& w2 = eig.eigenvalues();
  int rigid = 0;
  while (rigid < n && std::abs(w2[rigid]) <= 1e-10 * w2[n - 1]) ++rigid;
  const int f = n - rigid;
  const MatrixX Phi = eig.eigenvectors().rightCols(f);  // Φᵀ M Φ = I
  const long double omega_s = std::sqrt(static_cast<long double>(w2[n - 1]));
  LongMatrix monodromy = LongMatrix::Identity(2 * f, 2 * f);
  for (int k = 0; k < steps.num_intervals(); ++k) {
    const double theta = steps.interval_midpoint(k);
    const MatrixX K = Phi.transpose() * AssembleStiffness(model, ws, theta) * Phi;
    const MatrixX C = Phi.transpose() * AssembleDamping(model, ws, theta) * Phi;
    LongMatrix A = LongMatrix::Zero(2 * f, 2 * f);
    A.topRightCorner(f, f) = omega_s * LongMatrix::Identity(f, f);
    A.bottomLeftCorner(f, f) = -K.cast<long double>() / omega_s;
    A.bottomRightCorner(f, f) = -C.cast<long double>();
    const long double dt = static_cast<long double>(steps.interval_width(k)) / omega_m;
    monodromy = ((A * dt).exp() * monodromy).eval();
  }
  const Eigen::EigenSolver<LongMatrix> spectrum(monodromy);
  EXPECT_EQ(spectrum.info(), Eigen::Success);
  long double max_abs = 0.0L;
  for (int i = 0; i < 2 * f; ++i) max_abs = std::max(max_abs, std::abs(spectrum.eigenvalues()[i]));
  return max_abs;
}

TEST(ExactStepsRoundoffTest, EstimateCoversTheDifferenceToAnExtendedPrecisionProduct) {
  const SystemModel model = BuildSceneSystem(LoadScene("builtin:kahraman-blankenship-rig")).model;
  // 0.2 Hz (0.24 rpm), 2.5 Hz (3 rpm), the 2000 Hz operating point.
  for (const double hz : {0.2, 2.5, 2000.0}) {
    SCOPED_TRACE("f_m = " + std::to_string(hz) + " Hz");
    FloquetOptions o;
    o.mesh_frequency_hz = hz;
    o.method = FloquetMethod::kExactSteps;
    const FloquetResult r = ComputeFloquet(model, o);
    ASSERT_TRUE(r.summary.ok()) << r.summary.message;
    const long double truth = ExtendedPrecisionMaxAbs(model, hz);
    // The undamped rig: every flexible multiplier on the unit circle (extended-precision
    // round-off ~ 1e-19 · ‖A‖T ≤ 1e-13), so the verdict is stable and marginal.
    EXPECT_LT(std::abs(truth - 1.0L), 1e-12L);
    EXPECT_LE(std::abs(static_cast<long double>(r.max_abs_multiplier) - truth),
              static_cast<long double>(r.summary.error_estimate))
        << "max|λ| − 1 = " << r.max_abs_multiplier - 1.0
        << ", estimate = " << r.summary.error_estimate;
    EXPECT_EQ(r.verdict, FloquetVerdict::kStable);
    EXPECT_TRUE(r.marginal);
  }
}

}  // namespace
}  // namespace geardyn::test
