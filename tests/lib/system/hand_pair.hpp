/// @file
/// @brief Test fixture for the system tests: a hand-built spur pair (no geardyn::models), with
/// the line of action along +Y and zero pressure angle, so that G is known in closed form:
/// δ_η = y_i − y_j + r1 θz_i + r2 θz_j, δ_ζ = θx_i − θx_j.
#pragma once

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <vector>

#include "geardyn/common/errors.hpp"
#include "geardyn/system/system_builder.hpp"

namespace geardyn::test {

struct HandPairParams {
  double r1 = 0.04, r2 = 0.09;      // base radii [m]
  double m1 = 1.2, m2 = 5.0;        // masses [kg]
  double I1 = 9e-4, I2 = 2.4e-2;    // polar inertias [kg m²]
  double Id1 = 5e-4, Id2 = 1.3e-2;  // diametral inertias [kg m²]
  double k = 4e8;                   // mean mesh stiffness [N/m]
  double b = 0.0125;                // half face width [m]
  double bearing = 5e8;             // translational and tilt bearing stiffness
  bool bearings = true;
};

inline Matrix2x12 HandPairJacobian(const HandPairParams& p) {
  Matrix2x12 G = Matrix2x12::Zero();
  G(0, 1) = 1.0;    // y_i
  G(0, 5) = p.r1;   // θz_i
  G(0, 7) = -1.0;   // y_j
  G(0, 11) = p.r2;  // θz_j
  G(1, 3) = 1.0;    // θx_i
  G(1, 9) = -1.0;   // θx_j
  return G;
}

inline Matrix6 DiagMass(double m, double Id, double I) {
  Vector6 d;
  d << m, m, m, Id, Id, I;
  return d.asDiagonal();
}

/// Spur LTI-like core: K2 = k diag(1, b²/3) (one full-face line, spec 01 §6).
inline LinearMeshCore SpurCore(const HandPairParams& p) {
  return LinearMeshCore(MeshCoreLevel::kBlankenshipSingh,
                        ConstantCoefficient(Vector3(p.k, 0.0, p.k * p.b * p.b / 3.0)), p.b);
}

inline SystemBuilder HandPairBuilder(const HandPairParams& p, const MeshCore& core) {
  SystemBuilder builder;
  const BodyIndex i = builder.AddBody("pinion", DiagMass(p.m1, p.Id1, p.I1));
  const BodyIndex j =
      builder.AddBody("wheel", DiagMass(p.m2, p.Id2, p.I2), Vector3(p.r1 + p.r2, 0, 0));
  if (p.bearings) {
    Vector6 kb;
    kb << p.bearing, p.bearing, p.bearing, 0.01 * p.bearing, 0.01 * p.bearing, 0.0;
    builder.AddElement("pinion-bearing", ElementKind::kBearing, {i}, MatrixX(kb.asDiagonal()));
    builder.AddElement("wheel-bearing", ElementKind::kBearing, {j}, MatrixX(kb.asDiagonal()));
  }
  builder.AddMesh("mesh", i, j, HandPairJacobian(p), core);
  return builder;
}

/// Sorted generalized eigenvalues of (K, M).
inline VectorX SortedEigenvalues(const MatrixX& K, const MatrixX& M) {
  Eigen::GeneralizedSelfAdjointEigenSolver<MatrixX> eig(K, M, Eigen::EigenvaluesOnly);
  VectorX values = eig.eigenvalues();
  std::sort(values.data(), values.data() + values.size());
  return values;
}

}  // namespace geardyn::test
