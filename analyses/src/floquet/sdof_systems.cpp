// MakeMeissnerSystem and MakeMathieuSystem: the classical SDOF Hill equations as generic systems.
#include <cmath>
#include <numbers>

#include "geardyn/analyses/floquet_system.hpp"
#include "geardyn/common/check.hpp"

namespace geardyn {

PeriodicSecondOrderSystem MakeMeissnerSystem(double k_hi, double k_lo, double duty, double period_s,
                                             double damping) {
  GEARDYN_THROW_UNLESS(duty > 0.0 && duty < 1.0, "duty: must be in (0, 1), got " << duty);
  GEARDYN_THROW_UNLESS(period_s > 0.0, "period_s: must be > 0, got " << period_s);
  PeriodicSecondOrderSystem s;
  s.mass = MatrixX::Ones(1, 1);
  s.period_s = period_s;
  const MatrixX c = MatrixX::Constant(1, 1, damping);
  s.steps.push_back({duty * period_s, MatrixX::Constant(1, 1, k_hi), c});
  s.steps.push_back({(1.0 - duty) * period_s, MatrixX::Constant(1, 1, k_lo), c});
  return s;
}

PeriodicSecondOrderSystem MakeMathieuSystem(double delta, double epsilon, double period_s,
                                            double damping) {
  GEARDYN_THROW_UNLESS(period_s > 0.0, "period_s: must be > 0, got " << period_s);
  PeriodicSecondOrderSystem s;
  s.mass = MatrixX::Ones(1, 1);
  s.period_s = period_s;
  const double Omega = 2.0 * std::numbers::pi / period_s;
  s.coefficients = [=](double t, MatrixX* K, MatrixX* C) {
    K->setConstant(1, 1, delta + epsilon * std::cos(Omega * t));
    C->setConstant(1, 1, damping);
  };
  // δ + ε cos Ωt = δ + (ε/2) e^{iΩt} + (ε/2) e^{−iΩt}.
  s.stiffness_harmonics = {MatrixXc::Constant(1, 1, delta), MatrixXc::Constant(1, 1, epsilon / 2)};
  s.damping_harmonics = {MatrixXc::Constant(1, 1, damping), MatrixXc::Zero(1, 1)};
  return s;
}

}  // namespace geardyn
