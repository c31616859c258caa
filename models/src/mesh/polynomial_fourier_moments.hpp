/// @file
/// @brief Exact Fourier transforms of piecewise polynomials (internal to the mesh models): the
/// Chebyshev fit of a piece and the moments M_r(z) = ∫_{−1}^{1} t^r e^{−izt} dt, shared by the
/// contact-line series (5 nodes) and the transmission-error line transform (6 nodes).
#pragma once

#include <Eigen/Core>
#include <Eigen/LU>
#include <array>
#include <cmath>
#include <complex>

#include "geardyn/common/units.hpp"

namespace geardyn::internal {

/// @brief Chebyshev nodes t_i = cos((2i+1)π/(2N)) on [−1, 1] and the inverse of their Vandermonde
/// matrix V(i, r) = t_i^r: N values at the nodes fit a polynomial of degree < N exactly.
template <int N>
struct ChebyshevFit {
  std::array<double, N> nodes{};
  Eigen::Matrix<double, N, N> inverse_vandermonde;
  ChebyshevFit() {
    Eigen::Matrix<double, N, N> v;
    for (int i = 0; i < N; ++i) {
      nodes[i] = std::cos((2.0 * i + 1.0) * kPi / (2.0 * N));
      for (int r = 0; r < N; ++r) v(i, r) = std::pow(nodes[i], r);
    }
    inverse_vandermonde = v.inverse();
  }
};

/// The N-node fit, built once.
template <int N>
const ChebyshevFit<N>& GetChebyshevFit() {
  static const ChebyshevFit<N> fit;
  return fit;
}

/// @brief M_r(z) = ∫_{−1}^{1} t^r e^{−izt} dt for r = 0..N−1.
template <int N>
std::array<std::complex<double>, N> MomentIntegrals(double z) {
  static_assert(N >= 1 && N <= 6, "the recursion for |z| >= 2 is checked for r <= 5 only");
  // C_r = ∫_0^1 t^r cos(zt) dt, S_r = ∫_0^1 t^r sin(zt) dt.
  std::array<double, N> c{}, s{};
  if (std::abs(z) < 2.0) {
    // Power series C_r = Σ_k (−1)^k z^{2k}/(2k)!/(r+2k+1), S_r = Σ_k (−1)^k
    // z^{2k+1}/(2k+1)!/(r+2k+2) (terms ≤ e^2, 40 terms reach round-off).
    for (int r = 0; r < N; ++r) {
      double term = 1.0;  // z^m / m!
      double sum_c = 0.0, sum_s = 0.0;
      for (int m = 0; m < 40; ++m) {
        if (m > 0) term *= z / m;
        const double sign = ((m / 2) % 2 == 0) ? 1.0 : -1.0;
        if (m % 2 == 0) {
          sum_c += sign * term / (r + m + 1);
        } else {
          sum_s += sign * term / (r + m + 1);
        }
      }
      c[r] = sum_c;
      s[r] = sum_s;
    }
  } else {
    // Integration by parts, stable for |z| ≥ 2 and r ≤ 5 (amplification ≤ r!/|z|^r: ≤ 1.5 for
    // r ≤ 4, ≤ 3.75 for r = 5): C_r = sin z/z − (r/z) S_{r−1}, S_r = −cos z/z + (r/z) C_{r−1}.
    const double sz = std::sin(z), cz = std::cos(z);
    c[0] = sz / z;
    s[0] = (1.0 - cz) / z;
    for (int r = 1; r < N; ++r) {
      c[r] = sz / z - r / z * s[r - 1];
      s[r] = -cz / z + r / z * c[r - 1];
    }
  }
  std::array<std::complex<double>, N> m{};
  for (int r = 0; r < N; ++r) {
    m[r] = (r % 2 == 0) ? std::complex<double>(2.0 * c[r], 0.0)
                        : std::complex<double>(0.0, -2.0 * s[r]);
  }
  return m;
}

/// @brief Adds ∫_{mid−w}^{mid+w} q_c(x) e^{−iωx} dx to (*sum)[c] for every channel c, where
/// q_c(mid + w t) = Σ_r alpha(c, r) t^r (N = alpha's columns) and w = half_width:
/// the integral is w e^{−iω·mid} Σ_r alpha(c, r) M_r(ω w).
template <int N, class Alpha, class Sum>
void AddPieceTransform(const Alpha& alpha, double mid, double half_width, double omega, Sum* sum) {
  static_assert(Alpha::ColsAtCompileTime == N);
  const std::array<std::complex<double>, N> m = MomentIntegrals<N>(omega * half_width);
  const std::complex<double> phase = std::polar(half_width, -omega * mid);
  for (Eigen::Index c = 0; c < alpha.rows(); ++c) {
    std::complex<double> acc(0.0, 0.0);
    for (int r = 0; r < N; ++r) acc += alpha(c, r) * m[r];
    (*sum)[c] += phase * acc;
  }
}

}  // namespace geardyn::internal
