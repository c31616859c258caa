/// @file
/// @brief Helpers of the numerical stress suite, part A (eigen, Floquet, charts): finiteness
/// checks on result structs, hand-built systems with closed-form answers (spring chains in the
/// six directions of a body, the torsional gear pair on its two θz coordinates) and the
/// closed-form Meissner monodromy those systems reduce to. Independent of the analyses: every
/// truth here is a formula, never a call into geardyn's solvers.
#pragma once

#include <Eigen/Dense>
#include <algorithm>
#include <cctype>
#include <cmath>
#include <complex>
#include <numbers>
#include <string>
#include <vector>

#include "geardyn/common/eigen_types.hpp"
#include "geardyn/system/coefficient.hpp"
#include "geardyn/system/mesh_core.hpp"
#include "geardyn/system/system_builder.hpp"
#include "geardyn/system/system_model.hpp"

namespace geardyn::stress {

inline constexpr double kPi = std::numbers::pi;
inline constexpr double kTwoPi = 2.0 * std::numbers::pi;

/// True when every entry is finite (real or complex).
template <typename Derived>
bool AllFinite(const Eigen::DenseBase<Derived>& m) {
  for (Eigen::Index j = 0; j < m.cols(); ++j) {
    for (Eigen::Index i = 0; i < m.rows(); ++i) {
      const auto v = m(i, j);
      if constexpr (requires { v.real(); }) {
        if (!std::isfinite(v.real()) || !std::isfinite(v.imag())) return false;
      } else {
        if (!std::isfinite(v)) return false;
      }
    }
  }
  return true;
}

/// True when `text` contains "nan" or "inf" as a JSON/CSV number (case-insensitive, not inside a
/// longer word such as "info" or "infinity_norm" — a number token is delimited by , : [ ] space).
inline bool HasNonFiniteToken(const std::string& text) {
  std::string lower(text);
  std::transform(lower.begin(), lower.end(), lower.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  const auto is_delim = [](char c) {
    return c == ',' || c == ':' || c == '[' || c == ']' || c == ' ' || c == '\n' || c == '\t' ||
           c == '"' || c == '-' || c == '+' || c == '\r';
  };
  for (const std::string token : {"nan", "inf"}) {
    for (std::size_t p = lower.find(token); p != std::string::npos; p = lower.find(token, p + 1)) {
      const bool left = p == 0 || is_delim(lower[p - 1]);
      const std::size_t end = p + 3;
      const bool right =
          end >= lower.size() || is_delim(lower[end]) || lower.compare(end, 5, "inity") == 0;
      if (left && right) return true;
    }
  }
  return false;
}

/// Diagonal 6×6 body mass (m, m, m, J, J, J) with per-direction values.
inline Matrix6 DiagMass6(const Vector6& d) { return d.asDiagonal(); }

/// 12×12 stiffness of six uncoupled springs k_d between the same directions of two bodies.
inline MatrixX Spring12(const Vector6& k) {
  MatrixX K = MatrixX::Zero(12, 12);
  for (int d = 0; d < 6; ++d) {
    K(d, d) = K(d + 6, d + 6) = k(d);
    K(d, d + 6) = K(d + 6, d) = -k(d);
  }
  return K;
}

/// A fixed–fixed chain of `num_bodies` identical bodies (mass diagonal `mass`) joined by springs
/// `k` (six uncoupled directions) and tied to ground at both ends by the same springs. Each
/// direction d is an independent chain: λ_{j,d} = 4 (k_d/m_d) sin²(jπ/(2(N+1))), j = 1 … N.
inline SystemModel MakeSixWayChain(int num_bodies, const Vector6& mass, const Vector6& k,
                                   double ground_factor = 1.0) {
  SystemBuilder b;
  std::vector<BodyIndex> bodies;
  bodies.reserve(static_cast<std::size_t>(num_bodies));
  for (int i = 0; i < num_bodies; ++i) {
    bodies.push_back(b.AddBody("b" + std::to_string(i), DiagMass6(mass)));
  }
  const MatrixX ground = MatrixX((ground_factor * k).asDiagonal());
  b.AddElement("ground_left", ElementKind::kSpring, {bodies.front()}, ground);
  b.AddElement("ground_right", ElementKind::kSpring, {bodies.back()}, ground);
  const MatrixX K = Spring12(k);
  for (int i = 0; i + 1 < num_bodies; ++i) {
    b.AddElement("s" + std::to_string(i), ElementKind::kSpring, {bodies[i], bodies[i + 1]}, K);
  }
  return b.Build();
}

/// The lowest `count` eigenvalues of MakeSixWayChain (ground_factor 1), ascending [rad²/s²].
inline std::vector<double> SixWayChainEigenvalues(int num_bodies, const Vector6& mass,
                                                  const Vector6& k, int count) {
  std::vector<double> all;
  const int per_direction = std::min(num_bodies, count);
  for (int d = 0; d < 6; ++d) {
    for (int j = 1; j <= per_direction; ++j) {
      const double s = std::sin(j * kPi / (2.0 * (num_bodies + 1)));
      all.push_back(4.0 * k(d) / mass(d) * s * s);
    }
  }
  std::sort(all.begin(), all.end());
  all.resize(static_cast<std::size_t>(std::min<int>(count, static_cast<int>(all.size()))));
  return all;
}

/// Parameters of the torsional gear pair (SI unless the caller scales them consistently).
struct TorsionalPair {
  double I1 = 2.0e-3, I2 = 7.5e-3;    ///< polar inertias [kg·m²]
  double r1 = 0.03, r2 = 0.055;       ///< base radii [m]
  double k_lo = 3.0e8, k_hi = 4.5e8;  ///< mesh stiffness on the two intervals [N/m]
  double duty = 0.6;                  ///< fraction of the mesh period at k_hi (contact ratio − 1)
  double c_m = 0.0;                   ///< mesh damping [N·s/m]
  double half_face_width = 0.01;      ///< b [m] (not used by the torsional level)

  /// s = r1²/I1 + r2²/I2 [1/kg]: δ'' + c_m s δ' + k(θ) s δ = 0 for δ = r1 θ1 + r2 θ2.
  double s() const { return r1 * r1 / I1 + r2 * r2 / I2; }
  /// The same pair in mm–t–s units (lengths ×1e3, masses ×1e-3, so I ×1e3, k [N/mm] ×1e-3,
  /// c [N·s/mm] ×1e-3): every frequency and multiplier is unchanged.
  TorsionalPair InMillimetreTonneSecond() const {
    TorsionalPair p = *this;
    p.I1 *= 1e3;
    p.I2 *= 1e3;
    p.r1 *= 1e3;
    p.r2 *= 1e3;
    p.k_lo *= 1e-3;
    p.k_hi *= 1e-3;
    p.c_m *= 1e-3;
    p.half_face_width *= 1e3;
    return p;
  }
};

/// The torsional pair restricted to its two θz coordinates (one rigid rotation, one elastic
/// mesh mode), with a rectangular-wave mesh stiffness (k_hi on the first `duty` of the mesh
/// period), or constant k_lo when `constant`.
inline SystemModel MakeTorsionalPairModel(const TorsionalPair& p, bool constant = false) {
  SystemBuilder b;
  Vector6 m1, m2;
  m1 << 1.0, 1.0, 1.0, 1e-3, 1e-3, p.I1;
  m2 << 2.0, 2.0, 2.0, 3e-3, 3e-3, p.I2;
  const BodyIndex pinion = b.AddBody("pinion", DiagMass6(m1));
  const BodyIndex gear = b.AddBody("gear", DiagMass6(m2));
  Matrix2x12 G = Matrix2x12::Zero();
  G(0, 5) = p.r1;  // δ_η = r1 θz1 + r2 θz2
  G(0, 11) = p.r2;
  Coefficient stiffness = ConstantCoefficient((VectorX(3) << p.k_lo, 0.0, 0.0).finished());
  if (!constant) {
    VectorX breaks(2);
    breaks << 0.0, kTwoPi * p.duty;
    MatrixX values(3, 2);
    values << p.k_hi, p.k_lo, 0.0, 0.0, 0.0, 0.0;
    stiffness = PiecewiseConstantCoefficient(breaks, values);
  }
  b.AddMesh("mesh", pinion, gear, G,
            LinearMeshCore(MeshCoreLevel::kTorsional, std::move(stiffness), p.half_face_width,
                           std::nullopt, MeshDamping::FromCoefficient(p.c_m)));
  const SystemModel full = b.Build();
  return full.Restrict(
      {full.dof_map().dof(pinion, BodyDof::kThetaZ), full.dof_map().dof(gear, BodyDof::kThetaZ)});
}

/// Exact transfer matrix of x'' + 2σ x' + w2 x = 0 over τ on the state [x, x'] (w2 may be
/// negative; w2 − σ² ≠ 0).
inline Eigen::Matrix2d DampedTransfer(double w2, double sigma, double tau) {
  const std::complex<double> wd = std::sqrt(std::complex<double>(w2 - sigma * sigma));
  const std::complex<double> c = std::cos(wd * tau), sn = std::sin(wd * tau) / wd;
  Eigen::Matrix2d t;
  t << (c + sigma * sn).real(), sn.real(), (-w2 * sn).real(), (c - sigma * sn).real();
  return std::exp(-sigma * tau) * t;
}

/// Closed-form elastic multipliers of the pair at mesh frequency f_m (period 1/f_m): the
/// Meissner monodromy of δ, Φ = T(k_lo) T(k_hi) (k_hi first).
inline Eigen::Vector2cd PairElasticMultipliers(const TorsionalPair& p, double mesh_frequency_hz) {
  const double T = 1.0 / mesh_frequency_hz, sigma = 0.5 * p.c_m * p.s();
  const Eigen::Matrix2d phi = DampedTransfer(p.k_lo * p.s(), sigma, (1.0 - p.duty) * T) *
                              DampedTransfer(p.k_hi * p.s(), sigma, p.duty * T);
  return phi.eigenvalues();
}

/// max|λ| of a complex vector (NaN if any entry is NaN: no std::max swallowing).
inline double MaxAbs(const VectorXc& v) {
  double m = 0.0;
  for (Eigen::Index i = 0; i < v.size(); ++i) {
    const double a = std::abs(v[i]);
    if (std::isnan(a)) return a;
    m = std::max(m, a);
  }
  return m;
}

/// ‖ΦᵀMΦ − I‖_max (M-orthonormality of mode shapes).
inline double MOrthonormalityError(const MatrixX& shapes, const MatrixX& M) {
  const MatrixX g = shapes.transpose() * M * shapes;
  return (g - MatrixX::Identity(g.rows(), g.cols())).cwiseAbs().maxCoeff();
}

}  // namespace geardyn::stress
