#include "geardyn/models/contact/biarc_profile.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "geardyn/common/check.hpp"

namespace geardyn {

namespace {

Vector2 Perp(const Vector2& a) { return {-a.y(), a.x()}; }
double Cross(const Vector2& a, const Vector2& b) { return a.x() * b.y() - a.y() * b.x(); }

// True when u lies on the short arc from a to b (unit vectors).
bool Between(const Vector2& a, const Vector2& b, const Vector2& u) {
  const double ab = Cross(a, b);
  return Cross(a, u) * ab >= 0.0 && Cross(u, b) * ab >= 0.0 && u.dot(a + b) > 0.0;
}

// The circle through P tangent to T at P and through J.
FlankArc ArcThrough(const Vector2& p, const Vector2& t, const Vector2& j, bool from_p) {
  const Vector2 nrm = Perp(t);
  const Vector2 w = j - p;
  const double k = w.squaredNorm() / (2.0 * nrm.dot(w));  // signed radius along nrm
  FlankArc arc;
  arc.center = p + k * nrm;
  arc.radius = std::abs(k);
  const Vector2 up = (p - arc.center) / arc.radius, uj = (j - arc.center) / arc.radius;
  arc.start = from_p ? up : uj;
  arc.end = from_p ? uj : up;
  return arc;
}

// Distance of x from an arc (∞ when x's direction lies outside the arc's span).
double ArcDistance(const FlankArc& arc, const Vector2& x) {
  const Vector2 d = x - arc.center;
  const double r = d.norm();
  if (!Between(arc.start, arc.end, d / r)) return std::numeric_limits<double>::infinity();
  return std::abs(r - arc.radius);
}

struct WorldArc {
  Vector2 center = Vector2::Zero(), start = Vector2::UnitX(), end = Vector2::UnitX();
  double radius = 0.0;
};

WorldArc Place(const FlankArc& arc, const InvoluteFlankPose& pose) {
  const double c = std::cos(pose.base_angle), s = std::sin(pose.base_angle);
  const Matrix2 rot = (Matrix2() << c, -s, s, c).finished();
  return {pose.center + rot * arc.center, rot * arc.start, rot * arc.end, arc.radius};
}

}  // namespace

BiarcFlank::BiarcFlank(const ToothFlankGeometry& geometry, int unwind, int num_biarcs)
    : base_radius_(geometry.base_radius) {
  GEARDYN_THROW_UNLESS(unwind == 1 || unwind == -1, "unwind: must be +1 or -1, got " << unwind);
  GEARDYN_THROW_UNLESS(num_biarcs >= 1 && num_biarcs <= 1000,
                       "num_biarcs: " << num_biarcs << " must lie in [1, 1000]");
  InvoluteFlankPose canon;
  canon.base_radius = geometry.base_radius;
  canon.unwind = unwind;
  const double r0 = geometry.form_roll(), r1 = geometry.corner_roll();
  // Unit tangent along increasing roll: dP/dρ = (ρ/r_b) e(t) and n = −ε J e, so T = e = ε J n.
  auto tangent = [&](double rho) { return Vector2(unwind * Perp(InvoluteNormal(canon, rho))); };
  form_roll_ = r0;
  segment_ = (r1 - r0) / num_biarcs;
  arcs_.reserve(2 * num_biarcs);
  junction_roll_.reserve(num_biarcs);
  for (int k = 0; k < num_biarcs; ++k) {
    const double ra = r0 + (r1 - r0) * k / num_biarcs;
    const double rb = r0 + (r1 - r0) * (k + 1) / num_biarcs;
    const Vector2 p0 = InvolutePoint(canon, ra), p1 = InvolutePoint(canon, rb);
    const Vector2 t0 = tangent(ra), t1 = tangent(rb);
    const Vector2 v = p1 - p0, t = t0 + t1;
    const double denom = 2.0 * (1.0 - t0.dot(t1));
    const double vt = v.dot(t);
    const double d = denom > 1e-300 ? (-vt + std::sqrt(vt * vt + denom * v.squaredNorm())) / denom
                                    : 0.5 * v.norm();
    const Vector2 j = 0.5 * (p0 + d * t0 + p1 - d * t1);
    arcs_.push_back(ArcThrough(p0, t0, j, true));
    arcs_.push_back(ArcThrough(p1, t1, j, false));
    junction_roll_.push_back(
        std::sqrt(std::max(0.0, j.squaredNorm() - canon.base_radius * canon.base_radius)));
    // Largest distance of the involute from the two arcs on this segment.
    for (int i = 0; i <= 64; ++i) {
      const Vector2 x = InvolutePoint(canon, ra + (rb - ra) * i / 64.0);
      const double dist = std::min(ArcDistance(arcs_[2 * k], x), ArcDistance(arcs_[2 * k + 1], x));
      if (std::isfinite(dist)) max_deviation_ = std::max(max_deviation_, dist);
    }
  }
  // The tip corner: centre Q = P(ρ_t) − ρ_a n(ρ_t) (tip_corner_contact.hpp), spanning the
  // directions from the flank normal at ρ_t to the tip radial of Q.
  const double rho_a = geometry.tip_corner_radius;
  const Vector2 nt = InvoluteNormal(canon, r1);
  corner_.center = InvolutePoint(canon, r1) - rho_a * nt;
  corner_.radius = rho_a;
  corner_.start = nt;
  corner_.end = corner_.center.normalized();
}

int BiarcFlank::ArcIndex(double roll) const {
  const int segments = static_cast<int>(junction_roll_.size());
  const double u = segment_ > 0.0 ? (roll - form_roll_) / segment_ : 0.0;
  const int k = std::isfinite(u) ? std::clamp(static_cast<int>(std::floor(u)), 0, segments - 1) : 0;
  return 2 * k + (roll > junction_roll_[k] ? 1 : 0);
}

namespace {

// The best valid candidate so far: the two placed arcs and δ.
struct Best {
  bool found = false;
  WorldArc a, b;
  int corner = 0;
  double delta = -std::numeric_limits<double>::infinity();
};

// Arc A of body 1 against arc B of body 2: δ = r_A + r_B − |C_B − C_A| along n = C_A→C_B, valid
// when n lies in A's span, −n in B's, and |δ| ≤ depth.
void TryPair(const WorldArc& wa, const WorldArc& wb, int corner, double depth, Best* best) {
  const Vector2 d = wb.center - wa.center;
  const double dist = d.norm();
  const double delta = wa.radius + wb.radius - dist;
  if (!(delta > best->delta) || std::abs(delta) > depth || !(dist > 0.0)) return;
  const Vector2 n = d / dist;
  if (!Between(wa.start, wa.end, n) || !Between(wb.start, wb.end, Vector2(-n))) return;
  *best = {true, wa, wb, corner, delta};
}

// Involute roll of P on the flank (c, r_b) and its gradient from ∂P (2×6), c at columns col..col+1.
double RollWithGradient(const Vector2& p, const InvoluteFlankPose& pose,
                        const Eigen::Matrix<double, 2, 6>& dp, int col, PoseGradient* grad) {
  const Vector2 u = p - pose.center;
  const double rho =
      std::sqrt(std::max(0.0, u.squaredNorm() - pose.base_radius * pose.base_radius));
  Eigen::Matrix<double, 2, 6> dpc = dp;
  dpc.block<2, 2>(0, col) -= Matrix2::Identity();
  if (rho > 1e-12) {
    *grad = u.transpose() * dpc / rho;
  } else {
    grad->setZero();
  }
  return rho;
}

// The contact of the best candidate with its closed-form gradients (see the header).
FlankContact Finish(const Best& best, const InvoluteFlankPose& pose_a,
                    const InvoluteFlankPose& pose_b) {
  FlankContact out;
  if (!best.found) return out;
  out.found = true;
  out.valid = true;
  out.corner = best.corner;
  out.penetration = best.delta;
  const Vector2 d = best.b.center - best.a.center;
  const double dist = d.norm();
  const Vector2 n = d / dist;
  out.normal = n;
  Eigen::Matrix<double, 2, 6> dca = Eigen::Matrix<double, 2, 6>::Zero(), dcb = dca;
  dca.block<2, 2>(0, 0).setIdentity();
  dca.col(2) = Perp(best.a.center - pose_a.center);
  dcb.block<2, 2>(0, 3).setIdentity();
  dcb.col(5) = Perp(best.b.center - pose_b.center);
  out.d_penetration = n.transpose() * (dca - dcb);
  const Matrix2 proj = (Matrix2::Identity() - n * n.transpose()) / dist;
  const Eigen::Matrix<double, 2, 6> dn = proj * (dcb - dca);
  out.point1 = best.a.center + best.a.radius * n;
  out.point2 = best.b.center - best.b.radius * n;
  const Eigen::Matrix<double, 2, 6> dp1 = dca + best.a.radius * dn, dp2 = dcb - best.b.radius * dn;
  out.point = 0.5 * (out.point1 + out.point2);
  out.d_point = 0.5 * (dp1 + dp2);
  out.roll1 = RollWithGradient(out.point1, pose_a, dp1, 0, &out.d_roll1);
  out.roll2 = RollWithGradient(out.point2, pose_b, dp2, 3, &out.d_roll2);
  if (best.corner == 1) {  // as the exact corner kernel: ρ_t of the corner's flank
    out.roll1 = pose_a.roll_max;
    out.d_roll1.setZero();
  } else if (best.corner == 2) {
    out.roll2 = pose_b.roll_max;
    out.d_roll2.setZero();
  }
  return out;
}

FlankContact NotFinite() {
  FlankContact out;
  out.penetration = std::numeric_limits<double>::quiet_NaN();  // never "no contact" silently
  return out;
}

}  // namespace

FlankContact CalcBiarcContact(const BiarcFlank& a, const InvoluteFlankPose& pose_a,
                              const BiarcFlank& b, const InvoluteFlankPose& pose_b) {
  if (!IsFinite(pose_a) || !IsFinite(pose_b)) return NotFinite();
  const double depth = std::min(pose_a.max_depth, pose_b.max_depth);
  Best best;
  for (const FlankArc& la : a.arcs()) {
    const WorldArc wa = Place(la, pose_a);
    for (const FlankArc& lb : b.arcs()) TryPair(wa, Place(lb, pose_b), 0, depth, &best);
    TryPair(wa, Place(b.corner(), pose_b), 2, depth, &best);
  }
  const WorldArc corner_a = Place(a.corner(), pose_a);
  for (const FlankArc& lb : b.arcs()) TryPair(corner_a, Place(lb, pose_b), 1, depth, &best);
  return Finish(best, pose_a, pose_b);
}

FlankContact CalcBiarcContactNear(const BiarcFlank& a, const InvoluteFlankPose& pose_a,
                                  double roll_a, const BiarcFlank& b,
                                  const InvoluteFlankPose& pose_b, double roll_b) {
  if (!IsFinite(pose_a) || !IsFinite(pose_b)) return NotFinite();
  const double depth = std::min(pose_a.max_depth, pose_b.max_depth);
  const int last_a = static_cast<int>(a.arcs().size()) - 1;
  const int last_b = static_cast<int>(b.arcs().size()) - 1;
  const int ia = a.ArcIndex(roll_a), ib = b.ArcIndex(roll_b);
  const int a0 = std::max(0, ia - 1), a1 = std::min(last_a, ia + 1);
  const int b0 = std::max(0, ib - 1), b1 = std::min(last_b, ib + 1);
  Best best;
  WorldArc wb[3];
  for (int j = b0; j <= b1; ++j) wb[j - b0] = Place(b.arcs()[j], pose_b);
  const bool corner_b = b1 == last_b;
  const WorldArc wcb = corner_b ? Place(b.corner(), pose_b) : WorldArc{};
  for (int i = a0; i <= a1; ++i) {
    const WorldArc wa = Place(a.arcs()[i], pose_a);
    for (int j = b0; j <= b1; ++j) TryPair(wa, wb[j - b0], 0, depth, &best);
    if (corner_b) TryPair(wa, wcb, 2, depth, &best);
  }
  if (a1 == last_a) {
    const WorldArc wca = Place(a.corner(), pose_a);
    for (int j = b0; j <= b1; ++j) TryPair(wca, wb[j - b0], 1, depth, &best);
  }
  return Finish(best, pose_a, pose_b);
}

}  // namespace geardyn
