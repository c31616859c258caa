/// @file
/// @brief Shared cases of the stress suite part B (harmonic balance and time domain): the
/// torsional gear pair as a damped SDOF oscillator with closed-form answers, in SI or in
/// mm–t–s units, and the "no NaN/Inf in a result" checks.
///
/// The pair (tests/lib/system/hand_pair.hpp restricted to θz of both gears): δ = r1 θ1 + r2 θ2
/// obeys m_e δ̈ + c δ̇ + k(θ) (δ − ε) = T/r1 + (T_a/r1) cos(mθ) with m_e = 1/(r1²/I1 + r2²/I2)
/// (the torques T, T r2/r1 and T_a, T_a r2/r1 are balanced: the rigid rotation is not loaded).
/// So with constant k, mesh order m = 1 and ε = 0 the DTE amplitude at ω = 2π f_m is the SDOF
/// FRF |X| = F/(k |1 − r² + 2iζr|), F = T_a/r1, r = ω/ω_n, ω_n = √(k/m_e).
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <numbers>
#include <optional>
#include <string>

#include "analyses/harmonic_balance/hb_fixtures.hpp"
#include "geardyn/analyses/harmonic_balance.hpp"
#include "geardyn/analyses/time_response.hpp"
#include "lib/system/hand_pair.hpp"
#include "lib/system/periodic_fixture.hpp"

namespace geardyn::stress {

constexpr double kPi = std::numbers::pi;

/// Consistent unit system: lengths × L, masses × Mu, seconds unchanged (SI: 1, 1; mm–t–s: 1e3,
/// 1e-3, forces N unchanged). Derived: stiffness N/m × Mu, inertia and torque × Mu L²,
/// damping coefficient × Mu.
struct Units {
  double L = 1.0;
  double Mu = 1.0;
  double force() const { return Mu * L; }
  double stiffness() const { return Mu; }
  double inertia() const { return Mu * L * L; }
  double torque() const { return Mu * L * L; }
};
inline constexpr Units kSi{1.0, 1.0};
inline constexpr Units kMmTonneSecond{1e3, 1e-3};

/// How the mesh stiffness varies with θ.
enum class StiffnessShape {
  kConstant,  ///< k
  kCosine,    ///< k (1 + a cos θ): smooth, quasi-static DTE F/k(θ) in closed form
  kSpurWave,  ///< rectangular wave k_hi / k_lo (contact ratio 1.6), mean k: slow Fourier decay
};

/// The SDOF torsional pair (SI values; `units` converts them at the input boundary).
struct SdofPair {
  test::HandPairParams p;        // r1, r2, I1, I2, k (mean), b
  double torque = 150.0;         // T [N·m]
  double harmonic_torque = 0.0;  // T_a [N·m], order 1
  double zeta = 0.05;            // ζ of the mesh mode (mesh damping coefficient c = 2ζ√(k m_e))
  double e1 = 0.0;               // ε_η = e1 cos θ [m]
  StiffnessShape shape = StiffnessShape::kConstant;
  double a = 0.3;  // kCosine amplitude [-]
  Units units = kSi;

  double MeanMass() const { return 1.0 / (p.r1 * p.r1 / p.I1 + p.r2 * p.r2 / p.I2); }
  double NaturalRadPerS() const { return std::sqrt(p.k / MeanMass()); }
  double NaturalHz() const { return NaturalRadPerS() / (2.0 * kPi); }
  double Damping() const { return 2.0 * zeta * std::sqrt(p.k * MeanMass()); }
  double MeanForce() const { return torque / p.r1; }
  double AlternatingForce() const { return harmonic_torque / p.r1; }
  /// Static mean deflection T/(r1 k) [m, SI].
  double StaticDeflection() const { return MeanForce() / p.k; }
  /// Closed-form DTE amplitude of order 1 at f_m [m, SI] (constant k, ε = 0).
  double FrfAmplitude(double f_m) const {
    const double r = 2.0 * kPi * f_m / NaturalRadPerS();
    return AlternatingForce() / (p.k * std::abs(std::complex<double>(1.0 - r * r, 2.0 * zeta * r)));
  }

