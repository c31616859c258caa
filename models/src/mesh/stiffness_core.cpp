// The linear (B–S) mesh stiffness algebra (spec 01 §3, §5; B–S Eqs. 18–26, 39, 41).
#include "geardyn/models/mesh/stiffness_core.hpp"

#include <cmath>

#include "geardyn/common/check.hpp"

namespace geardyn {
namespace {

// Below this correlation 1 − K2₀₁² / (K2₀₀ K2₁₁) the two rows of K2 are parallel to rounding and
// the core is treated as rank 1 (a single point load, μ = κ²).
constexpr double kRankTol = 1e-10;
// Symmetry of a user-supplied core, relative to its largest entry (rounding of a product).
constexpr double kSymmetryTol = 1e-12;
// |c² + s² − 1| for a (cos, sin) pair given by the caller.
constexpr double kUnitTol = 1e-12;

void CheckCore(const Matrix2& K2) {
  GEARDYN_THROW_UNLESS(K2.allFinite(),
                       "K2: must be finite, got [" << K2.row(0) << "; " << K2.row(1) << "]");
  GEARDYN_THROW_UNLESS(
      std::abs(K2(0, 1) - K2(1, 0)) <= kSymmetryTol * K2.cwiseAbs().maxCoeff(),
      "K2: must be symmetric, got K2(0,1) = " << K2(0, 1) << " and K2(1,0) = " << K2(1, 0));
  GEARDYN_THROW_UNLESS(K2(0, 0) >= 0.0 && K2(1, 1) >= 0.0,
                       "K2: diagonal must be non-negative, got " << K2(0, 0) << ", " << K2(1, 1));
}

}  // namespace

Matrix2 CalcStiffnessCore(double K, double h, double mu, double half_face_width) {
  GEARDYN_THROW_UNLESS(std::isfinite(K) && K >= 0.0,
                       "K: mesh stiffness must be non-negative and finite, got " << K << " N/m");
  GEARDYN_THROW_UNLESS(std::isfinite(h), "h: load centre must be finite, got " << h << " m");
  GEARDYN_THROW_UNLESS(std::isfinite(mu), "mu: must be finite, got " << mu);
  GEARDYN_THROW_UNLESS(
      std::isfinite(half_face_width) && half_face_width > 0.0,
      "half_face_width: must be positive and finite, got " << half_face_width << " m");
  const double b = half_face_width;
  const double kappa = h / b;  // B–S Eq. (21e)
  // det K2 = K² b² (μ − κ²) ≥ 0: the core is PSD iff μ ≥ κ² (B–S Eq. 26b: μ = κ² + F²/(12b²)).
  GEARDYN_THROW_UNLESS(mu >= kappa * kappa * (1.0 - kCoreRoundoffTol),
                       "mu: " << mu << " is below kappa^2 = (h/b)^2 = " << kappa * kappa
                              << "; the stiffness core K2 would not be positive semi-definite");
  Matrix2 K2;
  K2 << K, -K * h, -K * h, K * mu * b * b;
  return K2;
}

Matrix12 CalcMeshStiffness(const Matrix2x12& G, const Matrix2& K2) {
  Matrix2x12 K2G;
  K2G.noalias() = K2 * G;
  // Gᵀ (K2 G), upper triangle only (inner dimension 2), then mirrored: exactly symmetric, and
  // 2.5× faster than Eigen's product here, which sends a 12×2·2×12 product down its general
  // matrix-matrix path (mesh_stiffness_benchmark).
  Matrix12 K_mesh;
  for (int c = 0; c < 12; ++c) {
    for (int r = 0; r <= c; ++r) K_mesh(r, c) = G(0, r) * K2G(0, c) + G(1, r) * K2G(1, c);
  }
  for (int c = 0; c < 12; ++c) {
    for (int r = c + 1; r < 12; ++r) K_mesh(r, c) = K_mesh(c, r);
  }
  return K_mesh;
}

Vector12 CalcMeshLoad(const Matrix2x12& G, const Matrix2& K2, const Vector2& epsilon) {
  Vector2 K2e;
  K2e.noalias() = K2 * epsilon;
  Vector12 f;
  f.noalias() = G.row(0).transpose() * K2e(0) + G.row(1).transpose() * K2e(1);
  return f;
}

Vector2 CalcTransmissionErrorPair(const Matrix2& K2, double k_e_integral,
                                  double k_sigma_e_integral) {
  CheckCore(K2);
  GEARDYN_THROW_UNLESS(std::isfinite(k_e_integral),
                       "k_e_integral: must be finite, got " << k_e_integral << " N");
  GEARDYN_THROW_UNLESS(std::isfinite(k_sigma_e_integral),
                       "k_sigma_e_integral: must be finite, got " << k_sigma_e_integral << " N*m");
  // Spec 01 §3: the linear term of U is −δᵀ [∫ke, −∫kσe] = −δᵀ K2 ε.
  const Vector2 rhs(k_e_integral, -k_sigma_e_integral);
  const double a = K2(0, 0);
  const double d = K2(1, 1);
  const double c = 0.5 * (K2(0, 1) + K2(1, 0));
  const double det = a * d - c * c;
  if (a > 0.0 && d > 0.0 && det > kRankTol * a * d) {
    return Vector2(d * rhs(0) - c * rhs(1), a * rhs(1) - c * rhs(0)) / det;
  }
  // Rank ≤ 1 (reduced cores K diag(1, 0), a point load μ = κ², or no contact): the solution with
  // ε_ζ = 0 that satisfies the normal-force equation exactly. For consistent integrals
  // (rhs in the range of K2) it gives the same load K2 ε as the pseudo-inverse, and a uniform
  // separation e still gives ε = [e, 0].
  if (a > 0.0) return Vector2(rhs(0) / a, 0.0);
  if (d > 0.0) return Vector2(0.0, rhs(1) / d);
  return Vector2::Zero();
}

Matrix2 CalcDampingCore(const Matrix2& K2, double c_m) {
  GEARDYN_THROW_UNLESS(
      std::isfinite(c_m) && c_m >= 0.0,
      "c_m: mesh damping must be non-negative and finite, got " << c_m << " N*s/m");
  CheckCore(K2);
  // B–S Eq. (39): C2 = c_m / K · K2; an empty mesh (K = 0) has no damping either.
  if (K2(0, 0) == 0.0) return Matrix2::Zero();
  return (c_m / K2(0, 0)) * K2;
}

Matrix12 CalcMeshDamping(const Matrix2x12& G, const Matrix2& K2, double c_m) {
  return CalcMeshStiffness(G, CalcDampingCore(K2, c_m));
}

double CalcMeshDampingCoefficient(double damping_ratio, double K, double equivalent_mass) {
  GEARDYN_THROW_UNLESS(std::isfinite(damping_ratio) && damping_ratio >= 0.0,
                       "damping_ratio: must be non-negative and finite, got " << damping_ratio);
  GEARDYN_THROW_UNLESS(std::isfinite(K) && K >= 0.0,
                       "K: mesh stiffness must be non-negative and finite, got " << K << " N/m");
  GEARDYN_THROW_UNLESS(
      std::isfinite(equivalent_mass) && equivalent_mass > 0.0,
      "equivalent_mass: must be positive and finite, got " << equivalent_mass << " kg");
  return 2.0 * damping_ratio * std::sqrt(K * equivalent_mass);
}

Matrix2 CalcLevelCore(MeshCoreLevel level, double K, double h, double mu, double half_face_width) {
  const Matrix2 K2 = CalcStiffnessCore(K, h, mu, half_face_width);
  switch (level) {
    case MeshCoreLevel::kBlankenshipSingh:
      return K2;
    case MeshCoreLevel::kCoupling4Dof:
    case MeshCoreLevel::kTorsional:
      // κ = 0 and the μ term dropped (B–S §5.3): only the normal approach is loaded.
      return Matrix2{{K, 0.0}, {0.0, 0.0}};
  }
  return K2;
}

TorsionalCore CalcTorsionalCore(const Matrix2x12& G, double K) {
  GEARDYN_THROW_UNLESS(std::isfinite(K) && K >= 0.0,
                       "K: mesh stiffness must be non-negative and finite, got " << K << " N/m");
  // G(0, 0:2) = η = cos ψ v + sin ψ Z, so its transverse length is cos ψ_b.
  const double cos_psi = std::hypot(G(0, 0), G(0, 1));
  GEARDYN_THROW_UNLESS(G.allFinite() && cos_psi > 0.0,
                       "G: its normal row has no transverse part (|eta_xy| = " << cos_psi << ")");
  TorsionalCore core;
  core.k = K * cos_psi * cos_psi;
  core.pinion_arm = G(0, 5) / cos_psi;
  core.gear_arm = G(0, 11) / cos_psi;
  return core;
}

Matrix12 CalcTorsionalMeshStiffness(const TorsionalCore& core) {
  Matrix12 K_mesh = Matrix12::Zero();
  K_mesh(5, 5) = core.k * core.pinion_arm * core.pinion_arm;
  K_mesh(5, 11) = core.k * core.pinion_arm * core.gear_arm;
  K_mesh(11, 5) = K_mesh(5, 11);
  K_mesh(11, 11) = core.k * core.gear_arm * core.gear_arm;
  return K_mesh;
}

Matrix6 CalcBsKo(double K, double kappa, double mu, double cos_psi_b, double sin_psi_b) {
  GEARDYN_THROW_UNLESS(std::isfinite(K) && K >= 0.0,
                       "K: mesh stiffness must be non-negative and finite, got " << K << " N/m");
  GEARDYN_THROW_UNLESS(std::isfinite(kappa), "kappa: must be finite, got " << kappa);
  GEARDYN_THROW_UNLESS(std::isfinite(mu), "mu: must be finite, got " << mu);
  GEARDYN_THROW_UNLESS(mu >= kappa * kappa * (1.0 - kCoreRoundoffTol),
                       "mu: " << mu << " is below kappa^2 = " << kappa * kappa
                              << "; K_o would not be positive semi-definite");
  GEARDYN_THROW_UNLESS(std::isfinite(cos_psi_b) && cos_psi_b > 0.0,
                       "cos_psi_b: must be positive and finite, got " << cos_psi_b);
  GEARDYN_THROW_UNLESS(
      std::isfinite(sin_psi_b) &&
          std::abs(cos_psi_b * cos_psi_b + sin_psi_b * sin_psi_b - 1.0) <= kUnitTol,
      "sin_psi_b: cos_psi_b^2 + sin_psi_b^2 must be 1, got " << cos_psi_b << ", " << sin_psi_b);
  // B–S Eq. (41b): K_o = K [g gᵀ + (μ − κ²) e4 e4ᵀ], g = (0, c, s, κ, −s, c).
  Vector6 g;
  g << 0.0, cos_psi_b, sin_psi_b, kappa, -sin_psi_b, cos_psi_b;
  Matrix6 Ko;
  Ko.noalias() = K * g * g.transpose();
  Ko(3, 3) += K * (mu - kappa * kappa);
  return Ko;
}

Matrix2x6 CalcBsDeflectionProjection(double cos_psi_b, double sin_psi_b, double half_face_width) {
  GEARDYN_THROW_UNLESS(
      std::isfinite(half_face_width) && half_face_width > 0.0,
      "half_face_width: must be positive and finite, got " << half_face_width << " m");
  Matrix2x6 P = Matrix2x6::Zero();
  // δ_η = g₀·δ_BS (the κ-free part of g), δ_ζ = −δ_BS,4 / b (mesh_jacobian.hpp).
  P(0, 1) = cos_psi_b;
  P(0, 2) = sin_psi_b;
  P(0, 4) = -sin_psi_b;
  P(0, 5) = cos_psi_b;
  P(1, 3) = -1.0 / half_face_width;
  return P;
}

Vector6 CalcBsTransmissionError(const Vector2& epsilon, double half_face_width, double cos_psi_b) {
  GEARDYN_THROW_UNLESS(
      std::isfinite(half_face_width) && half_face_width > 0.0,
      "half_face_width: must be positive and finite, got " << half_face_width << " m");
  GEARDYN_THROW_UNLESS(std::isfinite(cos_psi_b) && cos_psi_b > 0.0,
                       "cos_psi_b: must be positive and finite, got " << cos_psi_b);
  GEARDYN_THROW_UNLESS(epsilon.allFinite(), "epsilon: must be finite, got " << epsilon.transpose());
  Vector6 te = Vector6::Zero();
  te(1) = epsilon(0) / cos_psi_b;         // B–S Eq. (42): the line-of-action entry (Eq. 20)
  te(3) = -half_face_width * epsilon(1);  // rocking entry, −b ε_ζ
  return te;
}

}  // namespace geardyn
