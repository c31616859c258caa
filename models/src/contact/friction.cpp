// Regularised Coulomb friction (friction.hpp).
#include "geardyn/models/contact/friction.hpp"

#include <cmath>

namespace geardyn {

FrictionValue EvalFriction(double mu, double normal_force, double sliding_speed,
                           double speed_scale) {
  const double s = std::tanh(sliding_speed / speed_scale);
  FrictionValue out;
  out.force = -mu * normal_force * s;
  out.d_force_d_normal = -mu * s;
  out.d_force_d_speed = -mu * normal_force * (1.0 - s * s) / speed_scale;
  out.dissipation = -out.force * sliding_speed;
  return out;
}

}  // namespace geardyn
