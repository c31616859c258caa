// Numerical stress suite, part A — Floquet (ComputeFloquet), issue 16: operating points exactly
// on tongue edges, zero damping, mesh frequencies of 1e-3 Hz and 1e6 Hz, very stiff systems,
// non-finite coefficients and overflowing growth, and unit scaling. Each case gives the right
// multipliers within the reported error estimate, or an honest status/verdict; never a NaN or a
// "stable" verdict when |λ| > 1 beyond the error.
//
// Truths (independent of the Floquet engine):
// * Meissner (rectangular-wave stiffness): the exact monodromy T(k_lo, τ_lo)·T(k_hi, τ_hi) of
//   closed-form 2×2 transfer matrices; tongue edges |tr Φ| = 2 found by bisection on that trace.
// * The torsional gear pair reduces exactly to a Meissner equation for δ = r1θ1 + r2θ2
//   (δ'' + c s δ' + k(θ) s δ = 0, s = r1²/I1 + r2²/I2), plus a rigid rotation (multipliers 1).
// * Mathieu x'' + (δ + ε cos t)x = 0: a classical RK4 monodromy in this file (4 000 steps, error
//   ≈ 1e-12) and its tongue edges by bisection (a different method from Magnus/Hill/GSL).
// * Liouville: λ1 λ2 = det Φ = exp(−∫ tr C/M dt) = exp(−cT) for an SDOF system.
// * Overflowing growth: ln|λ_max| = x + ln(|2 cos a + sin a (v/w − w/v)|/2) + O(e^{−2x}) for the
//   hyperbolic Meissner step (x = vτ_lo), the log-domain closed form of the trace.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <ostream>
#include <string>
#include <vector>

#include "geardyn/analyses/floquet.hpp"
#include "geardyn/analyses/floquet_system.hpp"
#include "geardyn/common/errors.hpp"
#include "stress/stress_cases.hpp"
#include "support/expect_throws.hpp"

