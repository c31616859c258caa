/// @file
/// @brief The `geardyn mesh` report: the mesh parameters K(θ), h(θ), κ(θ), μ(θ) and the
/// transmission-error pair ε(θ) of every mesh of a scene, sampled over one period of its core
/// (one mesh cycle, or the hunting period when tooth-to-tooth errors are present) or over the
/// window the user asks for. ε of a contact-line mesh is evaluated exactly at each sample
/// (TransmissionErrorModel), never tabulated over the hunting period first.
#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "geardyn/models/scene/scene.hpp"

namespace geardyn::app {

/// Sampling of the mesh parameters.
struct MeshSamplingOptions {
  /// Samples per mesh cycle, an integer in [1, kMaxSamplesPerMesh] (a double, so that "2e5" on
  /// the command line is read as written and checked here); empty = automatic: 360 for a
  /// one-cycle period, fewer (≥ 16) for a hunting period so that a mesh has at most
  /// kMaxAutoSamples rows.
  std::optional<double> samples_per_mesh;
  /// Mesh cycles sampled from θ = 0, an integer in [1, kMaxCycles]; empty = the period of the
  /// mesh (one cycle, or the hunting period with tooth errors), at most kMaxAutoCycles of it.
  std::optional<double> cycles;
  static constexpr long kMaxAutoSamples = 200000;
  /// The default window over a long hunting period (997/991 teeth: 988 027 cycles): 12 500
  /// cycles at 16 samples, kMaxAutoSamples rows; a warning says how much of the period it is.
  static constexpr long kMaxAutoCycles = 12500;
  /// Upper bound of --cycles (2^31: the hunting period of any pair the models accept).
  static constexpr long kMaxCycles = 2147483647;
  /// 10⁵ samples per cycle resolve a mesh cycle to 10⁻⁵ (the stiffness steps of the contact
  /// lines are located exactly by the cores; the samples only draw them).
  static constexpr long kMaxSamplesPerMesh = 100000;
  /// Rows of one mesh (period × samples per cycle): 2·10⁶ rows are ≈ 0.1 GB in memory and
  /// ≈ 0.3 GB of CSV.
  static constexpr long kMaxSamples = 2000000;
  /// Bytes per row: the 8 columns in memory, and about 15 characters per CSV field.
  static constexpr double kBytesPerRow = 8 * 8.0;
  static constexpr double kCsvBytesPerRow = 8 * 15.0;
  /// @brief False (naming `--samples`, the value, the bound and the cost) when out of range.
  bool IsValid(std::string* why) const;
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
