/// @file
/// @brief SearchBranches (branch_search.hpp): Newton from scaled contact guesses at frequencies
/// inside the range; a solution off the traced curve is traced both ways and appended.
#include "nonlinear_hb/branch_search.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <iomanip>
#include <limits>
#include <sstream>

#include "nonlinear_hb/folds.hpp"

namespace geardyn::internal {
namespace {

/// Scales of the contact guess's alternating part: the guess itself (a contact branch), a
/// smaller response, and larger ones that reach contact loss and the back flank.
constexpr std::array<double, 4> kGuessScales{1.0, 0.3, 3.0, 8.0};
/// A solution is on a traced segment when it lies within kSameOmega (relative Ω) and
/// kSameRms (relative RMS of coordinate 0) of a chord between consecutive points: the chords
/// deviate from the curve by far less (the tangent-angle limit, 0.15 rad), and distinct branches
/// at one frequency differ by more (5.85 vs 17 µm on the spur pair with backlash).
constexpr double kSameOmega = 5e-3;
constexpr double kSameRms = 2e-2;
/// Most segments added (each a full trace): a bound on the cost of a pathological scene.
constexpr int kMaxSegments = 8;

/// Distance of (Ω, r) from the traced curve in units of (kSameOmega·Ω, kSameRms·r): the
/// smallest over the chords between consecutive points of one segment.
double DistanceFromCurve(const NhbCurve& curve, double omega, double rms) {
  double best = std::numeric_limits<double>::infinity();
  const double so = kSameOmega * std::abs(omega), sr = kSameRms * std::max(rms, 1e-300);
  auto scaled = [&](const NhbPoint& p) {
    return std::array<double, 2>{(p.omega - omega) / so, (p.rms[0] - rms) / sr};
  };
  for (size_t i = 0; i + 1 < curve.points.size(); ++i) {
    const NhbPoint &p = curve.points[i], &q = curve.points[i + 1];
    if (p.segment != q.segment) continue;
    const std::array<double, 2> a = scaled(p), b = scaled(q);
    const double dx = b[0] - a[0], dy = b[1] - a[1];
    const double len2 = dx * dx + dy * dy;
    const double w = len2 > 0 ? std::clamp(-(a[0] * dx + a[1] * dy) / len2, 0.0, 1.0) : 0.0;
    best = std::min(best, std::hypot(a[0] + w * dx, a[1] + w * dy));
  }
  if (curve.points.size() == 1) {
    const std::array<double, 2> a = scaled(curve.points[0]);
    best = std::hypot(a[0], a[1]);
  }
  return best;
}

/// `first` reversed (arclength from its far end to its start) followed by `second` without its
/// first point (the shared start): one segment in arclength order. Fold indices follow.
NhbCurve Join(const NhbCurve& first, const NhbCurve& second) {
  NhbCurve out;
  const int n1 = static_cast<int>(first.points.size());
  for (int i = n1 - 1; i >= 0; --i) {
    NhbPoint p = first.points[static_cast<size_t>(i)];
    p.tangent_omega = -p.tangent_omega;  // the arclength runs the other way
    out.points.push_back(std::move(p));
  }
  for (auto it = first.folds.rbegin(); it != first.folds.rend(); ++it) {
    NhbFold f = *it;
    f.index = n1 - 2 - f.index;  // the point before the fold, counted from the other end
    out.folds.push_back(f);
  }
  for (size_t i = 1; i < second.points.size(); ++i) out.points.push_back(second.points[i]);
  for (const NhbFold& fold : second.folds) {
    NhbFold f = fold;
    f.index += n1 - 1;
    out.folds.push_back(f);
  }
  return out;
}

}  // namespace

void SearchBranches(const NhbProblem& problem, const NhbOptions& options,
                    const NhbContinuationOptions& c, NhbCurve& curve) {
  const int H = curve.harmonics_used;
  NhbSolver solver(problem, options, H);
  const int n = problem.law->num_coordinates();
  const int m = solver.num_unknowns();
  const double lo = std::min(c.omega_start, c.omega_end);
  const double hi = std::max(c.omega_start, c.omega_end);
  long solves = 0;
  int found = 0;
  int next_branch = 0;
  for (const NhbPoint& p : curve.points) next_branch = std::max(next_branch, p.branch + 1);
  for (int i = 0; i < c.branch_search && found < kMaxSegments; ++i) {
    const double omega = lo + (hi - lo) * (i + 0.5) / c.branch_search;
    const VectorX contact = solver.ContactGuess(omega);
    for (double scale : kGuessScales) {
      if (found >= kMaxSegments) break;
      VectorX x = contact;
      x.tail(m - n) *= scale;
      Status status = Status::kNotConverged;
      double rn = 0.0;
      solver.Newton(x, omega, &status, &rn);
      ++solves;
      if (status != Status::kSuccess || !x.allFinite()) continue;
      NhbPoint point;
      solver.Describe(x, omega, point);
      if (!std::isfinite(point.rms[0]) || DistanceFromCurve(curve, omega, point.rms[0]) <= 1.0) {
        continue;
      }
      // Off the curve: trace it towards both ends of the range (the way of the original trace
      // first), then join the two halves at the solution.
      NhbContinuationOptions forward = c;
      BranchStart from{x, omega, false};
      const NhbCurve ahead = TraceWithHarmonics(problem, options, forward, H, &from);
      NhbCurve segment;
      std::vector<const Summary*> summaries{&ahead.summary};
      NhbCurve behind;
      if (from.closed) {
        segment.points = ahead.points;
        segment.folds = ahead.folds;
      } else {
        NhbContinuationOptions backward = c;
        std::swap(backward.omega_start, backward.omega_end);
        BranchStart back{x, omega, false};
        behind = TraceWithHarmonics(problem, options, backward, H, &back);
        summaries.push_back(&behind.summary);
        segment = Join(behind, ahead);
      }
      if (segment.points.size() < 2) continue;
      ++found;
      // Branch ids: a new one at the segment's start and after each of its folds.
      std::sort(segment.folds.begin(), segment.folds.end(),
                [](const NhbFold& a, const NhbFold& b) { return a.index < b.index; });
      const int offset = static_cast<int>(curve.points.size());
      size_t next_fold = 0;
      for (size_t k = 0; k < segment.points.size(); ++k) {
        if (next_fold < segment.folds.size() &&
            static_cast<int>(k) == segment.folds[next_fold].index + 1) {
          ++next_branch;
          ++next_fold;
        }
        segment.points[k].branch = next_branch;
        segment.points[k].segment = found;
      }
      ++next_branch;
      for (NhbFold f : segment.folds) {
        f.index += offset;
        curve.folds.push_back(f);
      }
      for (NhbPoint& p : segment.points) curve.points.push_back(std::move(p));
      std::ostringstream w;
      w << std::setprecision(6) << "branch search: a branch off the traced curve at "
        << (c.omega_text ? c.omega_text(omega) : "Omega = " + std::to_string(omega))
        << " (RMS of coordinate 0: " << point.rms[0] << ") traced as segment " << found
        << (from.closed ? " (a closed loop, an isola)" : "");
      for (const Summary* s : summaries) {
        if (!s->ok()) w << "; its trace stopped: " << s->message;
        for (const std::string& warning : s->warnings) curve.summary.warnings.push_back(warning);
      }
      curve.summary.warnings.push_back(w.str());
      for (const NhbCurve* part : std::array<const NhbCurve*, 2>{&ahead, &behind}) {
        for (const auto& u : part->unbounded_branches) curve.unbounded_branches.push_back(u);
      }
    }
  }
  if (found > 0) {
    FindJumps(curve);
    long undetermined = 0;
    double err = 0.0;
    for (const NhbPoint& p : curve.points) {
      undetermined += p.stable == FloquetVerdict::kUndetermined ? 1 : 0;
      err = std::max(err, p.error_estimate);
    }
    curve.summary.error_estimate = err;
    curve.summary.counters["undetermined_verdicts"] = undetermined;
    if (undetermined > 0 && curve.summary.ok()) {
      curve.summary.status = Status::kNumericalIssue;
      curve.summary.message = "stability undetermined (non-finite max |mu|) at " +
                              std::to_string(undetermined) + " point(s)";
    }
    curve.summary.counters["points"] = static_cast<long>(curve.points.size());
    curve.summary.counters["folds"] = static_cast<long>(curve.folds.size());
  }
  curve.summary.counters["branch_search_solves"] = solves;
  curve.summary.counters["branches_found"] = found;
}

}  // namespace geardyn::internal
