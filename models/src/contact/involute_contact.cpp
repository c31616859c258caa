#include "geardyn/models/contact/involute_contact.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace geardyn {

namespace {

Vector2 Perp(const Vector2& a) { return {-a.y(), a.x()}; }  // J a, rotation by +90°

}  // namespace

FlankContact CalcInvoluteContact(const InvoluteFlankPose& flank1, const InvoluteFlankPose& flank2) {
  FlankContact out;
  const int eps = flank1.unwind;
  if (flank2.unwind != eps) return out;  // opposite senses never meet on an external pair
  const Vector2 d = flank2.center - flank1.center;
  const double c = d.norm();
  const double r1 = flank1.base_radius, r2 = flank2.base_radius, r = r1 + r2;
  if (!(c > r)) return out;  // overlapping base circles (or NaN): no internal common tangent
  const Vector2 e = d / c, ep = Perp(e);
  const double length = std::sqrt((c - r) * (c + r));  // L = √(C² − R²)
  const double cos_a = r / c, sin_a = length / c;
  // The internal tangent on which flanks of sense ε can face each other has ω = ε.
  const Vector2 m = cos_a * e + eps * sin_a * ep;
  const Vector2 n = -eps * Perp(m);
  const double t1 = std::atan2(m.y(), m.x());
  const double two_pi = 2.0 * std::numbers::pi;
  // ρ_k = ε r_k wrap(t_k − β_k), t2 = t1 + π.
  const double rho1 = eps * r1 * std::remainder(t1 - flank1.base_angle, two_pi);
  const double rho2 = eps * r2 * std::remainder(t1 + std::numbers::pi - flank2.base_angle, two_pi);
  out.found = true;
  out.roll1 = rho1;
  out.roll2 = rho2;
  out.tangent_length = length;
  out.penetration = rho1 + rho2 - length;
  out.normal = n;
  out.point1 = flank1.center + r1 * m + rho1 * n;
  out.point2 = flank2.center - r2 * m - rho2 * n;
  out.point = 0.5 * (out.point1 + out.point2);
  out.valid = rho1 >= flank1.roll_min && rho1 <= flank1.roll_max && rho2 >= flank2.roll_min &&
              rho2 <= flank2.roll_max &&
              std::abs(out.penetration) <= std::min(flank1.max_depth, flank2.max_depth);
  // Closed-form derivatives (see the header).
  out.d_penetration << n.x(), n.y(), -eps * r1, -n.x(), -n.y(), -eps * r2;
  const Vector2 dt = ep / c + (eps * r / (c * length)) * e;  // ∂t1/∂c2 = −∂t1/∂c1
  const Vector2 g1 = eps * r1 * dt, g2 = eps * r2 * dt;
  out.d_roll1 << -g1.x(), -g1.y(), -eps * r1, g1.x(), g1.y(), 0.0;
  out.d_roll2 << -g2.x(), -g2.y(), 0.0, g2.x(), g2.y(), -eps * r2;
  // ∂t1/∂pose = [−dt, 0, dt, 0]; ∂P1 = [I 0 0 0] + (r1 J m + ρ1 ε m) ∂t1 + n ∂ρ1, and
  // ∂P2 = [0 0 I 0] − (r2 J m + ρ2 ε m) ∂t1 − n ∂ρ2.
  PoseGradient dt1;
  dt1 << -dt.x(), -dt.y(), 0.0, dt.x(), dt.y(), 0.0;
  const Vector2 a1 = r1 * Perp(m) + rho1 * eps * m;
  const Vector2 a2 = r2 * Perp(m) + rho2 * eps * m;
  Eigen::Matrix<double, 2, 6> dp = (a1 - a2) * dt1 + n * (out.d_roll1 - out.d_roll2);
  dp(0, 0) += 1.0;
  dp(1, 1) += 1.0;
  dp(0, 3) += 1.0;
  dp(1, 4) += 1.0;
  out.d_point = 0.5 * dp;
  return out;
}

ContactRates CalcContactRates(const FlankContact& contact, const Vector2& center1,
                              const Vector3& rate1, const Vector2& center2, const Vector3& rate2) {
  const Vector2 v1 = rate1.head<2>() + rate1.z() * Perp(contact.point - center1);
  const Vector2 v2 = rate2.head<2>() + rate2.z() * Perp(contact.point - center2);
  const Vector2 dv = v1 - v2;
  return {dv.dot(contact.normal), dv.dot(Perp(contact.normal))};
}

}  // namespace geardyn
