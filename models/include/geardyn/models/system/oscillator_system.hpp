/// @file
/// @brief The SystemModel of an oscillator scene (Scene::oscillator, OscillatorDef): the
/// dimensionless single-DOF gear-mesh oscillator of Kahraman & Singh (1990, 1991) and
/// Blankenship & Kahraman (1995) as a genuine SystemModel, so that every analysis and report
/// (modes, floquet, stability-chart, linear and nonlinear hb, simulate) runs on it unchanged.
///
/// **Equation** (τ = ω_n t, x in units of the half backlash b):
/// \f[ x'' + 2ζ x' + (1 + α \cos Ωτ)\, g(x) = F_m + F_a \cos(Ωτ + φ). \f]
///
/// **Scaling to 1 Hz.** The model is the equation in physical time with ω_n = 2π rad/s
/// (kOscillatorNaturalFrequencyHz = 1 Hz): M = 1, C = 2ζω_n, k = ω_n², forces F·ω_n². The mesh
/// phase is θ = ω_m t = Ωτ, so the mesh frequency in Hz that hb, floquet and simulate take IS the
/// frequency ratio Ω = ω_m/ω_n, and x (the DTE δ_η the reports print) stays dimensionless.
///
/// **Mapping.** Bodies "mass" (index 0) and "ground" (index 1, held fixed), both with unit mass;
/// the model is restricted to the x DOF of "mass" (one DOF, "mass.x"). One mesh "oscillator"
/// from "mass" (pinion) to "ground" with G = [e_x, −e_x; 0] (δ_η = x_mass − x_ground = x), and
/// a grounded element "damper" (stiffness 0, damping C) for the viscous term 2ζx', which acts in
/// and out of contact as in the equation. The mesh core by OscillatorDef::model:
/// * kSlices — SliceMeshCore with one slice at σ = 0, k_s(θ) = k(1 + α cos θ), separation
///   e_s = +1 (the front flank closes at x > 1: a = x − 1) and backlash j = 2 (the back flank at
///   a < −2, i.e. x < −1), or kNoBackFlank without back contact: g(a) = [a]₊ − [−a − j]₊ is the
///   clearance g(x) above;
/// * kTorsional — LinearMeshCore (kTorsional) with channels (k(1 + α cos θ), 0, 0): g(x) = x;
/// * kLti — the same with α dropped (mean stiffness k, mean-LTI core).
/// Loads: the constant F_m ω_n² and the harmonic load F_a ω_n² e^{iφ} of order 1 on mass.x
/// (SystemBuilder::AddHarmonicLoad). With α = 0 the stiffness is a ConstantCoefficient (the LTI
/// paths of every analysis apply).
#pragma once

#include "geardyn/models/scene/scene.hpp"
#include "geardyn/system/system_model.hpp"

namespace geardyn {

/// The oscillator's undamped natural frequency in the model [Hz] (mean stiffness): 1.
inline constexpr double kOscillatorNaturalFrequencyHz = 1.0;

/// The note BuildSceneSystem adds to the warnings of an oscillator scene (the reports print DTE
/// in µm and frequencies in Hz: what they mean here).
inline constexpr const char* kOscillatorUnitsNote =
    "oscillator scene (dimensionless, natural frequency 1 Hz): the mesh frequency [Hz] is the "
    "frequency ratio Omega = omega_m/omega_n and the DTE is x in units of the half backlash b "
    "(JSON *_m fields give x; text columns in um give 1e6 x)";

/// @brief The SystemModel of an oscillator (see the @file).
/// @throws InvalidInput naming the field on ζ < 0, |α| ≥ 1, a non-finite value, or model =
///   kSlices without backlash.
SystemModel MakeOscillatorSystemModel(const OscillatorDef& oscillator);

}  // namespace geardyn
