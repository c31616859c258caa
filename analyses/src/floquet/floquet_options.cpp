// FloquetOptions::IsValid and the method names.
#include <cmath>
#include <sstream>

#include "floquet/floquet_internal.hpp"
#include "geardyn/analyses/floquet.hpp"
#include "geardyn/common/errors.hpp"

namespace geardyn {
namespace {
constexpr int kMaxArpackIterations = 100000;  // implicit restarts (ARPACK iparam[2])
}  // namespace

const char* ToString(FloquetMethod method) {
  switch (method) {
    case FloquetMethod::kAuto:
      return "auto";
    case FloquetMethod::kExactSteps:
      return "exact_steps";
    case FloquetMethod::kMagnus:
      return "magnus";
    case FloquetMethod::kOdeStepper:
      return "ode_stepper";
    case FloquetMethod::kHill:
      return "hill";
    case FloquetMethod::kModalProjection:
      return "modal_projection";
    case FloquetMethod::kArpackMonodromy:
      return "arpack_monodromy";
  }
  return "unknown";
}

FloquetMethod ParseFloquetMethod(const std::string& name, const std::string& field) {
  std::string names;
  for (FloquetMethod m : kFloquetMethods) {
    if (name == ToString(m)) return m;
    names += (names.empty() ? "" : ", ") + std::string(ToString(m));
  }
  throw InvalidInput(field + ": unknown Floquet method '" + name + "' (one of " + names + ")");
}

bool FloquetOptions::IsValid(std::string* why) const {
  std::ostringstream os;
  if (!(std::isfinite(mesh_frequency_hz) && mesh_frequency_hz > 0.0)) {
    os << "mesh_frequency_hz: must be finite and > 0, got " << mesh_frequency_hz;
  } else if (!(std::isfinite(tolerance) && tolerance > 0.0 && tolerance < 1.0)) {
    os << "tolerance: must be in (0, 1), got " << tolerance;
  } else if (hill_harmonics < 0 || hill_harmonics > 199) {
    // 199: the largest H whose Hill matrix (2·(2H+1) for the smallest state, 2 rows) stays within
    // the 800 rows of internal::kMaxHillSize; larger systems are checked with their dimension.
    os << "hill_harmonics: must be in [0, 199] (0 = automatic; a Hill matrix of dim·(2H+1) rows "
          "is limited to 800), got "
       << hill_harmonics;
  } else if (num_modes < 0 || num_modes > internal::kMaxBasisModes) {
    os << "num_modes: must be in [0, " << internal::kMaxBasisModes
       << "] (0 = automatic; the projection is checked with up to 2.25·num_modes modes, each "
          "run a Floquet analysis of a 2·num_modes state), got "
       << num_modes;
  } else if (magnus_order != 4 && magnus_order != 6) {
    os << "magnus_order: must be 4 or 6, got " << magnus_order;
  } else if (magnus_steps < 0 || magnus_steps > internal::kMaxMagnusSteps) {
    // The automatic step choice stops at the same cap (magnus.cpp).
    os << "magnus_steps: must be in [0, " << internal::kMaxMagnusSteps << "] (0 = automatic), got "
       << magnus_steps
       << "; every step costs 2-3 evaluations of K(θ), C(θ) and a dense exponential of the "
          "2n x 2n state, about 25·(2n)³ flops (arpack_monodromy also stores (2n)² doubles per "
          "step)";
  } else if (arpack_nev < 1) {
    os << "arpack_nev: must be >= 1, got " << arpack_nev;
  } else if (arpack_ncv != 0 && arpack_ncv < arpack_nev + 2) {
    os << "arpack_ncv: must be 0 (automatic) or >= arpack_nev + 2 = " << arpack_nev + 2 << ", got "
       << arpack_ncv;
  } else if (arpack_max_iterations < 1 || arpack_max_iterations > kMaxArpackIterations) {
    os << "arpack_max_iterations: must be in [1, " << kMaxArpackIterations
       << "] (every restart applies the monodromy up to arpack_ncv times, each a propagation "
          "over the whole period), got "
       << arpack_max_iterations;
  } else if (max_approximant_period_meshes < 0 ||
             max_approximant_period_meshes > internal::kMaxFloquetCommonPeriodMeshes) {
    os << "max_approximant_period_meshes: must be in [0, "
       << internal::kMaxFloquetCommonPeriodMeshes
       << "] (0 refuses incommensurate mesh "
          "frequencies; the work grows with the period), got "
       << max_approximant_period_meshes;
  } else if (modal_projection_min_dofs < 1) {
    os << "modal_projection_min_dofs: must be >= 1, got " << modal_projection_min_dofs;
  } else {
    return true;
  }
  if (why != nullptr) *why = os.str();
  return false;
}

}  // namespace geardyn
