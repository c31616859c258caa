/// @file
/// @brief The quasi-static (slow-roll) solve of `geardyn simulate --quasi-static`: at S uniform
/// mesh phases over one mesh cycle, the static equilibrium under the scene's loads
/// (SolveTimeDomainStatic, time_response.hpp) and, at it, each mesh's loaded static transmission
/// error and tangent mesh stiffness — the K(θ) and STE that build an LTV mesh from the contact or
/// slice model (issue 14; mesh_parameters_export.hpp writes them).
///
/// **Per mesh k and sample s** (θ_s = 2πs/S, the system phase chosen so that the mesh's own
/// phase r_k θ + φ_k equals θ_s):
/// * STE_s = δ_η = G_η q (the loaded TE along the tooth normal, probes.hpp);
/// * the 2×2 tangent K2 = ∂F/∂δ of the mesh force pair F = [F_η, M_ζ] at the static state:
///   linear core EvalStiffnessCore (exact, state-independent); slice core the slice Jacobian
///   (the loaded slices); nonlinear core its n×n tangent with the internal coordinates condensed
///   (Schur complement, they are in equilibrium) to the 12 body coordinates, K12, then
///   projected on the mesh deflections, K2 = A K12 Aᵀ with A = (G Gᵀ)⁺ G — exact when
///   the body forces act through G (K12 = Gᵀ K2 G), otherwise the least-squares pair;
/// * the channels (K, K·h, K·μ·b²) = (K2₀₀, −K2₀₁, K2₁₁) and ε_η = δ_η − (K2⁺ F)_η, so that the
///   LTV mesh's static deflection ε + K2⁻¹F reproduces the STE at this load.
/// The mesh force F: EvalMeshProbe for linear and slice cores; −A f12 for a nonlinear core (f12
/// the core's force on the 12 body coordinates).
#pragma once

#include <vector>

#include "geardyn/common/summary.hpp"
#include "geardyn/mesh_parameters_export.hpp"
#include "geardyn/system/system_model.hpp"

namespace geardyn::app {

/// One mesh's quasi-static result.
struct QuasiStaticMesh {
  MeshParameterSamples parameters;  ///< the table to export (K, K·h, K·μ·b², ε_η)
  std::vector<double> loaded_ste;   ///< (S) δ_η [m]
  std::vector<double> force;        ///< (S) F_η [N]
};

/// The quasi-static result of every mesh.
struct QuasiStaticResult {
  std::vector<QuasiStaticMesh> meshes;  ///< in model order
  Summary summary;  ///< the worst static solve's status; counters "static_solves"
};

/// Largest number of samples per mesh cycle of ComputeQuasiStatic.
inline constexpr int kMaxQuasiStaticSamples = 4096;

/// @brief The quasi-static K(θ) and STE of every mesh (see the @file).
/// @param[in] model the system (any mesh-core form).
/// @param[in] half_face_widths (num_meshes) b [m] per mesh (for μ).
/// @param[in] samples S per mesh cycle, in [1, kMaxQuasiStaticSamples].
/// @throws InvalidInput naming --samples-per-period (S out of range) or --quasi-static: a linear
///   or slice mesh whose parameters repeat over more than one mesh cycle (tooth errors, which one
///   `[mesh.parameters]` cycle cannot hold); a contact (NonlinearMeshCore) mesh with P > 1 whose
///   K or STE one mesh cycle later differs by more than 1e-6 (its teeth are not identical); a
///   model without meshes.
QuasiStaticResult ComputeQuasiStatic(const SystemModel& model,
                                     const std::vector<double>& half_face_widths, int samples);

}  // namespace geardyn::app
