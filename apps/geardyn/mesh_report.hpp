/// @file
/// @brief The `geardyn mesh` report: the mesh parameters K(θ), h(θ), κ(θ), μ(θ) and the
/// transmission-error pair ε(θ) of every mesh of a scene, sampled over one period of its core
/// (one mesh cycle, or the hunting period when tooth-to-tooth errors are present).
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "geardyn/models/scene/scene.hpp"

namespace geardyn::app {

/// Sampling of the mesh parameters.
struct MeshSamplingOptions {
  /// Samples per mesh cycle; 0 = automatic: 360 for a one-cycle period, fewer (≥ 16) for a
  /// hunting period so that a mesh has at most kMaxAutoSamples rows.
  int samples_per_mesh = 0;
  static constexpr long kMaxAutoSamples = 200000;
};

/// The sampled parameters of one mesh (columns of its CSV).
struct MeshSamples {
  std::string mesh_name;
  std::vector<double> cycle;        ///< θ / 2π, mesh cycles from θ = 0 [-]
  std::vector<double> stiffness;    ///< K [N/m]
  std::vector<double> load_centre;  ///< h [m] along σ̂ from the pitch point
  std::vector<double> kappa;        ///< κ = h / b [-]
  std::vector<double> mu;           ///< μ [-]
  std::vector<double> te_eta;       ///< ε_η [m] (empty when the core has no TE)
  std::vector<double> te_zeta;      ///< ε_ζ [rad] (empty when the core has no TE)
};

/// @brief Samples every mesh of the scene and summarises it.
/// @param[out] samples one entry per mesh, in scene order.
/// @return JSON: per mesh the level, time dependence, period, ranges and K's harmonics.
nlohmann::json MakeMeshReport(const Scene& scene, const MeshSamplingOptions& options,
                              std::vector<MeshSamples>* samples);

/// @brief The samples as CSV with a header line naming each column and its unit.
std::string FormatMeshCsv(const MeshSamples& samples);

/// @brief An SVG figure of the samples: K, h, μ and (if present) ε_η, ε_ζ over the mesh cycles.
std::string RenderMeshSvg(const MeshSamples& samples, const std::string& title);

}  // namespace geardyn::app
