#include "geardyn/models/contact/tip_corner_contact.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace geardyn {

namespace {

Vector2 Perp(const Vector2& a) { return {-a.y(), a.x()}; }  // J a
double Cross(const Vector2& a, const Vector2& b) { return a.x() * b.y() - a.y() * b.x(); }

// True when u lies on the short arc from a to b (unit vectors).
bool Between(const Vector2& a, const Vector2& b, const Vector2& u) {
  const double ab = Cross(a, b);
  return Cross(a, u) * ab >= 0.0 && Cross(u, b) * ab >= 0.0 && u.dot(a + b) > 0.0;
}

}  // namespace

FlankContact CalcTipCornerContact(const InvoluteFlankPose& corner_flank, double corner_radius,
                                  const InvoluteFlankPose& mate) {
  FlankContact out;
  const double rba = corner_flank.base_radius, rbb = mate.base_radius;
  const int ea = corner_flank.unwind, eb = mate.unwind;
  // Corner centre Q on the corner flank's inward normal at ρ_t.
  const double rho_t = corner_flank.roll_max;
  const double ta = corner_flank.base_angle + ea * rho_t / rba;
  const Vector2 ua(std::cos(ta), std::sin(ta));
  const Vector2 na = -ea * Perp(ua);
  const Vector2 q = corner_flank.center + rba * ua + (rho_t - corner_radius) * na;
  // Foot on the mate: the tangent from Q to its base circle.
  const Vector2 d = q - mate.center;
  const double dn = d.norm();
  if (!(dn > rbb)) return out;  // Q inside the mate's base circle (or NaN)
  const Vector2 dh = d / dn;
  const double lambda = std::sqrt((dn - rbb) * (dn + rbb));
  const double t = std::atan2(d.y(), d.x()) + eb * std::acos(rbb / dn);
  const Vector2 e(std::cos(t), std::sin(t));
  const Vector2 nb = -eb * Perp(e);
  const double sigma = eb * rbb * std::remainder(t - mate.base_angle, 2.0 * std::numbers::pi);
  out.found = true;
  out.corner = 1;
  out.penetration = corner_radius + sigma - lambda;
  out.normal = -nb;
  out.roll1 = rho_t;
  out.roll2 = sigma;
  out.point1 = q - corner_radius * nb;
  out.point2 = mate.center + rbb * e + sigma * nb;
  out.point = 0.5 * (out.point1 + out.point2);
  out.tangent_length = lambda;
  const Vector2 radial = (q - corner_flank.center).normalized();
  out.valid = Between(na, radial, -nb) && sigma >= mate.roll_min && sigma <= mate.roll_max &&
              std::abs(out.penetration) <= std::min(corner_flank.max_depth, mate.max_depth);
  // Derivatives; Q moves with body A: ∂Q/∂c_A = I, ∂Q/∂β_A = J(Q − c_A).
  const Vector2 jq = Perp(q - corner_flank.center);
  out.d_penetration << -nb.x(), -nb.y(), -nb.dot(jq), nb.x(), nb.y(), -eb * rbb;
  const Vector2 dt = Perp(dh) / dn + (eb * rbb / (dn * lambda)) * dh;  // ∂t/∂d
  const Vector2 ds = eb * rbb * dt;                                    // ∂σ/∂d
  out.d_roll2 << ds.x(), ds.y(), ds.dot(jq), -ds.x(), -ds.y(), -eb * rbb;
  // ∂t/∂pose, then ∂P_B = ∂c_B + (r_b J e + σ ε_B e) ∂t + n_B ∂σ, ∂P_A = ∂Q − ρ_a ε_B e ∂t.
  PoseGradient dtp;
  dtp << dt.x(), dt.y(), dt.dot(jq), -dt.x(), -dt.y(), 0.0;
  Eigen::Matrix<double, 2, 6> dpb = (rbb * Perp(e) + sigma * eb * e) * dtp + nb * out.d_roll2;
  dpb(0, 3) += 1.0;
  dpb(1, 4) += 1.0;
  Eigen::Matrix<double, 2, 6> dpa = -corner_radius * eb * e * dtp;
  dpa(0, 0) += 1.0;
  dpa(1, 1) += 1.0;
  dpa.col(2) += jq;
  out.d_point = 0.5 * (dpa + dpb);
  return out;
}

FlankContact SwapBodies(const FlankContact& c) {
  FlankContact s = c;
  auto swap = [](const PoseGradient& g) {
    PoseGradient r;
    r << g.tail<3>(), g.head<3>();
    return r;
  };
  s.corner = c.corner == 1 ? 2 : (c.corner == 2 ? 1 : 0);
  s.normal = -c.normal;
  s.point1 = c.point2;
  s.point2 = c.point1;
  s.roll1 = c.roll2;
  s.roll2 = c.roll1;
  s.d_penetration = swap(c.d_penetration);
  s.d_roll1 = swap(c.d_roll2);
  s.d_roll2 = swap(c.d_roll1);
  s.d_point.leftCols<3>() = c.d_point.rightCols<3>();
  s.d_point.rightCols<3>() = c.d_point.leftCols<3>();
  return s;
}

}  // namespace geardyn
