/// @file
/// @brief Accuracy of the monodromy Floquet multiplier of nonlinear HB orbits of the
/// Blankenship & Kahraman (1995) oscillator (nonlinear_hb.hpp, "Stability"): the switch-split
/// Magnus-4 product against an independent GSL rk8pd integration (tolerance 1e-12) of the
/// variational equation y'' + 2ζ y' + (1 + α cos Ωt) c'(u(t)) y = 0 along the same orbit u(t)
/// (the HB harmonics summed in the right-hand side), and its convergence in the step count,
/// on a single-sided-impact orbit and on a back-contact orbit (several contact switches per
/// period). g is continuous at a switch, so no saltation matrix enters either computation.
#include <gsl/gsl_errno.h>
#include <gsl/gsl_odeiv2.h>
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <complex>
#include <numbers>

#include "analyses/nonlinear_hb/bk_parameter_sets.hpp"
#include "geardyn/analyses/nonlinear_hb.hpp"
#include "geardyn/analyses/nonlinear_hb_clearance.hpp"

namespace geardyn {
namespace {

struct Orbit {
  ClearanceOscillatorParameters p;
  double omega;
  VectorX x;  // Newton unknowns
};

/// Converged HB orbit at Ω from the contact guess (H = 32).
Orbit Solve(const ClearanceOscillatorParameters& p, double omega, const VectorX* guess) {
  NhbOptions o;
  o.harmonics = 32;
  NhbSolver solver(MakeClearanceOscillator(p), o, 32);
  Orbit orbit{p, omega, guess ? *guess : solver.ContactGuess(omega)};
  Status st;
  double rn;
  solver.Newton(orbit.x, omega, &st, &rn);
  EXPECT_EQ(st, Status::kSuccess) << "Ω = " << omega;
  return orbit;
}

struct VarOde {
  const Orbit* orbit;
  int H;
};

int VarRhs(double t, const double y[], double f[], void* params) {
  const VarOde& o = *static_cast<const VarOde*>(params);
  const VectorX& x = o.orbit->x;
  const double w = o.orbit->omega;
  double u = x[0];
  for (int k = 1; k <= o.H; ++k) {
    u += 2.0 * (x[2 * k - 1] * std::cos(k * w * t) - x[2 * k] * std::sin(k * w * t));
  }
  const ClearanceOscillatorParameters& p = o.orbit->p;
  const double dc = (u > 1.0 || (p.back_contact && u < -1.0)) ? 1.0 : 0.0;
  const double kt = (1.0 + p.alpha * std::cos(w * t)) * dc;
  // Two independent solutions (columns of Φ): y = [y1, y1', y2, y2'].
  f[0] = y[1];
  f[1] = -2.0 * p.zeta * y[1] - kt * y[0];
  f[2] = y[3];
  f[3] = -2.0 * p.zeta * y[3] - kt * y[2];
  return GSL_SUCCESS;
}

double GslMaxMultiplier(const Orbit& orbit) {
  VarOde ode{&orbit, static_cast<int>(orbit.x.size() - 1) / 2};
  gsl_odeiv2_system sys{VarRhs, nullptr, 4, &ode};
  gsl_odeiv2_driver* d =
      gsl_odeiv2_driver_alloc_y_new(&sys, gsl_odeiv2_step_rk8pd, 1e-4, 1e-12, 1e-12);
  const double T = 2.0 * std::numbers::pi / orbit.omega;
  double t = 0.0;
  double y[4] = {1.0, 0.0, 0.0, 1.0};
  gsl_odeiv2_driver_apply(d, &t, T, y);
  gsl_odeiv2_driver_free(d);
  Eigen::Matrix2d phi;
  phi << y[0], y[2], y[1], y[3];
  return Eigen::EigenSolver<Eigen::Matrix2d>(phi, false).eigenvalues().cwiseAbs().maxCoeff();
}

double EngineMaxMultiplier(const Orbit& orbit, int steps) {
  const int H = static_cast<int>(orbit.x.size() - 1) / 2;
  NhbOptions o;
  o.harmonics = H;
  o.monodromy_steps = steps;
  NhbSolver solver(MakeClearanceOscillator(orbit.p), o, H);
  return solver.MaxMultiplier(orbit.x, orbit.omega);
}

void CheckOrbit(const Orbit& orbit) {
  const double truth = GslMaxMultiplier(orbit);
  const double coarse = EngineMaxMultiplier(orbit, 32);
  const double fine = EngineMaxMultiplier(orbit, 128);
  const double standard = EngineMaxMultiplier(orbit, 0);  // max(64, 4H)
  // Documented tolerance: 1e-5 relative at the default step count (64 for H ≤ 16), 1e-6 at
  // 128 steps, and fourth-order-like convergence (32 → 128 steps: the error shrinks at least
  // 16-fold or sits at round-off).
  EXPECT_NEAR(standard, truth, 1e-5 * truth) << "Ω = " << orbit.omega;
  EXPECT_NEAR(fine, truth, 1e-6 * truth);
  EXPECT_LE(std::abs(fine - truth), std::max(std::abs(coarse - truth) / 16.0, 1e-9 * truth))
      << "coarse " << coarse << " fine " << fine << " GSL " << truth;
}

TEST(NonlinearHbMonodromy, SingleSidedImpactOrbitsMatchGslVariationalEquation) {
  ClearanceOscillatorParameters p;
  p.zeta = 0.05;
  p.alpha = 0.1;
  p.mean_force = 0.1;
  p.alternating_force = 0.03;
  // Contact loss on the resonant branch (two switches per period) and full contact below it.
  for (double omega : {0.80, 0.95, 1.0}) {
    const Orbit orbit = Solve(p, omega, nullptr);
    CheckOrbit(orbit);
  }
}

TEST(NonlinearHbMonodromy, BackContactOrbitMatchesGslVariationalEquation) {
  const ClearanceOscillatorParameters p = testing::BkBackContactSet();
  // The back-contact branch of bk_jumps_test; its last point (Ω ≈ 0.42) has four switches per
  // period (front contact → gap → back contact → gap).
  NhbOptions o;
  o.harmonics = 16;  // the orbit is any trigonometric polynomial here
  o.stability = NhbStabilityMethod::kNone;
  const NhbCurve curve =
      TraceNonlinearHarmonicBalance(MakeClearanceOscillator(p), o, testing::BkBackContactTrace());
  ASSERT_TRUE(curve.summary.ok()) << curve.summary.BriefReport();
  const NhbPoint& last = curve.points.back();
  ASSERT_LT(last.minimum[0], -1.0) << "not a back-contact orbit";
  const Orbit orbit{p, last.omega, testing::PointUnknowns(last)};
  CheckOrbit(orbit);
}

}  // namespace
}  // namespace geardyn
