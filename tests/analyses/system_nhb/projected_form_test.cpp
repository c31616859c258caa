/// @file
/// @brief Exact integration of the slice law through its projected form (nonlinear_hb.hpp,
/// "Exact integration of projected laws") against the general path: the sampled AFT of the same
/// law at a very fine grid, on the Kahraman–Blankenship rig with a backlash small enough that
/// the chosen orbit hits the back flank as well as losing contact.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "geardyn/analyses/nonlinear_hb.hpp"
#include "geardyn/analyses/system_nonlinear_hb.hpp"
#include "geardyn/models/scene/scene_reader.hpp"
#include "geardyn/models/system/scene_system.hpp"

namespace geardyn {
namespace {

// Centre distance 150.01 mm: backlash ≈ 7 µm (0.2 mm of allowance gives ≈ 0.14 mm).
SystemModel RigWithSmallBacklash() {
  const std::vector<std::string> overrides = {
      "mesh.pinion-wheel.model=\"slices\"", "mesh.pinion-wheel.slices=10",
      "mesh.pinion-wheel.center_distance=0.15001", "mesh.pinion-wheel.damping_ratio=0.05"};
  return BuildSceneSystem(LoadScene("builtin:kahraman-blankenship-rig", overrides)).model;
}

// The sampled AFT (trapezoidal rule) errs by O(h) where g jumps (the stiffness steps of k_s(θ)
// times a loaded slice) and O(h²) at the contact kinks, h = 2π/S: its error against the exact
// coefficients must stay below C·h (first order): at S = 16384·H below 1e-5 of the
// residual's scale (measured 4.7e-6), at half the samples below 2e-5 (measured 5e-7: the error
// depends on where the steps fall between the samples). The Jacobian coefficients err by O(h) at
// the switches: 2e-3 leaves a factor ≈ 10.
constexpr int kFineSamplesPerHarmonic = 16384;
constexpr double kResidualTol = 1e-5;
constexpr double kJacobianTol = 2e-3;

TEST(ProjectedSliceForm, ExactEqualsFinelySampledAftWithContactLossAndBackFlank) {
  const SystemModel model = RigWithSmallBacklash();
  const SystemNhbProblem sp = MakeSystemNhbProblem(model);
  ASSERT_EQ(sp.problem.law->num_coordinates(), 2);
  const int H = 12;
  NhbOptions exact_options;
  exact_options.period_multiple = sp.period_meshes;
  NhbOptions sampled_options = exact_options;
  sampled_options.force_integration = NhbForceIntegration::kSampled;
  sampled_options.samples_per_harmonic = kFineSamplesPerHarmonic;
  NhbSolver exact(sp.problem, exact_options, H);
  NhbSolver sampled(sp.problem, sampled_options, H);
  NhbOptions coarse_options = sampled_options;
  coarse_options.samples_per_harmonic = kFineSamplesPerHarmonic / 2;
  NhbSolver coarse(sp.problem, coarse_options, H);
  ASSERT_TRUE(exact.exact_integration());
  ASSERT_FALSE(sampled.exact_integration());

  // An orbit around the static deflection with an alternating part of 4× the mean deflection
  // in δ_η (contact loss and back-flank contact: backlash ≈ 7 µm) and a tilt δ_ζ that moves
  // the switches of the slices apart.
  const double omega = 2.0 * std::numbers::pi * 1700.0;
  VectorX x = exact.ContactGuess(omega);
  const double mean = x[0];
  ASSERT_GT(mean, 0.0);
  const double amplitude = 4.0 * std::max(mean, 7e-6);
  const int n = 2;
  for (int k = 1; k <= 3; ++k) {
    x[n * (2 * k - 1)] = amplitude / (2.0 * k);             // Re U_k of δ_η
    x[n * 2 * k] = -0.3 * amplitude / (2.0 * k);            // Im U_k of δ_η
    x[n * (2 * k - 1) + 1] = 0.02 * amplitude / (2.0 * k);  // Re U_k of δ_ζ [rad]
  }
  VectorX r_exact, r_sampled, d_exact, d_sampled;
  MatrixX j_exact, j_sampled;
  exact.Evaluate(x, omega, &r_exact, &j_exact, &d_exact);
  sampled.Evaluate(x, omega, &r_sampled, &j_sampled, &d_sampled);
  const double r_scale = r_exact.lpNorm<Eigen::Infinity>();
  ASSERT_GT(r_scale, 0.0);
  VectorX r_coarse;
  coarse.Evaluate(x, omega, &r_coarse, nullptr, nullptr);
  const double fine_error = (r_exact - r_sampled).lpNorm<Eigen::Infinity>();
  const double coarse_error = (r_exact - r_coarse).lpNorm<Eigen::Infinity>();
  EXPECT_LE(fine_error, kResidualTol * r_scale);
  // First order with a constant that depends on where the steps fall between samples (so not
  // monotone in S): bounded by the same constant times h.
  EXPECT_LE(coarse_error, 2.0 * kResidualTol * r_scale);
  EXPECT_LE((d_exact - d_sampled).lpNorm<Eigen::Infinity>(),
            kResidualTol * d_exact.lpNorm<Eigen::Infinity>());
  const double j_scale = j_exact.lpNorm<Eigen::Infinity>();
  EXPECT_LE((j_exact - j_sampled).lpNorm<Eigen::Infinity>(), kJacobianTol * j_scale);

  // The orbit really covers the three states: the extremes of δ_η straddle 0 and −backlash.
  NhbPoint point;
  exact.Describe(x, omega, point);
  EXPECT_GT(point.maximum[0], 0.0);
  EXPECT_LT(point.minimum[0], -7e-6);
}

// The exact Jacobian is the derivative of the exact residual: central differences (the
// residual is C¹ in x away from grazing, and piecewise smooth).
TEST(ProjectedSliceForm, JacobianMatchesFiniteDifferences) {
  const SystemModel model = RigWithSmallBacklash();
  const SystemNhbProblem sp = MakeSystemNhbProblem(model);
  NhbOptions options;
  options.period_multiple = sp.period_meshes;
  const int H = 6;
  NhbSolver solver(sp.problem, options, H);
  const double omega = 2.0 * std::numbers::pi * 1700.0;
  VectorX x = solver.ContactGuess(omega);
  const double amplitude = 3.0 * std::max(x[0], 7e-6);
  x[2] = amplitude;
  x[3] = 0.01 * amplitude;
  x[4] = 0.5 * amplitude;
  VectorX r0, rp, rm;
  MatrixX J;
  solver.Evaluate(x, omega, &r0, &J, nullptr);
  const double scale = J.lpNorm<Eigen::Infinity>();
  for (Eigen::Index c = 0; c < x.size(); ++c) {
    const double h = 1e-6 * (std::abs(x[c]) + amplitude);
    VectorX xp = x, xm = x;
    xp[c] += h;
    xm[c] -= h;
    solver.Evaluate(xp, omega, &rp, nullptr, nullptr);
    solver.Evaluate(xm, omega, &rm, nullptr, nullptr);
    const VectorX fd = (rp - rm) / (2.0 * h);
    EXPECT_LE((fd - J.col(c)).lpNorm<Eigen::Infinity>(), 1e-5 * scale) << "column " << c;
  }
}

}  // namespace
}  // namespace geardyn
