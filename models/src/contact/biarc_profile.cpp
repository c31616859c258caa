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
  Vector2 center, start, end;
  double radius;
};

WorldArc Place(const FlankArc& arc, const InvoluteFlankPose& pose) {
  const double c = std::cos(pose.base_angle), s = std::sin(pose.base_angle);
  const Matrix2 rot = (Matrix2() << c, -s, s, c).finished();
  return {pose.center + rot * arc.center, rot * arc.start, rot * arc.end, arc.radius};
}

double Roll(const Vector2& p, const InvoluteFlankPose& pose) {
  return std::sqrt(
      std::max(0.0, (p - pose.center).squaredNorm() - pose.base_radius * pose.base_radius));
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
  arcs_.reserve(2 * num_biarcs);
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
    // Largest distance of the involute from the two arcs on this segment.
    for (int i = 0; i <= 64; ++i) {
      const Vector2 x = InvolutePoint(canon, ra + (rb - ra) * i / 64.0);
      const double dist = std::min(ArcDistance(arcs_[2 * k], x), ArcDistance(arcs_[2 * k + 1], x));
      if (std::isfinite(dist)) max_deviation_ = std::max(max_deviation_, dist);
    }
  }
}

FlankContact CalcBiarcContact(const BiarcFlank& a, const InvoluteFlankPose& pose_a,
                              const BiarcFlank& b, const InvoluteFlankPose& pose_b) {
  FlankContact best;
  best.penetration = -std::numeric_limits<double>::infinity();
  const double depth = std::min(pose_a.max_depth, pose_b.max_depth);
  auto consider = [&](double delta, const Vector2& n, const Vector2& p1, const Vector2& p2,
                      const Vector2& ca, const Vector2& cb, int corner) {
    if (!(delta > best.penetration) || std::abs(delta) > depth) return;
    best.found = true;
    best.valid = true;
    best.corner = corner;
    best.penetration = delta;
    best.normal = n;
    best.point1 = p1;
    best.point2 = p2;
    best.point = 0.5 * (p1 + p2);
    best.roll1 = Roll(p1, pose_a);
    best.roll2 = Roll(p2, pose_b);
    // δ depends on the centres (or corner points) ca, cb moving rigidly with their poses.
    // ∂δ/∂ca = n, ∂δ/∂cb = −n; ∂(point)/∂β = J(point − c).
    best.d_penetration << n.x(), n.y(), n.dot(Perp(ca - pose_a.center)), -n.x(), -n.y(),
        -n.dot(Perp(cb - pose_b.center));
    best.d_roll1.setZero();
    best.d_roll2.setZero();
    best.d_point.setZero();
  };
  const auto& arcs_a = a.arcs();
  const auto& arcs_b = b.arcs();
  for (const FlankArc& la : arcs_a) {
    const WorldArc wa = Place(la, pose_a);
    for (const FlankArc& lb : arcs_b) {
      const WorldArc wb = Place(lb, pose_b);
      const Vector2 d = wb.center - wa.center;
      const double dist = d.norm();
      const Vector2 n = d / dist;
      if (!Between(wa.start, wa.end, n) || !Between(wb.start, wb.end, Vector2(-n))) continue;
      consider(wa.radius + wb.radius - dist, n, wa.center + wa.radius * n,
               wb.center - wb.radius * n, wa.center, wb.center, 0);
    }
  }
  // Sharp tip corners (the last arc's end) against the mate's arcs.
  const WorldArc tip_a = Place(arcs_a.back(), pose_a);
  const Vector2 qa = tip_a.center + tip_a.radius * tip_a.end;
  for (const FlankArc& lb : arcs_b) {
    const WorldArc wb = Place(lb, pose_b);
    const Vector2 d = qa - wb.center;
    const double dist = d.norm();
    if (!Between(wb.start, wb.end, Vector2(d / dist))) continue;
    // δ = r_B − |Q − C_B|, n = −d/|d| (into B): ∂δ/∂Q = n, ∂δ/∂C_B = −n.
    consider(wb.radius - dist, Vector2(-d / dist), qa, wb.center + wb.radius * d / dist, qa,
             wb.center, 1);
  }
  const WorldArc tip_b = Place(arcs_b.back(), pose_b);
  const Vector2 qb = tip_b.center + tip_b.radius * tip_b.end;
  for (const FlankArc& la : arcs_a) {
    const WorldArc wa = Place(la, pose_a);
    const Vector2 d = qb - wa.center;
    const double dist = d.norm();
    if (!Between(wa.start, wa.end, Vector2(d / dist))) continue;
    consider(wa.radius - dist, Vector2(d / dist), wa.center + wa.radius * d / dist, qb, wa.center,
             qb, 2);
  }
  if (!best.found) best.penetration = 0.0;
  return best;
}

}  // namespace geardyn
