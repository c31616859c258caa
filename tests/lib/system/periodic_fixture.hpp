/// @file
/// @brief Test fixture for the periodic-structure tests: a pinion driving two wheels through two
/// hand-built meshes (hand_pair.hpp's Jacobian) whose cores and phase offsets the test chooses.
#pragma once

#include <numbers>

#include "hand_pair.hpp"

namespace geardyn::test {

/// A spur rectangular wave: K = k_hi on [0, 2π(ε−1)), k_lo elsewhere, plus a mesh-period
/// shift `start` [rad] (K·h = 0, K·μb² = K b²/3).
inline PiecewiseConstantCoefficient SpurWave(double k_lo, double k_hi, double contact_ratio,
                                             double start = 0.0, double b = 0.0125) {
  const double two_pi = 2.0 * std::numbers::pi;
  const double split = two_pi * (contact_ratio - 1.0);
  VectorX breakpoints(2);
  breakpoints << start, start + split;
  MatrixX values(3, 2);
  values << k_hi, k_lo, 0.0, 0.0, k_hi * b * b / 3.0, k_lo * b * b / 3.0;
  return PiecewiseConstantCoefficient(breakpoints, values);
}

/// A smooth helical-like core: K = k (1 + a cos θ + c sin 2θ), K·h and K·μb² with their own
/// small harmonics (K2 stays positive definite for a, c small).
inline FourierCoefficient SmoothStiffness(double k, double a, double c, double b = 0.0125) {
  const Vector3 mean(k, 0.0, k * b * b / 3.0);
  MatrixX cosines = MatrixX::Zero(3, 2), sines = MatrixX::Zero(3, 2);
  cosines(0, 0) = a * k;
  sines(0, 1) = c * k;
  cosines(1, 0) = 0.02 * k * b;
  sines(2, 0) = 0.05 * k * b * b / 3.0;
  return FourierCoefficient::FromCosSin(mean, cosines, sines);
}

/// Pinion (body 0) driving wheel A (body 1) through "mesh-a" and wheel B (body 2) through
/// "mesh-b"; the bearings' y stiffness is `bearing_y_factor` × the others'. `ratio_b` ≠ 1 runs
/// mesh-b at another frequency (the LTV equations of a two-stage train; kinematically one pinion
/// cannot do that, but the solvers see only the equations).
inline SystemBuilder TwoMeshBuilder(const MeshCore& core_a, const MeshCore& core_b,
                                    double offset_b = 0.0, double bearing_y_factor = 1.0,
                                    double ratio_b = 1.0) {
  const HandPairParams p;
  SystemBuilder builder;
  const BodyIndex pinion = builder.AddBody("pinion", DiagMass(p.m1, p.Id1, p.I1));
  const BodyIndex a = builder.AddBody("wheel-a", DiagMass(p.m2, p.Id2, p.I2), Vector3(0.13, 0, 0));
  const BodyIndex b =
      builder.AddBody("wheel-b", DiagMass(0.7 * p.m2, p.Id2, 0.8 * p.I2), Vector3(-0.13, 0, 0));
  Vector6 kb;
  kb << p.bearing, bearing_y_factor * p.bearing, p.bearing, 0.01 * p.bearing, 0.01 * p.bearing, 0.0;
  for (const BodyIndex body : {pinion, a, b}) {
    builder.AddElement("bearing" + std::to_string(body.value()), ElementKind::kBearing, {body},
                       MatrixX(kb.asDiagonal()));
  }
  builder.AddMesh("mesh-a", pinion, a, HandPairJacobian(p), core_a);
  builder.AddMesh("mesh-b", pinion, b, HandPairJacobian(p), core_b, std::nullopt, ratio_b,
                  offset_b);
  return builder;
}

/// TwoMeshBuilder(…).Build().
inline SystemModel TwoMeshSystem(const MeshCore& core_a, const MeshCore& core_b,
                                 double offset_b = 0.0) {
  return TwoMeshBuilder(core_a, core_b, offset_b).Build();
}

}  // namespace geardyn::test
