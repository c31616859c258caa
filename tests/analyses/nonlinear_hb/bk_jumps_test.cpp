/// @file
/// @brief Jump frequencies and amplitudes of the Blankenship & Kahraman (1995) oscillator
/// x'' + 2ζx' + (1 + α cos Ωt) g(x) = F_m + F_a cos(Ωt + φ) (spec 02; issue 6) from the
/// nonlinear HB continuation against slow up- and down-sweeps of an independent GSL rk8pd
/// time integration (tests/analyses/nonlinear_hb/bk_time_integration.hpp).
///
/// Two parameter sets: single-sided impacts (x never below −1) and back-side contact (the
/// upper branch of the softened resonance reaches x < −1). The parameter sets are chosen in the
/// ranges of B&K 1995 (ζ = 0.05…0.1, α ≤ 0.2, F_m = 0.1) — the paper's OCR is not in
/// shared/references, so its exact sets are not reproduced; the truth here is the time integration,
/// not the paper.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "analyses/nonlinear_hb/bk_parameter_sets.hpp"
#include "analyses/nonlinear_hb/bk_time_integration.hpp"
#include "geardyn/analyses/nonlinear_hb.hpp"
#include "geardyn/analyses/nonlinear_hb_clearance.hpp"

namespace geardyn {
namespace {

using testing::BkParameters;
using testing::BkState;
using testing::BkStats;
using testing::BkSweep;

/// RMS and max of coordinate 0 on the stable HB branch crossing Ω nearest to `rms_hint`.
bool StableBranchAt(const NhbCurve& curve, double omega, double rms_hint, double* rms,
                    double* maximum) {
  double best = 1e300;
  for (size_t i = 0; i + 1 < curve.points.size(); ++i) {
    const NhbPoint& p = curve.points[i];
    const NhbPoint& q = curve.points[i + 1];
    if (p.stable != FloquetVerdict::kStable || q.stable != FloquetVerdict::kStable ||
        p.branch != q.branch) {
      continue;
    }
    if ((p.omega - omega) * (q.omega - omega) > 0 || p.omega == q.omega) continue;
    const double w = (omega - p.omega) / (q.omega - p.omega);
    const double r = p.rms[0] + w * (q.rms[0] - p.rms[0]);
    if (std::abs(r - rms_hint) < best) {
      best = std::abs(r - rms_hint);
      *rms = r;
      *maximum = p.maximum[0] + w * (q.maximum[0] - p.maximum[0]);
    }
  }
  return best < 1e300;
}

/// Index of the first sweep step whose RMS differs from the previous one by more than 20 %.
int JumpIndex(const std::vector<BkStats>& sweep) {
  for (size_t i = 1; i < sweep.size(); ++i) {
    if (std::abs(sweep[i].rms - sweep[i - 1].rms) > 0.2 * sweep[i - 1].rms) return int(i);
  }
  return -1;
}

std::vector<double> Range(double from, double to, double step) {
  std::vector<double> w;
  const int n = int(std::round(std::abs(to - from) / step));
  for (int i = 0; i <= n; ++i) w.push_back(from + (to > from ? 1 : -1) * i * step);
  return w;
}

/// Checks one sweep direction: the TI jump lies within 1 % of the HB fold, and RMS and max
/// just before and just after the jump match the HB stable branches within 1 %.
void CheckSweep(const NhbCurve& curve, const std::vector<BkStats>& sweep, bool up) {
  const int j = JumpIndex(sweep);
  ASSERT_GT(j, 0) << (up ? "up" : "down") << "-sweep: no jump in the time integration";
  const double omega_ti = 0.5 * (sweep[j - 1].omega + sweep[j].omega);
  const NhbJump* jump = nullptr;
  for (const NhbJump& jp : curve.jumps) {
    if (jp.up_sweep == up) jump = &jp;
  }
  ASSERT_NE(jump, nullptr) << (up ? "up" : "down") << "-sweep jump missing in the HB curve";
  EXPECT_NEAR(jump->omega, omega_ti, 0.01 * omega_ti) << (up ? "up" : "down");
  for (int side : {j - 1, j}) {
    double rms = 0, mx = 0;
    ASSERT_TRUE(StableBranchAt(curve, sweep[side].omega, sweep[side].rms, &rms, &mx));
    EXPECT_NEAR(rms, sweep[side].rms, 0.01 * sweep[side].rms) << "Ω = " << sweep[side].omega;
    EXPECT_NEAR(mx, sweep[side].maximum, 0.01 * std::abs(sweep[side].maximum))
        << "Ω = " << sweep[side].omega;
  }
}

TEST(NonlinearHbBkOscillator, SingleSidedImpactsJumpsMatchTimeIntegration) {
  const ClearanceOscillatorParameters p = testing::BkSingleSidedSet();
  NhbOptions options;
  options.harmonics = 16;
  NhbContinuationOptions c;
  c.omega_start = 0.65;
  c.omega_end = 1.05;
  c.max_step = 0.1;
  c.max_tangent_angle = 0.5;
  const NhbCurve curve = TraceNonlinearHarmonicBalance(MakeClearanceOscillator(p), options, c);
  ASSERT_TRUE(curve.summary.ok()) << curve.summary.BriefReport();
  ASSERT_EQ(curve.folds.size(), 2u);
  // Single-sided: the back flank (x < −1) is never reached.
  for (const NhbPoint& pt : curve.points) EXPECT_GT(pt.minimum[0], -1.0);

  const BkParameters bk{p.zeta, p.alpha, p.mean_force, p.alternating_force, 0.0, true};
  // Up-sweep: from the static equilibrium at Ω = 0.70 (below the bistable band, one branch
  // only), coarse steps to 0.87, then 0.35 % steps through the fold near Ω = 0.90.
  // Down-sweep: from Ω = 1.0 (above the band) down to 0.80, then fine steps through the fold
  // near Ω = 0.76. 120 periods per frequency, statistics of the last 4.
  BkState low{1.0 + p.mean_force, 0.0, 0.0};
  testing::BkIntegrate(bk, 0.70, 300, 0, low, nullptr);
  BkSweep(bk, Range(0.70, 0.86, 0.02), low, 80, 1, &low);
  const auto up = BkSweep(bk, Range(0.87, 0.93, 0.003), low, 120, 4);
  CheckSweep(curve, up, true);
  BkState high{1.0 + p.mean_force, 0.0, 0.0};
  testing::BkIntegrate(bk, 1.0, 300, 0, high, nullptr);
  BkSweep(bk, Range(1.0, 0.81, 0.02), high, 80, 1, &high);
  const auto down = BkSweep(bk, Range(0.80, 0.74, 0.003), high, 120, 4);
  CheckSweep(curve, down, false);
}

/// Back-side contact (B&K's "double-sided impacts"): with F_a > F_m and ζ = 0.08 the
/// softening resonance of the contact-loss branch sits near Ω ≈ 0.5; its upper branch reaches
/// the back flank (x < −1) and ends at an up-sweep jump near Ω = 0.548 onto a branch with
/// single-sided impacts only, whose down-sweep jump near Ω = 0.484 lands back on the
/// back-contact branch. Truth: slow GSL sweeps as above.
TEST(NonlinearHbBkOscillator, BackSideContactJumpsMatchTimeIntegration) {
  const ClearanceOscillatorParameters p = testing::BkBackContactSet();
  NhbOptions options;
  options.harmonics = 16;
  const NhbCurve curve = TraceNonlinearHarmonicBalance(MakeClearanceOscillator(p), options,
                                                       testing::BkBackContactTrace());
  ASSERT_TRUE(curve.summary.ok()) << curve.summary.BriefReport();
  ASSERT_EQ(curve.folds.size(), 2u);
  ASSERT_EQ(curve.jumps.size(), 2u);
  for (const NhbJump& jp : curve.jumps) EXPECT_TRUE(std::isfinite(jp.rms_after));

  const BkParameters bk{p.zeta, p.alpha, p.mean_force, p.alternating_force, 0.0, true};
  BkState low{1.1, 0.0, 0.0};
  testing::BkIntegrate(bk, 0.44, 300, 0, low, nullptr);
  BkSweep(bk, Range(0.44, 0.52, 0.02), low, 80, 1, &low);
  const auto up = BkSweep(bk, Range(0.53, 0.56, 0.003), low, 120, 4);
  CheckSweep(curve, up, true);
  BkState high{1.1, 0.0, 0.0};
  testing::BkIntegrate(bk, 0.60, 300, 0, high, nullptr);
  BkSweep(bk, Range(0.60, 0.50, 0.02), high, 80, 1, &high);
  const auto down = BkSweep(bk, Range(0.497, 0.470, 0.003), high, 120, 4);
  CheckSweep(curve, down, false);

  // The back flank is reached where claimed: on the branch before the up-sweep jump and after
  // the down-sweep jump (time integration and HB), not on the branch between the jumps.
  const int ju = JumpIndex(up), jd = JumpIndex(down);
  ASSERT_GT(ju, 0);
  ASSERT_GT(jd, 0);
  EXPECT_LT(up[ju - 1].minimum, -1.0);
  EXPECT_GT(up[ju].minimum, -1.0);
  EXPECT_GT(down[jd - 1].minimum, -1.0);
  EXPECT_LT(down[jd].minimum, -1.0);
  int back = 0;
  for (const NhbPoint& pt : curve.points) {
    // Right at a fold the lower branch grazes the back flank: skip points within 0.5 %.
    bool near_fold = false;
    for (const NhbFold& f : curve.folds) near_fold |= std::abs(pt.omega - f.omega) < 5e-3 * f.omega;
    if (pt.stable != FloquetVerdict::kStable || near_fold) continue;
    const bool on_back_branch = pt.rms[0] > 1.0;  // the back-contact branch has RMS > 1.05
    EXPECT_EQ(pt.minimum[0] < -1.0, on_back_branch) << "Ω = " << pt.omega << " RMS " << pt.rms[0];
    back += on_back_branch;
  }
  EXPECT_GT(back, 3);
}

}  // namespace
}  // namespace geardyn
