/// @file
/// @brief Fold and jump extraction. A fold lies between points i and i+1 where dΩ/ds changes
/// sign; it is the one located by LocateFold (fold_location.cpp) during the trace, or, when that
/// failed, Ω is the cubic Hermite interpolant of Ω(s) (values and slopes at both points) at
/// the zero of the linearly interpolated slope; other quantities are interpolated linearly.
/// A fold where Ω has a local maximum ends the branch an up-sweep follows (jump of an up-sweep),
/// a local minimum one of a down-sweep. The landing branch is the stable crossing of Ω_fold
/// (away from the fold's own segments) nearest in RMS.
#include "nonlinear_hb/folds.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace geardyn::internal {
namespace {

double Lerp(double a, double b, double w) { return a + w * (b - a); }

/// Points on each side of a fold searched for a stable one.
constexpr int kFlickerPoints = 8;

}  // namespace

void FindFoldsAndJumps(NhbCurve& curve, const std::vector<double>& steps, double omega_scale,
                       const std::vector<NhbFold>& located) {
  auto& pts = curve.points;
  for (size_t i = 0; i < pts.size(); ++i) {
    if (i > 0 && (pts[i - 1].tangent_omega > 0) != (pts[i].tangent_omega > 0)) {
      const auto found = std::find_if(located.begin(), located.end(), [&](const NhbFold& f) {
        return f.index == static_cast<int>(i - 1);
      });
      if (found != located.end() && found->located) {
        curve.folds.push_back(*found);
        continue;
      }
      const NhbPoint& a = pts[i - 1];
      const NhbPoint& b = pts[i];
      const double ds = steps[i];
      const double d0 = omega_scale * a.tangent_omega * ds;
      const double d1 = omega_scale * b.tangent_omega * ds;
      const double w = d0 / (d0 - d1);
      const double h00 = 2 * w * w * w - 3 * w * w + 1, h10 = w * w * w - 2 * w * w + w;
      const double h01 = -2 * w * w * w + 3 * w * w, h11 = w * w * w - w * w;
      NhbFold fold;
      fold.omega = h00 * a.omega + h10 * d0 + h01 * b.omega + h11 * d1;
      fold.rms = Lerp(a.rms[0], b.rms[0], w);
      fold.maximum = Lerp(a.maximum[0], b.maximum[0], w);
      fold.minimum = Lerp(a.minimum[0], b.minimum[0], w);
      fold.index = static_cast<int>(i - 1);
      fold.omega_maximum = a.tangent_omega > 0;
      fold.omega_error = fold.omega_maximum ? std::abs(fold.omega - std::max(a.omega, b.omega))
                                            : std::abs(fold.omega - std::min(a.omega, b.omega));
      if (found != located.end() && found->omega_error < fold.omega_error) {
        // The locator missed the tolerance but still improved on the interpolation.
        fold = *found;
      }
      curve.folds.push_back(fold);
    }
  }
  // The AFT residual is only piecewise smooth (a sample crossing a kink of g), which can put
  // micro-zigzags of ΔΩ ~ 1e-4 Ω near a fold. A consecutive pair of opposite folds closer than
  // kFoldMergeTolerance·Ω is such an artefact and is removed (the surviving fold of the
  // cluster keeps its position within that tolerance).
  constexpr double kFoldMergeTolerance = 1e-3;
  for (size_t i = 0; i + 1 < curve.folds.size();) {
    const NhbFold& f0 = curve.folds[i];
    const NhbFold& f1 = curve.folds[i + 1];
    if (std::abs(f0.omega - f1.omega) < kFoldMergeTolerance * std::abs(f0.omega)) {
      // The surviving neighbours of the cluster are only known to within its span: their error
      // estimates grow to it (and they no longer count as located to the tolerance).
      for (size_t k : {i - 1, i + 2}) {
        if ((k == i - 1 && i == 0) || k >= curve.folds.size()) continue;
        NhbFold& f = curve.folds[k];
        const double span = std::max(std::abs(f.omega - f0.omega), std::abs(f.omega - f1.omega));
        if (span < kFoldMergeTolerance * std::abs(f.omega) && span > f.omega_error) {
          f.omega_error = span;
          f.located = false;
        }
      }
      curve.folds.erase(curve.folds.begin() + i, curve.folds.begin() + i + 2);
      if (i > 0) --i;
    } else {
      ++i;
    }
  }
  int branch = 0;
  size_t next = 0;
  for (size_t i = 0; i < pts.size(); ++i) {
    if (next < curve.folds.size() && static_cast<int>(i) == curve.folds[next].index + 1) {
      ++branch;
      ++next;
    }
    pts[i].branch = branch;
  }
  FindJumps(curve);
}

void FindJumps(NhbCurve& curve) {
  auto& pts = curve.points;
  curve.jumps.clear();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (const NhbFold& fold : curve.folds) {
    // Both branches meeting at the fold lie on the same side in Ω, the side a sweep comes
    // from; the sweep arrives on the stable one (a fold between two unstable branches is not
    // a jump of a slow sweep).
    // Near a fold |μ| ≈ 1 and the flag may flicker (the monodromy error is not zero): a side
    // is stable when one of its points 2 to kFlickerPoints steps away from the fold is.
    auto side_stable = [&](int from, int direction) {
      const int side_branch = pts[static_cast<size_t>(from)].branch;
      for (int k = 2; k <= kFlickerPoints; ++k) {
        const int i = from + direction * k;
        if (i < 0 || i >= static_cast<int>(pts.size())) break;
        if (pts[static_cast<size_t>(i)].branch != side_branch) break;
        if (pts[static_cast<size_t>(i)].stable == FloquetVerdict::kStable) return true;
      }
      return false;
    };
    const int after = std::min(fold.index + 1, static_cast<int>(pts.size()) - 1);
    if (!side_stable(fold.index, -1) && !side_stable(after, 1)) continue;
    NhbJump jump;
    jump.up_sweep = fold.omega_maximum;
    jump.omega = fold.omega;
    jump.rms_before = fold.rms;
    jump.max_before = fold.maximum;
    jump.rms_after = nan;
    jump.max_after = nan;
    double best = std::numeric_limits<double>::infinity();
    for (size_t i = 0; i + 1 < pts.size(); ++i) {
      const NhbPoint& p = pts[i];
      const NhbPoint& q = pts[i + 1];
      // The landing branch is neither of the two branches that meet at the fold.
      if (p.branch != q.branch || p.branch == pts[fold.index].branch ||
          p.branch == pts[std::min<size_t>(fold.index + 1, pts.size() - 1)].branch) {
        continue;
      }
      if (p.stable != FloquetVerdict::kStable || q.stable != FloquetVerdict::kStable) continue;
      if ((p.omega - fold.omega) * (q.omega - fold.omega) > 0 || p.omega == q.omega) continue;
      const double w = (fold.omega - p.omega) / (q.omega - p.omega);
      const double rms = Lerp(p.rms[0], q.rms[0], w);
      jump.rms_landings.push_back(rms);
      if (std::abs(rms - fold.rms) < best) {
        best = std::abs(rms - fold.rms);
        jump.rms_after = rms;
        jump.max_after = Lerp(p.maximum[0], q.maximum[0], w);
      }
    }
    std::sort(jump.rms_landings.begin(), jump.rms_landings.end(),
              [&](double a, double b) { return std::abs(a - fold.rms) < std::abs(b - fold.rms); });
    curve.jumps.push_back(jump);
  }
}

}  // namespace geardyn::internal
