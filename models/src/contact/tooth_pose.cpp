#include "geardyn/models/contact/tooth_pose.hpp"

#include <cmath>

namespace geardyn {

EffectiveBaseCircle CalcEffectiveBaseCircle(const Vector2& gear_center, double gear_angle,
                                            double tooth_angle, double pivot_radius,
                                            const ToothDeflection& deflection) {
  // c′ = c + (r_p + τ_r) e(a) − r_p e(a + ψ) + τ_t e′(a), a = φ + γ, φ′ = φ + ψ.
  const double a = gear_angle + tooth_angle;
  const double psi = deflection.rotation;
  const Vector2 e(std::cos(a), std::sin(a));
  const Vector2 ep(-e.y(), e.x());
  const Vector2 f(std::cos(a + psi), std::sin(a + psi));
  const Vector2 fp(-f.y(), f.x());
  const double rp = pivot_radius;
  EffectiveBaseCircle out;
  out.center = gear_center + (rp + deflection.radial) * e - rp * f + deflection.tangential * ep;
  out.angle = gear_angle + psi;
  auto& jac = out.jacobian;
  jac.setZero();
  jac(0, 0) = 1.0;
  jac(1, 1) = 1.0;
  jac.block<2, 1>(0, 2) = (rp + deflection.radial) * ep - rp * fp - deflection.tangential * e;
  jac.block<2, 1>(0, 3) = -rp * fp;
  jac.block<2, 1>(0, 4) = e;
  jac.block<2, 1>(0, 5) = ep;
  jac(2, 2) = 1.0;
  jac(2, 3) = 1.0;
  return out;
}

}  // namespace geardyn