  LinearMeshCore Core() const {
    const Units& u = units;
    const double k = p.k * u.stiffness(), b = p.b * u.L;
    std::optional<Coefficient> eps;
    if (e1 != 0.0) eps = Coefficient(test::SmoothTransmissionError(e1 * u.L, 0.0, 0.0));
    Coefficient stiffness = ConstantCoefficient(Vector3(k, 0.0, k * b * b / 3.0));
    if (shape == StiffnessShape::kCosine) {
      MatrixX cosines = MatrixX::Zero(3, 1), sines = MatrixX::Zero(3, 1);
      cosines(0, 0) = a * k;
      cosines(2, 0) = a * k * b * b / 3.0;
      stiffness = FourierCoefficient::FromCosSin(Vector3(k, 0.0, k * b * b / 3.0), cosines, sines);
    } else if (shape == StiffnessShape::kSpurWave) {
      // Mean k: 0.6 k_hi + 0.4 k_lo = k with k_hi = 1.25 k.
      stiffness = test::SpurWave(0.625 * k, 1.25 * k, 1.6, 0.0, b);
    }
    return LinearMeshCore(MeshCoreLevel::kBlankenshipSingh, stiffness, b, eps,
                          MeshDamping::FromCoefficient(Damping() * u.stiffness()));
  }

  SystemModel Model() const { return ModelWith(Core()); }

  SystemModel ModelWith(const MeshCore& core) const {
    const Units& u = units;
    test::HandPairParams q = p;
    q.r1 *= u.L;
    q.r2 *= u.L;
    q.b *= u.L;
    q.m1 *= u.Mu;
    q.m2 *= u.Mu;
    q.I1 *= u.inertia();
    q.I2 *= u.inertia();
    q.Id1 *= u.inertia();
    q.Id2 *= u.inertia();
    q.k *= u.stiffness();
    q.bearing *= u.stiffness();
    SystemBuilder builder = test::HandPairBuilder(q, core);
    Vector6 t = Vector6::Zero();
    t(5) = torque * u.torque();
    builder.AddTorque(BodyIndex(0), t, "drive");
    t(5) = torque * u.torque() * q.r2 / q.r1;
    builder.AddTorque(BodyIndex(1), t, "brake");
    if (harmonic_torque != 0.0) {
      Vector6c h = Vector6c::Zero();
      h(5) = harmonic_torque * u.torque();
      builder.AddHarmonicLoad(BodyIndex(0), h, 1, "ripple-pinion");
      h(5) = harmonic_torque * u.torque() * q.r2 / q.r1;
      builder.AddHarmonicLoad(BodyIndex(1), h, 1, "ripple-wheel");
    }
    return builder.Build().Restrict({5, 11});
  }
};

/// True when every number of an HB result is finite (summary, meshes, elements, harmonics).
inline ::testing::AssertionResult AllFinite(const HbResult& r) {
  auto bad = [](const std::string& what) { return ::testing::AssertionFailure() << what; };
  if (!std::isfinite(r.summary.error_estimate)) return bad("summary.error_estimate");
  if (!std::isfinite(r.reciprocal_condition)) return bad("reciprocal_condition");
  for (const HbMeshOutput& m : r.meshes) {
    for (double v : {m.mean_dte, m.rms_dte, m.peak_to_peak_dte, m.mean_force, m.rms_force,
                     m.peak_to_peak_force}) {
      if (!std::isfinite(v)) return bad("mesh " + m.name + " statistics");
    }
    if (!m.dte_amplitudes.allFinite()) return bad("mesh " + m.name + " dte_amplitudes");
  }
  for (const HbElementOutput& e : r.elements) {
    if (!e.mean_force.allFinite() || !e.rms_force.allFinite()) return bad("element " + e.name);
  }
  if (!r.response_harmonics.allFinite()) return bad("response_harmonics");
  if (!r.dte_samples.allFinite()) return bad("dte_samples");
  return ::testing::AssertionSuccess();
}

/// True when every number of a time response is finite.
inline ::testing::AssertionResult AllFinite(const TimeResponse& r) {
  auto bad = [](const std::string& what) { return ::testing::AssertionFailure() << what; };
  if (!r.time.allFinite()) return bad("time");
  if (!std::isfinite(r.max_energy_error)) return bad("max_energy_error");
  for (const MeshTimeHistory& m : r.meshes) {
    if (!m.dte.allFinite() || !m.force.allFinite() || !m.channels.allFinite()) {
      return bad("mesh " + m.name + " histories");
    }
    for (double v : {m.mean_dte, m.rms_dte, m.peak_to_peak_dte, m.contact_loss_fraction}) {
      if (!std::isfinite(v)) return bad("mesh " + m.name + " statistics");
    }
  }
  for (const MatrixX& f : r.element_forces) {
    if (!f.allFinite()) return bad("element forces");
  }
  for (const EnergyBalancePeriod& e : r.energy) {
    for (double v : {e.input_work, e.stored_change, e.dissipated, e.gross_flow, e.relative_error}) {
      if (!std::isfinite(v)) return bad("energy balance");
    }
  }
  if (!r.final_state.allFinite()) return bad("final_state");
  return ::testing::AssertionSuccess();
}

}  // namespace geardyn::stress
