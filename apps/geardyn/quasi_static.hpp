/// @file
/// @brief The quasi-static (slow-roll) export of `geardyn simulate --quasi-static`: the engine's
/// SimulateQuasiStatic (time_response.hpp) sampled per mesh at S uniform phases of the mesh's own
/// cycle (QuasiStaticSampling::kMeshCycle), turned into the `[mesh.parameters]` samples that
/// mesh_parameters_export.hpp writes — the K(θ) and STE that build an LTV mesh from the contact
/// or slice model (issue 14). No solve of its own: the engine gives, per mesh and sample, the
/// loaded STE δ_η, the symmetric tangent K2 = ∂F/∂δ (contact core: its tooth coordinates
/// condensed, projected through (G Gᵀ)⁻¹G), the mesh force pair F (contact core: F = −(G Gᵀ)⁻¹G
/// f₁₂, = T/r_b statically) and ε_η = δ_η − (K2⁺F)_η, so that the LTV mesh's static deflection
/// ε + K2⁻¹F reproduces the STE at this load. Here: the channels (K, K·h, K·μ·b²) =
/// (max(K2₀₀, 0), −K2₀₁, K2₁₁) and the checks that one table can hold the mesh.
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
