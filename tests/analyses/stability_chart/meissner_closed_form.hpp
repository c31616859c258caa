/// @file
/// @brief Closed forms of the damped Meissner equation for the chart tests (independent of the
/// Floquet engine): x'' + 2ζω₀ x' + ω₀²(1 ± ε) x = 0, +ε for the first half of T = 1/f_m, −ε for
/// the second, ω₀ = 2π f_n.
///
/// Over an interval τ of constant w² the state [x, x'] is mapped by the exact transfer matrix
/// e^{−στ} [[c + σ s/ω_d, s/ω_d], [−w² s/ω_d, c − σ s/ω_d]], σ = ζω₀, ω_d = √(w² − σ²),
/// c = cos ω_d τ, s = sin ω_d τ; Φ = T₂ T₁. With x = e^{−σt} y the y-equation is undamped with
/// frequencies ω_i = √(w_i² − σ²), so eig Φ = e^{−σT}·eig Φ_y, det Φ_y = 1 and
/// tr Φ_y = 2 cos a cos b − (ω₁/ω₂ + ω₂/ω₁) sin a sin b (a = ω₁T/2, b = ω₂T/2): the transition
/// curves are |tr Φ_y| = 2 cosh(σT).
#pragma once

#include <Eigen/Dense>
#include <cmath>
#include <numbers>

namespace geardyn::test {

struct Meissner {
  double natural_frequency_hz = 1.0;  ///< f_n [Hz]
  double zeta = 0.0;                  ///< ζ [-]

  double omega0() const { return 2.0 * std::numbers::pi * natural_frequency_hz; }

  /// Transfer matrix over τ for stiffness w² (per unit mass).
  Eigen::Matrix2d Transfer(double w2, double tau) const {
    const double sigma = zeta * omega0();
    const double wd = std::sqrt(w2 - sigma * sigma);
    const double c = std::cos(wd * tau), s = std::sin(wd * tau);
    Eigen::Matrix2d t;
    t << c + sigma * s / wd, s / wd, -w2 * s / wd, c - sigma * s / wd;
    return std::exp(-sigma * tau) * t;
  }

  /// max|λ| of Φ = T₂ T₁ (Eigen's eigenvalues of the 2×2 product).
  double MaxAbsMultiplier(double mesh_frequency_hz, double epsilon) const {
    const double w2 = omega0() * omega0();
    const double tau = 0.5 / mesh_frequency_hz;
    const Eigen::Matrix2d phi =
        Transfer(w2 * (1.0 - epsilon), tau) * Transfer(w2 * (1.0 + epsilon), tau);
    return phi.eigenvalues().cwiseAbs().maxCoeff();
  }

  /// |tr Φ_y| − 2 cosh(σT): > 0 unstable, < 0 stable, 0 on a transition curve.
  double BoundaryFunction(double mesh_frequency_hz, double epsilon) const {
    const double sigma = zeta * omega0();
    const double T = 1.0 / mesh_frequency_hz;
    const double w2 = omega0() * omega0();
    const double o1 = std::sqrt(w2 * (1.0 + epsilon) - sigma * sigma);
    const double o2 = std::sqrt(w2 * (1.0 - epsilon) - sigma * sigma);
    const double a = 0.5 * o1 * T, b = 0.5 * o2 * T;
    const double tr =
        2.0 * std::cos(a) * std::cos(b) - (o1 / o2 + o2 / o1) * std::sin(a) * std::sin(b);
    return std::abs(tr) - 2.0 * std::cosh(sigma * T);
  }
};

}  // namespace geardyn::test
