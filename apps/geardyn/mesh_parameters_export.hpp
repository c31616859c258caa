/// @file
/// @brief The quasi-static export of `geardyn simulate --quasi-static`: a mesh's loaded K(θ) and
/// transmission error over one mesh cycle written as a ready-to-paste `[mesh.parameters]` table
/// (docs/scene-format.md), so that an LTV mesh can be built from the contact (or slice) model and
/// the two compared (issue 14, spec 03 "Quasi-static mode").
///
/// **What is written.** With the channels (K, K·h, K·μ·b²) [N/m, N, N·m] sampled at S uniform
/// mesh phases θ_s = 2πs/S (`form = "table"`): stiffness = K, load_centre = K·h/K,
/// mu = K·μ·b²/(K b²) (h = 0 and μ = 0 where K = 0: no contact, any value gives the same K2 = 0),
/// and te_eta = ε_η. The LTV mesh's static deflection under the mean mesh force F̄ is
/// δ_η = ε_η + F̄/K (spec 01 §3), so ε_η = STE − F̄/K makes it reproduce the loaded static
/// transmission error STE of the source model at this load (the linearization at the operating
/// load: K is the tangent stiffness there).
#pragma once

#include <string>
#include <vector>

namespace geardyn::app {

/// One mesh's quasi-static samples over one mesh cycle (S ≥ 1 samples, θ_s = 2πs/S).
struct MeshParameterSamples {
  std::string mesh;                     ///< the mesh's name (scene `[[mesh]]` name)
  double half_face_width = 0.0;         ///< b > 0 [m]
  std::vector<double> stiffness;        ///< (S) K(θ_s) [N/m], ≥ 0
  std::vector<double> stiffness_h;      ///< (S) K·h [N] (empty: centred load, h = 0)
  std::vector<double> stiffness_mu_b2;  ///< (S) K·μ·b² [N·m] (empty: the reader's default μ)
  std::vector<double> transmission_error;  ///< (S) ε_η [m] (empty: none)
};

/// @brief The `[mesh.parameters]` table (TOML, with a comment block saying where to paste it),
/// numbers with 17 significant digits (exact round trip).
/// @param[in] samples one mesh's samples.
/// @param[in] comment lines (without '#') put first, e.g. the source scene and load.
/// @throws InvalidInput naming the field when the arrays have different lengths, S = 0, a value
///   is not finite, K < 0, or b ≤ 0.
std::string FormatMeshParametersToml(const MeshParameterSamples& samples,
                                     const std::vector<std::string>& comment);

/// @brief The same table as a `--set` override, `mesh.NAME.parameters={form="table", …}` (one
/// line, for `geardyn hb SCENE --set '…'`).
/// @throws InvalidInput as FormatMeshParametersToml.
std::string FormatMeshParametersOverride(const MeshParameterSamples& samples);

}  // namespace geardyn::app
