// kArpackMonodromy (ARPACK on the matrix-free monodromy operator) against independent truths:
// the closed form of a 201-DOF system of decoupled damped oscillators plus a Meissner SDOF (the
// sparse expm-action path), the dense exact-steps path on 60 geared-shaft DOFs (the dense step
// propagators), the dense Magnus path on the smooth 12-DOF pair; bad options → InvalidInput.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <numbers>
#include <vector>

#include "floquet_test_support.hpp"
#include "geardyn/common/errors.hpp"
#include "support/expect_throws.hpp"

namespace geardyn::test {
namespace {

constexpr double kMeshHz = 5000.0;

// Distance of λ to the nearest of `truth`.
double Nearest(std::complex<double> lambda, const VectorXc& truth) {
  return (truth.array() - lambda).abs().minCoeff();
}

// Moduli of v, descending.
std::vector<double> Moduli(const VectorXc& v) {
  std::vector<double> m;
  for (int i = 0; i < v.size(); ++i) m.push_back(std::abs(v[i]));
  std::sort(m.rbegin(), m.rend());
  return m;
}

// 200 decoupled oscillators q̈_i + c_i q̇_i + ω_i² q_i = 0 (ω_i = 0.3 … 1.0 rad/s, c_i = 0.02 (1 +
// i) 1/s) and a Meissner SDOF (k = 1.3 / 0.7, duty 0.5) over T = 3.1 s (in its principal
// instability tongue). M = I, so the state matrices are sparse.
constexpr int kOscillators = 200;
constexpr double kPeriod = 3.1;
double Omega(int i) { return 0.3 + 0.7 * i / (kOscillators - 1.0); }
double Damping(int i) { return 0.02 * (1.0 + i); }

PeriodicSecondOrderSystem OscillatorsAndMeissner() {
  const int n = kOscillators + 1;
  PeriodicSecondOrderSystem s;
  s.mass = MatrixX::Identity(n, n);
  s.period_s = kPeriod;
  for (const double k : {1.3, 0.7}) {
    PeriodicStep step;
    step.duration_s = 0.5 * kPeriod;
    step.stiffness = MatrixX::Zero(n, n);
    step.damping = MatrixX::Zero(n, n);
    for (int i = 0; i < kOscillators; ++i) {
      step.stiffness(i, i) = Omega(i) * Omega(i);
      step.damping(i, i) = Damping(i);
    }
    step.stiffness(kOscillators, kOscillators) = k;
    s.steps.push_back(std::move(step));
  }
  return s;
}

// Closed form: e^{sT}, s = −c/2 ± √(c²/4 − ω²) for each oscillator; the Meissner pair from the
// trace of its two exact transfer matrices.
VectorXc OscillatorsAndMeissnerTruth() {
  VectorXc l(2 * kOscillators + 2);
  for (int i = 0; i < kOscillators; ++i) {
    const double c = Damping(i), w = Omega(i);
    const std::complex<double> root = std::sqrt(std::complex<double>(c * c / 4.0 - w * w));
    l[2 * i] = std::exp((-c / 2.0 + root) * kPeriod);
    l[2 * i + 1] = std::exp((-c / 2.0 - root) * kPeriod);
  }
  l.tail(2) = MeissnerMultipliers(MeissnerTrace(1.3, 0.7, 0.5 * kPeriod, 0.5 * kPeriod));
  return l;
}

TEST(ArpackMonodromyTest, DominantMultipliersOfA201DofSystemEqualTheClosedForm) {
  const PeriodicSecondOrderSystem system = OscillatorsAndMeissner();
  const VectorXc truth = OscillatorsAndMeissnerTruth();
  FloquetOptions o;
  o.method = FloquetMethod::kArpackMonodromy;
  o.arpack_nev = 6;
  o.tolerance = 1e-10;
  const FloquetResult r = ComputeFloquet(system, o);
  ASSERT_TRUE(r.summary.ok()) << r.summary.message;
  EXPECT_EQ(r.method_used, FloquetMethod::kArpackMonodromy);
  EXPECT_EQ(r.summary.counters.at("expm_action"), 1);  // the sparse matrix-free path
  EXPECT_EQ(r.summary.counters.at("arpack_converged"), 6);
  ASSERT_GE(r.multipliers.size(), 6);
  EXPECT_LE(r.summary.error_estimate, 1e-9);
  const std::vector<double> top = Moduli(truth);
  const std::vector<double> got = Moduli(r.multipliers);
  for (int i = 0; i < r.multipliers.size(); ++i) {
    // Each is a true multiplier, and they are the largest ones.
    EXPECT_LE(Nearest(r.multipliers[i], truth), r.summary.error_estimate + 1e-12) << i;
    EXPECT_NEAR(got[i], top[i], r.summary.error_estimate + 1e-12) << i;
  }
  // The unstable Meissner multiplier dominates: the verdict is "unstable".
  EXPECT_NEAR(r.max_abs_multiplier, top[0], 1e-10);
  EXPECT_GT(r.max_abs_multiplier, 1.3);
  EXPECT_FALSE(r.stable());
}

TEST(ArpackMonodromyTest, DominantMultipliersOfGearedShaftsEqualTheDenseExactPath) {
  // 60 DOFs, damped shafts (β = 2e-6 s) and mesh (600 N·s/m): one free rotation, so the dense
  // step propagators (the change of variables is not diagonal).
  const SystemModel model = GearedShafts(4, HandSpurWaveCore(600.0), 2e-6);
  FloquetOptions o;
  o.mesh_frequency_hz = kMeshHz;
  o.split_blocks = false;
  o.tolerance = 1e-10;
  o.method = FloquetMethod::kExactSteps;
  const FloquetResult dense = ComputeFloquet(model, o);
  ASSERT_TRUE(dense.summary.ok()) << dense.summary.message;
  o.method = FloquetMethod::kArpackMonodromy;
  o.arpack_nev = 8;
  const FloquetResult r = ComputeFloquet(model, o);
  ASSERT_TRUE(r.summary.ok()) << r.summary.message;
  EXPECT_EQ(r.summary.counters.at("expm_action"), 0);
  const double tol = r.summary.error_estimate + dense.summary.error_estimate + 1e-12;
  EXPECT_LE(r.summary.error_estimate, 1e-8);
  // The 8 (+ a conjugate) flexible multipliers and the 2 rigid ones (exactly 1).
  ASSERT_GE(r.multipliers.size(), 10);
  const std::vector<double> top = Moduli(dense.multipliers);
  const std::vector<double> got = Moduli(r.multipliers);
  for (int i = 0; i < r.multipliers.size(); ++i) {
    EXPECT_LE(Nearest(r.multipliers[i], dense.multipliers), tol) << i;
    EXPECT_NEAR(got[i], top[i], tol) << i;
  }
  EXPECT_NEAR(r.max_abs_multiplier, dense.max_abs_multiplier, tol);
}

TEST(ArpackMonodromyTest, SmoothCoefficientsUseMagnusPropagatorsWithinTheTolerance) {
  // 12-DOF pair, smooth core, mesh damping: against the dense adaptive Magnus path.
  const SystemModel model = HandPair(HandSmoothCore(0.2, 0.05, 900.0));
  FloquetOptions o;
  o.mesh_frequency_hz = kMeshHz;
  o.split_blocks = false;
  o.tolerance = 1e-9;
  o.method = FloquetMethod::kMagnus;
  const FloquetResult dense = ComputeFloquet(model, o);
  ASSERT_TRUE(dense.summary.ok()) << dense.summary.message;
  o.method = FloquetMethod::kArpackMonodromy;
  o.arpack_nev = 4;
  const FloquetResult r = ComputeFloquet(model, o);
  ASSERT_TRUE(r.summary.ok()) << r.summary.message;
  // The estimate is κ·ρ with ARPACK's residual ρ ≈ 0.1·tol (floquet.hpp): a sanity bound only
  // (8e-8 measured since the Magnus start follows ‖A‖T, issue 12); the accuracy is checked
  // against the dense path below.
  EXPECT_LE(r.summary.error_estimate, 1e-7);
  for (int i = 0; i < r.multipliers.size(); ++i) {
    EXPECT_LE(Nearest(r.multipliers[i], dense.multipliers),
              r.summary.error_estimate + dense.summary.error_estimate)
        << i;
  }
  EXPECT_NEAR(r.max_abs_multiplier, dense.max_abs_multiplier,
              r.summary.error_estimate + dense.summary.error_estimate);
}

TEST(ArpackMonodromyTest, BadArpackOptionsAreInvalidInput) {
  const PeriodicSecondOrderSystem sdof = MakeMeissnerSystem(1.3, 0.7, 0.5, 3.1);
  FloquetOptions o;
  o.method = FloquetMethod::kArpackMonodromy;
  o.arpack_nev = 0;
  EXPECT_THROWS_MESSAGE(ComputeFloquet(sdof, o), InvalidInput, "arpack_nev.*>= 1");
  o.arpack_nev = 3;  // > 2n = 2
  EXPECT_THROWS_MESSAGE(ComputeFloquet(sdof, o), InvalidInput, "arpack_nev.*<= 2n = 2");
  o.arpack_nev = 4;
  o.arpack_ncv = 5;
  EXPECT_THROWS_MESSAGE(ComputeFloquet(sdof, o), InvalidInput, "arpack_ncv");
  o.arpack_ncv = 0;
  o.arpack_max_iterations = 0;
  EXPECT_THROWS_MESSAGE(ComputeFloquet(sdof, o), InvalidInput, "arpack_max_iterations");
  FloquetOptions m;
  m.mesh_frequency_hz = kMeshHz;
  m.method = FloquetMethod::kArpackMonodromy;
  m.arpack_nev = 25;  // 2n = 24
  EXPECT_THROWS_MESSAGE(ComputeFloquet(HandPair(HandSpurWaveCore()), m), InvalidInput,
                        "arpack_nev.*<= 2n = 24");
}

TEST(ArpackMonodromyTest, ASmallStateGetsAllItsMultipliersFromTheSamePropagators) {
  // SDOF (state dimension 2 < nev + 2): Φ formed from the exact steps; closed form.
  const double T = 3.1;
  const PeriodicSecondOrderSystem sdof = MakeMeissnerSystem(1.3, 0.7, 0.5, T);
  FloquetOptions o;
  o.method = FloquetMethod::kArpackMonodromy;
  o.arpack_nev = 1;
  const FloquetResult r = ComputeFloquet(sdof, o);
  ASSERT_TRUE(r.summary.ok()) << r.summary.message;
  EXPECT_EQ(r.method_used, FloquetMethod::kArpackMonodromy);
  EXPECT_LE(MultiplierDistance(r.multipliers,
                               MeissnerMultipliers(MeissnerTrace(1.3, 0.7, 0.5 * T, 0.5 * T))),
            1e-12);
}

}  // namespace
}  // namespace geardyn::test
