/// @file
/// @brief Helpers shared by the Floquet tests: multiplier matching, the closed-form Meissner
/// multipliers and the hand-built 12-DOF pair of tests/lib/system (hand_pair.hpp).
#pragma once

#include <complex>
#include <limits>
#include <string>
#include <vector>

#include "../../lib/system/periodic_fixture.hpp"
#include "geardyn/analyses/floquet.hpp"
#include "geardyn/analyses/floquet_system.hpp"
#include "geardyn/models/elements/shaft_beam.hpp"

namespace geardyn::test {

/// Largest distance between the multipliers of a and b after greedy nearest matching (sizes equal).
inline double MultiplierDistance(const VectorXc& a, const VectorXc& b) {
  if (a.size() != b.size()) return std::numeric_limits<double>::infinity();
  std::vector<bool> used(b.size(), false);
  double worst = 0.0;
  for (int i = 0; i < a.size(); ++i) {
    int best = -1;
    for (int j = 0; j < b.size(); ++j) {
      if (!used[j] && (best < 0 || std::abs(a[i] - b[j]) < std::abs(a[i] - b[best]))) best = j;
    }
    used[best] = true;
    worst = std::max(worst, std::abs(a[i] - b[best]));
  }
  return worst;
}

/// Closed-form transfer matrix of x'' + k x = 0 over τ: [[cos ωτ, sin ωτ/ω], [−ω sin ωτ, cos ωτ]],
/// ω = √k (complex for k < 0: cos → cosh). Real result.
inline Eigen::Matrix2d ConstantTransfer(double k, double tau) {
  const std::complex<double> w = std::sqrt(std::complex<double>(k));
  const std::complex<double> c = std::cos(w * tau), s = std::sin(w * tau) / w;
  Eigen::Matrix2d T;
  T << c.real(), s.real(), (-k * s).real(), c.real();
  return T;
}

/// Trace of the Meissner monodromy T(k_lo, τ_lo) T(k_hi, τ_hi):
/// 2 cos ω1τ1 cos ω2τ2 − (ω1/ω2 + ω2/ω1) sin ω1τ1 sin ω2τ2 (det = 1).
inline double MeissnerTrace(double k_hi, double k_lo, double tau_hi, double tau_lo) {
  return (ConstantTransfer(k_lo, tau_lo) * ConstantTransfer(k_hi, tau_hi)).trace();
}

/// Roots of λ² − tr λ + 1 = 0.
inline VectorXc MeissnerMultipliers(double trace) {
  const std::complex<double> d = std::sqrt(std::complex<double>(0.25 * trace * trace - 1.0));
  VectorXc l(2);
  l << 0.5 * trace + d, 0.5 * trace - d;
  return l;
}

/// The hand pair (12 DOF, one free rotation) with a given core; undamped unless the core says so.
inline SystemModel HandPair(const MeshCore& core) {
  const HandPairParams p;
  return HandPairBuilder(p, core).Build();
}

/// Spur rectangular-wave core of the hand pair (contact ratio 1.6, ±25 % about 4e8 N/m).
inline LinearMeshCore HandSpurWaveCore(double c_m = 0.0) {
  return LinearMeshCore(MeshCoreLevel::kBlankenshipSingh, SpurWave(3e8, 5e8, 1.6), 0.0125,
                        std::nullopt, MeshDamping::FromCoefficient(c_m));
}

/// Smooth helical-like core K = k (1 + a cos θ + c sin 2θ).
inline LinearMeshCore HandSmoothCore(double a = 0.2, double c = 0.05, double c_m = 0.0) {
  return LinearMeshCore(MeshCoreLevel::kBlankenshipSingh, SmoothStiffness(4e8, a, c), 0.0125,
                        std::nullopt, MeshDamping::FromCoefficient(c_m));
}

/// Two steel shafts (along Z, 0.3 m, Ø 40 mm, `elements` Timoshenko elements each, bearings at both
/// ends with no torsional stiffness) carrying the hand pair's pinion and wheel at their middle
/// nodes, meshing through `core`: 12·(elements + 1) DOFs, one free rotation. `shaft_beta` [s]:
/// stiffness-proportional damping C_e = β K_e of every shaft element (0: undamped shafts).
inline SystemModel GearedShafts(int elements, const MeshCore& core, double shaft_beta = 0.0) {
  const HandPairParams p;
  SystemBuilder b;
  const double length = 0.3, h = length / elements;
  ShaftBeam beam;
  beam.section.outer_diameter = 0.04;
  beam.material = ShaftMaterial::FromPoissonRatio(2.1e11, 0.3, 7850.0);
  beam.node_b = Vector3(0.0, 0.0, h);
  const MatrixX K = CalcShaftBeamStiffness(beam), M = CalcShaftBeamMass(beam);
  Vector6 kb;
  kb << p.bearing, p.bearing, p.bearing, 0.0, 0.0, 0.0;
  BodyIndex gears[2];
  for (int s = 0; s < 2; ++s) {
    const double x = s == 0 ? 0.0 : p.r1 + p.r2;
    std::vector<BodyIndex> nodes;
    for (int i = 0; i <= elements; ++i) {
      const bool gear = 2 * i == elements;
      const Matrix6 mass = !gear    ? Matrix6::Zero()
                           : s == 0 ? DiagMass(p.m1, p.Id1, p.I1)
                                    : DiagMass(p.m2, p.Id2, p.I2);
      nodes.push_back(b.AddBody("s" + std::to_string(s) + "n" + std::to_string(i), mass,
                                Vector3(x, 0.0, i * h)));
      if (gear) gears[s] = nodes.back();
    }
    for (int i = 0; i < elements; ++i) {
      b.AddElement("shaft" + std::to_string(s) + "_" + std::to_string(i), ElementKind::kShaft,
                   {nodes[i], nodes[i + 1]}, K,
                   shaft_beta > 0.0 ? MatrixX(shaft_beta * K) : MatrixX(), M);
    }
    for (const int end : {0, elements}) {
      b.AddElement("bearing" + std::to_string(s) + "_" + std::to_string(end), ElementKind::kBearing,
                   {nodes[end]}, MatrixX(kb.asDiagonal()));
    }
  }
  b.AddMesh("mesh", gears[0], gears[1], HandPairJacobian(p), core);
  return b.Build();
}

/// Options at mesh frequency f_m [Hz] with `method` and a 1e-10 tolerance.
inline FloquetOptions FloquetAt(double f_m, FloquetMethod method) {
  FloquetOptions o;
  o.mesh_frequency_hz = f_m;
  o.method = method;
  o.tolerance = 1e-10;
  return o;
}

// Two hand pairs that do not touch (several_frequencies_test.cpp, incommensurate_test.cpp).
// Pair a (bodies 0, 1, mesh "a", ratio 1) and pair b (bodies 2, 3, mesh "b", ratio r), apart.
inline SystemModel TwoSeparatePairs(const MeshCore& core_a, const MeshCore& core_b,
                                    double ratio_b) {
  const HandPairParams p;
  SystemBuilder builder;
  Vector6 kb;
  kb << p.bearing, p.bearing, p.bearing, 0.01 * p.bearing, 0.01 * p.bearing, 0.0;
  for (const char* pair : {"a", "b"}) {
    const double z = pair[0] == 'a' ? 0.0 : 0.5;
    const BodyIndex i = builder.AddBody(std::string("pinion-") + pair, DiagMass(p.m1, p.Id1, p.I1),
                                        Vector3(0, 0, z));
    const BodyIndex j = builder.AddBody(std::string("wheel-") + pair, DiagMass(p.m2, p.Id2, p.I2),
                                        Vector3(p.r1 + p.r2, 0, z));
    for (const BodyIndex body : {i, j}) {
      builder.AddElement(std::string("bearing-") + pair + std::to_string(body.value()),
                         ElementKind::kBearing, {body}, MatrixX(kb.asDiagonal()));
    }
    if (pair[0] == 'a') {
      builder.AddMesh("a", i, j, HandPairJacobian(p), core_a);
    } else {
      builder.AddMesh("b", i, j, HandPairJacobian(p), core_b, std::nullopt, ratio_b, 0.4);
    }
  }
  return builder.Build();
}

}  // namespace geardyn::test