namespace geardyn::stress {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

struct FloquetCase {
  std::string name;
  std::function<FloquetResult()> run;
  /// Asserts the answer or the status against the truth.
  std::function<void(const FloquetResult&)> check;
};
void PrintTo(const FloquetCase& c, std::ostream* os) { *os << c.name; }

// ---------------------------------------------------------------- truths

// Meissner x'' + k(t)x = 0 (m = 1), k_hi on the first `duty` of T: exact monodromy.
Eigen::Matrix2d MeissnerMonodromy(double k_hi, double k_lo, double duty, double T, double c = 0.0) {
  return DampedTransfer(k_lo, 0.5 * c, (1 - duty) * T) * DampedTransfer(k_hi, 0.5 * c, duty * T);
}
double MeissnerMaxAbs(double k_hi, double k_lo, double duty, double T, double c = 0.0) {
  return MeissnerMonodromy(k_hi, k_lo, duty, T, c).eigenvalues().cwiseAbs().maxCoeff();
}

// Classical RK4 monodromy of x'' + c x' + (δ + ε cos(2πt/T)) x = 0.
Eigen::Matrix2d MathieuRk4(double delta, double eps, double T, double c = 0.0, int steps = 4000) {
  const double h = T / steps, w = kTwoPi / T;
  const auto f = [&](double t, const Eigen::Vector2d& y) {
    return Eigen::Vector2d(y(1), -c * y(1) - (delta + eps * std::cos(w * t)) * y(0));
  };
  Eigen::Matrix2d phi;
  for (int col = 0; col < 2; ++col) {
    Eigen::Vector2d y = Eigen::Vector2d::Unit(col);
    for (int i = 0; i < steps; ++i) {
      const double t = i * h;
      const Eigen::Vector2d k1 = f(t, y), k2 = f(t + h / 2, y + h / 2 * k1),
                            k3 = f(t + h / 2, y + h / 2 * k2), k4 = f(t + h, y + h * k3);
      y += h / 6 * (k1 + 2 * k2 + 2 * k3 + k4);
    }
    phi.col(col) = y;
  }
  return phi;
}

// RK4 with 8 000 and 16 000 steps, Richardson-extrapolated (error O(h⁶) ≈ 1e-16 here): the
// Mathieu truth, accurate enough that |λ| at its tongue edges is 1 within ≈ 3e-8.
Eigen::Matrix2d MathieuTruth(double delta, double eps, double T, double c = 0.0) {
  return (16.0 * MathieuRk4(delta, eps, T, c, 16000) - MathieuRk4(delta, eps, T, c, 8000)) / 15.0;
}

// Bisection of a sign change of g on [lo, hi] to machine precision.
double Bisect(const std::function<double(double)>& g, double lo, double hi) {
  const bool lo_positive = g(lo) > 0;
  if (lo_positive == (g(hi) > 0)) return kNaN;  // no sign change: the case fails on a NaN truth
  for (int i = 0; i < 200 && hi - lo > 4 * std::numeric_limits<double>::epsilon() * std::abs(hi);
       ++i) {
    const double mid = 0.5 * (lo + hi);
    ((g(mid) > 0) == lo_positive ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

// ---------------------------------------------------------------- checks

// The documented verdict rules (floquet_verdict.hpp), as invariants of every result.
void ExpectHonestVerdict(const FloquetResult& r) {
  const double e = r.summary.error_estimate;
  const bool clean_status = r.summary.status == Status::kSuccess;
  if (r.verdict == FloquetVerdict::kStable) {
    EXPECT_TRUE(clean_status) << "stable with status " << StatusName(r.summary.status);
    EXPECT_TRUE(AllFinite(r.multipliers)) << "stable with a non-finite multiplier";
    EXPECT_LE(r.max_abs_multiplier, 1.0 + e) << "stable with max|λ| beyond 1 + e";
  }
  if (r.verdict == FloquetVerdict::kUnstable) {
    EXPECT_GT(r.max_abs_multiplier - e, 1.0) << "unstable within the error";
  }
  if (r.summary.status != Status::kSuccess && r.summary.status != Status::kToleranceNotMet) {
    EXPECT_EQ(r.verdict, FloquetVerdict::kUndetermined);
  }
  if (std::isnan(e) || std::isnan(r.max_abs_multiplier)) {
    EXPECT_EQ(r.verdict, FloquetVerdict::kUndetermined);
  }
  if (!r.summary.ok()) {
    EXPECT_FALSE(r.summary.message.empty()) << "a status without a message";
  }
}

// A successful result has finite exponents and estimate and no NaN anywhere; a multiplier may
// be ±inf only as an overflowing growth, i.e. with a finite exponent of positive real part
// (floquet_verdict.hpp).
void ExpectFiniteIfOk(const FloquetResult& r) {
  if (r.summary.status == Status::kSuccess || r.summary.status == Status::kToleranceNotMet) {
    EXPECT_TRUE(AllFinite(r.exponents)) << r.exponents.transpose();
    EXPECT_TRUE(std::isfinite(r.summary.error_estimate));
    ASSERT_EQ(r.multipliers.size(), r.exponents.size());
    for (Eigen::Index i = 0; i < r.multipliers.size(); ++i) {
      const std::complex<double> l = r.multipliers[i];
      EXPECT_FALSE(std::isnan(l.real()) || std::isnan(l.imag())) << "NaN multiplier " << l;
      if (!std::isfinite(std::abs(l))) {
        EXPECT_GT(r.exponents[i].real(), 0.0) << "inf multiplier without growth: " << l;
      }
    }
    EXPECT_FALSE(std::isnan(r.max_abs_multiplier));
    EXPECT_EQ(r.max_abs_multiplier, MaxAbs(r.multipliers));
  }
}

// Computed max|λ| against a truth known to `truth_tol`, within the reported error; and the
// verdict must agree with the truth wherever the truth is decided beyond both errors.
void ExpectMaxAbsNear(const FloquetResult& r, double truth, double truth_tol) {
  // kToleranceNotMet is an honest outcome (its verdict is then undetermined unless unstable
  // beyond the estimate), but its estimate must still bound the error.
  ASSERT_TRUE(r.summary.status == Status::kSuccess || r.summary.status == Status::kToleranceNotMet)
      << r.summary.BriefReport();
  if (r.summary.status == Status::kToleranceNotMet) {
    EXPECT_NE(r.verdict, FloquetVerdict::kStable);
  }
  const double e = r.summary.error_estimate;
  EXPECT_NEAR(r.max_abs_multiplier, truth, e + truth_tol)
      << "error estimate " << e << ", truth ± " << truth_tol;
  SCOPED_TRACE(::testing::Message() << "max|λ| " << r.max_abs_multiplier << ", e " << e
                                    << ", truth " << truth << " ± " << truth_tol);
  if (truth > 1.0 + 2 * (e + truth_tol) && r.summary.ok()) {
    EXPECT_EQ(r.verdict, FloquetVerdict::kUnstable);
  }
  // "Unstable" must be possible under the truth: the true max|λ| may exceed 1.
  if (r.verdict == FloquetVerdict::kUnstable) {
    EXPECT_GT(truth + truth_tol, 1.0) << "unstable where the truth is |λ| ≤ 1";
  }
}

FloquetOptions Opts(FloquetMethod method, double mesh_hz = 1.0, double tol = 1e-10) {
  FloquetOptions o;
  o.method = method;
  o.mesh_frequency_hz = mesh_hz;
  o.tolerance = tol;
  o.list_undamped_modes = false;
  return o;
}

// The elastic multipliers of the pair: drop the two rigid ones (exactly 1).
VectorXc Elastic(const FloquetResult& r) {
  std::vector<std::complex<double>> kept;
  int dropped = 0;
  for (Eigen::Index i = 0; i < r.multipliers.size(); ++i) {
    if (dropped < 2 && r.multipliers[i] == std::complex<double>(1.0, 0.0)) {
      ++dropped;
      continue;
    }
    kept.push_back(r.multipliers[i]);
  }
  return Eigen::Map<VectorXc>(kept.data(), static_cast<Eigen::Index>(kept.size()));
}

// Greedy distance between two multiplier sets of equal size.
double SetDistance(const VectorXc& a, const Eigen::Vector2cd& b) {
  if (a.size() != 2) return std::numeric_limits<double>::infinity();
  return std::min(std::max(std::abs(a[0] - b[0]), std::abs(a[1] - b[1])),
                  std::max(std::abs(a[0] - b[1]), std::abs(a[1] - b[0])));
}

// ---------------------------------------------------------------- the table

std::vector<FloquetCase> Cases() {
  std::vector<FloquetCase> cases;
  const FloquetMethod kMethods[] = {FloquetMethod::kAuto, FloquetMethod::kMagnus,
                                    FloquetMethod::kOdeStepper};
  const auto method_name = [](FloquetMethod m) { return std::string(ToString(m)); };

  // 1. Meissner, T = 2π, duty ½, k = δ(1 ± 0.3): the first tongue around δ = ¼ (f_m = 2 f_n).
  // At each edge exactly (|tr| = 2: a double multiplier ±1, |λ| = 1 to √ε of the edge's
  // position) and 1e-6 of δ inside and outside.
  {
    const double eps = 0.3, T = kTwoPi;
    const auto g = [=](double d) {
      return std::abs(MeissnerMonodromy(d * (1 + eps), d * (1 - eps), 0.5, T).trace()) - 2.0;
    };
    const double lower = Bisect(g, 0.1, 0.25), upper = Bisect(g, 0.25, 0.45);
    struct Point {
      const char* name;
      double delta;
    };
    const Point points[] = {{"lower_edge", lower},
                            {"upper_edge", upper},
                            {"lower_edge_inside", lower * (1 + 1e-6)},
                            {"lower_edge_outside", lower * (1 - 1e-6)},
                            {"upper_edge_inside", upper * (1 - 1e-6)},
                            {"upper_edge_outside", upper * (1 + 1e-6)}};
    for (const Point& p : points) {
      for (const FloquetMethod m : kMethods) {
        const double d = p.delta;
        // |λ| of the closed form is exact to ≈ √(ε·|tr|) ≈ 2e-8 next to a double root.
        const double truth = MeissnerMaxAbs(d * (1 + eps), d * (1 - eps), 0.5, T);
        cases.push_back({"meissner_" + std::string(p.name) + "_" + method_name(m),
                         [=] {
                           return ComputeFloquet(
                               MakeMeissnerSystem(d * (1 + eps), d * (1 - eps), 0.5, T), Opts(m));
                         },
                         [=](const FloquetResult& r) { ExpectMaxAbsNear(r, truth, 3e-8); }});
      }
    }
  }

  // 2. Mathieu x'' + (δ + 0.4 cos t)x = 0, first tongue edges from the RK4 truth (smooth
  // coefficients: kAuto → Magnus; Hill; GSL). The edges are bisected lazily (first use), so that
  // listing the tests stays fast.
  {
    struct Point {
      const char* name;
      int which;  // 0 lower edge, 1 upper edge, 2 mid-tongue, 3 outside (δ = 0.8)
    };
    for (const Point& p : {Point{"lower_edge", 0}, Point{"upper_edge", 1}, Point{"inside", 2},
                           Point{"outside", 3}}) {
      for (const FloquetMethod m :
           {FloquetMethod::kAuto, FloquetMethod::kHill, FloquetMethod::kOdeStepper}) {
        const int which = p.which;
        const auto delta = [which] {
          static const std::pair<double, double> edges = [] {
            const auto g = [](double d) {
              return std::abs(MathieuTruth(d, 0.4, kTwoPi).trace()) - 2.0;
            };
            return std::make_pair(Bisect(g, 0.0, 0.25), Bisect(g, 0.25, 0.6));
          }();
          return which == 0   ? edges.first
                 : which == 1 ? edges.second
                 : which == 2 ? 0.5 * (edges.first + edges.second)
                              : 0.8;
        };
        cases.push_back({"mathieu_" + std::string(p.name) + "_" + method_name(m),
                         // Hill at 1e-10 on an edge raises H to its cap 199 (20 s: the
                         // √-sensitivity of a double root): ask 1e-7 there.
                         [=] {
                           return ComputeFloquet(
                               MakeMathieuSystem(delta(), 0.4, kTwoPi),
                               Opts(m, 1.0, m == FloquetMethod::kHill ? 1e-7 : 1e-10));
                         },
                         [=](const FloquetResult& r) {
                           const Eigen::Matrix2d phi = MathieuTruth(delta(), 0.4, kTwoPi);
                           const double truth = phi.eigenvalues().cwiseAbs().maxCoeff();
                           // The truth's trace is good to ≈ 1e-13; at an edge (double root) |λ|
                           // moves by the square root of that: ±1e-6 (2e-7 measured). Away from
                           // edges 1e-11.
                           ExpectMaxAbsNear(r, truth, which <= 1 ? 1e-6 : 1e-11);
                           // The trace λ1 + λ2 is well conditioned even at a double root.
                           ASSERT_EQ(r.multipliers.size(), 2);
                           EXPECT_NEAR(r.multipliers.sum().real(), phi.trace(),
                                       2 * r.summary.error_estimate + 1e-10);
                         }});
      }
    }
  }

  // 3. Zero damping in a stable region: multipliers on the unit circle. The verdict must be
  // stable-and-marginal or undetermined; never unstable; |λ| = 1 within the estimate; λ1λ2 = 1.
  for (const FloquetMethod m : kMethods) {
    cases.push_back(
        {"undamped_stable_marginal_" + method_name(m),
         [=] { return ComputeFloquet(MakeMeissnerSystem(0.65, 0.35, 0.5, kTwoPi), Opts(m)); },
         [](const FloquetResult& r) {
           ASSERT_TRUE(r.summary.ok()) << r.summary.BriefReport();
           EXPECT_NE(r.verdict, FloquetVerdict::kUnstable);
           if (r.verdict == FloquetVerdict::kStable) {
             EXPECT_TRUE(r.marginal);
           }
           EXPECT_NEAR(r.max_abs_multiplier, 1.0, r.summary.error_estimate + 1e-12);
           EXPECT_NEAR(std::abs(r.multipliers.prod()), 1.0, 2 * r.summary.error_estimate + 1e-12);
         }});
  }

  // 4. The torsional gear pair at extreme mesh frequencies, exact steps vs the closed form:
  // f_m = 1e-3 Hz (≈ 1.6e7 rad of oscillation per period; the closed form's own phase error is
  // ≈ ε·ωT ≈ 4e-9) and f_m = 1e6 Hz (0.016 rad per period), undamped and damped.
  for (const double fm : {1e-3, 1e6}) {
    for (const double cm : {0.0, 200.0}) {
      TorsionalPair p;
      p.c_m = cm;
      const double omega = std::sqrt(p.k_hi * p.s());
      const double truth_tol = 50 * std::numeric_limits<double>::epsilon() * omega / fm + 1e-13;
      const std::string name = std::string("pair_exact_steps_fm_") + (fm < 1 ? "1em3" : "1e6") +
                               (cm > 0 ? "_damped" : "_undamped");
      cases.push_back(
          {name,
           [=] {
             return ComputeFloquet(MakeTorsionalPairModel(p), Opts(FloquetMethod::kAuto, fm));
           },
           [=](const FloquetResult& r) {
             ASSERT_TRUE(r.summary.ok()) << r.summary.BriefReport();
             EXPECT_EQ(r.method_used, FloquetMethod::kExactSteps);
             const VectorXc elastic = Elastic(r);
             const Eigen::Vector2cd truth = PairElasticMultipliers(p, fm);
             EXPECT_LE(SetDistance(elastic, truth), r.summary.error_estimate + truth_tol)
                 << "computed " << elastic.transpose() << "\ntruth " << truth.transpose()
                 << "\nestimate " << r.summary.error_estimate;
           }});
    }
  }

  // 5. The same pair with a smooth mesh stiffness k(1 + 0.2 cos θ) at 1e-3 Hz: Magnus needs
  // ≈ ωT/π ≈ 5e6 steps, beyond its 65 536 cap. Either an honest non-success status (then
  // undetermined), or multipliers with λ1λ2 = 1 (Liouville, undamped) within the estimate.
  // At 1e6 Hz the same core is trivial: |λ| = 1 and λ1λ2 = 1.
  for (const double fm : {1e-3, 1e6}) {
    cases.push_back(
        {std::string("pair_smooth_magnus_fm_") + (fm < 1 ? "1em3" : "1e6"),
         [=] {
           const TorsionalPair p;
           SystemBuilder b;
           Vector6 m1, m2;
           m1 << 1, 1, 1, 1e-3, 1e-3, p.I1;
           m2 << 2, 2, 2, 3e-3, 3e-3, p.I2;
           const BodyIndex a = b.AddBody("pinion", DiagMass6(m1)),
                           c = b.AddBody("gear", DiagMass6(m2));
           Matrix2x12 G = Matrix2x12::Zero();
           G(0, 5) = p.r1;
           G(0, 11) = p.r2;
           MatrixX cosines = MatrixX::Zero(3, 1);
           cosines(0, 0) = 0.2 * p.k_lo;
           b.AddMesh("mesh", a, c, G,
                     LinearMeshCore(
                         MeshCoreLevel::kTorsional,
                         FourierCoefficient::FromCosSin((VectorX(3) << p.k_lo, 0.0, 0.0).finished(),
                                                        cosines, MatrixX::Zero(3, 1)),
                         0.01));
           const SystemModel full = b.Build();
           const SystemModel model = full.Restrict(
               {full.dof_map().dof(a, BodyDof::kThetaZ), full.dof_map().dof(c, BodyDof::kThetaZ)});
           return ComputeFloquet(model, Opts(FloquetMethod::kMagnus, fm, 1e-8));
         },
         [](const FloquetResult& r) {
           if (!r.summary.ok()) {
             EXPECT_EQ(r.verdict, FloquetVerdict::kUndetermined) << r.summary.BriefReport();
             return;
           }
           const VectorXc elastic = Elastic(r);
           ASSERT_EQ(elastic.size(), 2);
           EXPECT_NEAR(std::abs(elastic.prod()), 1.0, 2 * r.summary.error_estimate + 1e-12);
         }});
  }

  // 6. Very stiff SDOF systems (many steps per period): Meissner with √k·T = 1e4 rad (exact
  // steps, closed form) and Mathieu with δ = 1e6 (√δ·T ≈ 6 283 rad; Magnus/GSL), undamped and
  // damped (Liouville λ1λ2 = e^{−cT}).
  {
    const double T = 1.0, k = 1e8;  // √k·T = 1e4
    for (const FloquetMethod m : {FloquetMethod::kAuto, FloquetMethod::kMagnus}) {
      cases.push_back(
          {"stiff_meissner_" + method_name(m),
           [=] { return ComputeFloquet(MakeMeissnerSystem(1.1 * k, 0.9 * k, 0.4, T), Opts(m)); },
           [=](const FloquetResult& r) {
             if (!r.summary.ok()) {
               EXPECT_EQ(r.verdict, FloquetVerdict::kUndetermined);
               return;
             }
             const double truth = MeissnerMaxAbs(1.1 * k, 0.9 * k, 0.4, T);
             ExpectMaxAbsNear(r, truth, 1e-10);
           }});
    }
    for (const double c : {0.0, 0.3}) {
      for (const FloquetMethod m : {FloquetMethod::kAuto, FloquetMethod::kOdeStepper}) {
        cases.push_back(
            {std::string("stiff_mathieu_") + (c > 0 ? "damped_" : "undamped_") + method_name(m),
             [=] {
               return ComputeFloquet(MakeMathieuSystem(1e6, 1e5, kTwoPi, c), Opts(m, 1.0, 1e-8));
             },
             [=](const FloquetResult& r) {
               if (!r.summary.ok()) {
                 EXPECT_EQ(r.verdict, FloquetVerdict::kUndetermined) << r.summary.BriefReport();
                 return;
               }
               EXPECT_NEAR(std::abs(r.multipliers.prod()), std::exp(-c * kTwoPi),
                           2 * r.summary.error_estimate + 1e-10);
             }});
      }
    }
  }

  // 8. Overflowing growth: k_lo = −1e6 for τ = ½ s (e^{500}, finite) and for τ = 1 s (e^{1000}:
  // |λ| overflows). The exponent must stay finite and right (log-domain closed form) and the
  // verdict unstable — an inf multiplier with a finite exponent is growth, not failure.
  for (const double T : {1.0, 2.0}) {
    const double k_hi = 4.0, k_lo = -1e6, duty = 0.5;
    const double w = std::sqrt(k_hi), v = std::sqrt(-k_lo), a = w * duty * T,
                 x = v * (1 - duty) * T;
    const double log_max =
        x + std::log(std::abs(2 * std::cos(a) + std::sin(a) * (v / w - w / v)) / 2);
    cases.push_back({std::string("overflowing_growth_e") + (T < 1.5 ? "500" : "1000"),
                     [=] {
                       return ComputeFloquet(MakeMeissnerSystem(k_hi, k_lo, duty, T),
                                             Opts(FloquetMethod::kAuto));
                     },
                     [=](const FloquetResult& r) {
                       EXPECT_EQ(r.verdict, FloquetVerdict::kUnstable) << r.summary.BriefReport();
                       ASSERT_GE(r.exponents.size(), 1);
                       EXPECT_TRUE(std::isfinite(r.exponents[0].real())) << r.exponents[0];
                       EXPECT_NEAR(r.exponents[0].real() * T, log_max, 1e-9 * log_max);
                     }});
  }

  // 9. Scaling invariance: the pair in SI and in mm–t–s (lengths ×1e3, masses ×1e-3) at a mesh
  // frequency on its principal tongue (f_m = 2 f_n) and off it, undamped and damped: the same
  // multipliers within the two estimates, and both equal to the closed form.
  for (const double ratio : {2.0, 1.37}) {
    for (const double cm : {0.0, 300.0}) {
      TorsionalPair si;
      si.c_m = cm;
      const double fn = std::sqrt(0.5 * (si.k_hi + si.k_lo) * si.s()) / kTwoPi;
      const double fm = ratio * fn;
      const std::string name = std::string("scaling_mm_t_s_") +
                               (ratio == 2.0 ? "on_tongue" : "off_tongue") +
                               (cm > 0 ? "_damped" : "_undamped");
      cases.push_back({name,
                       [=] {
                         return ComputeFloquet(MakeTorsionalPairModel(si.InMillimetreTonneSecond()),
                                               Opts(FloquetMethod::kAuto, fm));
                       },
                       [=](const FloquetResult& r) {
                         ASSERT_TRUE(r.summary.ok()) << r.summary.BriefReport();
                         const FloquetResult ref = ComputeFloquet(MakeTorsionalPairModel(si),
                                                                  Opts(FloquetMethod::kAuto, fm));
                         ASSERT_TRUE(ref.summary.ok());
                         EXPECT_EQ(r.verdict, ref.verdict);
                         EXPECT_NEAR(r.max_abs_multiplier, ref.max_abs_multiplier,
                                     r.summary.error_estimate + ref.summary.error_estimate + 1e-13);
                         EXPECT_LE(SetDistance(Elastic(r), PairElasticMultipliers(si, fm)),
                                   r.summary.error_estimate + 1e-12);
                       }});
    }
  }
  return cases;
}

// The RK4 tongue edges of the Mathieu cases against the perturbation series
// δ = ¼ ∓ ε/2 − ε²/8 ± ε³/32 (Nayfeh & Mook 1979, Eq. 5.2.22), good to O(ε⁴) = 0.026: the truth
// of those cases is itself checked by a third source.
TEST(FloquetStressTruth, MathieuRk4EdgesMatchThePerturbationSeries) {
  const double eps = 0.4, T = kTwoPi;
  const auto g = [=](double d) { return std::abs(MathieuRk4(d, eps, T).trace()) - 2.0; };
  const double e4 = eps * eps * eps * eps;
  EXPECT_NEAR(Bisect(g, 0.0, 0.25), 0.25 - eps / 2 - eps * eps / 8 + eps * eps * eps / 32, e4);
  EXPECT_NEAR(Bisect(g, 0.25, 0.6), 0.25 + eps / 2 - eps * eps / 8 - eps * eps * eps / 32, e4);
}

// Non-finite coefficients: K(t) turns NaN or +inf in the second half of the period. That is bad
// input from the caller's callback: the documented answer is InvalidInput naming K(t) (never a
// NaN monodromy or a verdict), for the default path and the GSL reference path.
TEST(FloquetStressNonFinite, NonFiniteCoefficientsThrowInvalidInput) {
  for (const double bad :
       {kNaN, std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()}) {
    for (const FloquetMethod m :
         {FloquetMethod::kAuto, FloquetMethod::kMagnus, FloquetMethod::kOdeStepper}) {
      SCOPED_TRACE(std::string("K = ") + std::to_string(bad) + ", method " + ToString(m));
      PeriodicSecondOrderSystem s = MakeMathieuSystem(0.3, 0.1, kTwoPi);
      s.stiffness_harmonics.clear();
      s.damping_harmonics.clear();
      s.coefficients = [bad](double t, MatrixX* K, MatrixX* C) {
        K->setConstant(1, 1, t > 0.5 * kTwoPi ? bad : 0.3);
        C->setZero(1, 1);
      };
      EXPECT_THROWS_MESSAGE(ComputeFloquet(s, Opts(m)), InvalidInput, "K\\(t\\)");
    }
  }
}

class FloquetStress : public ::testing::TestWithParam<FloquetCase> {};

TEST_P(FloquetStress, RightMultipliersOrHonestStatus) {
  const FloquetCase& c = GetParam();
  const FloquetResult r = c.run();
  // The outcome, for the report (--gtest_output=json lists these properties per case).
  RecordProperty("outcome_status", StatusName(r.summary.status));
  RecordProperty("verdict", ToString(r.verdict));
  RecordProperty("message", r.summary.message);
  RecordProperty("method", ToString(r.method_used));
  RecordProperty("max_abs", ::testing::PrintToString(r.max_abs_multiplier));
  RecordProperty("error_estimate", ::testing::PrintToString(r.summary.error_estimate));
  ExpectHonestVerdict(r);
  ExpectFiniteIfOk(r);
  c.check(r);
}

INSTANTIATE_TEST_SUITE_P(Cases, FloquetStress, ::testing::ValuesIn(Cases()),
                         [](const ::testing::TestParamInfo<FloquetCase>& param_info) {
                           return param_info.param.name;
                         });

}  // namespace
}  // namespace geardyn::stress
