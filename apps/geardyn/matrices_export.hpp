/// @file
/// @brief `geardyn matrices`: the system matrices of a scene for the user's own tools — the mean
/// (LTI) pencil M, C̄, K̄ that `geardyn modes` solves (mean_system.hpp), the mean load f̄, and on
/// request the Fourier harmonics K_m, C_m, f_m of the periodic system (system_harmonics.hpp) —
/// with the DOF map (body, coordinate), as MatrixMarket files and a JSON index.
///
/// Files (MatrixMarket coordinate, 17 significant digits, symmetric matrices stored "general"):
/// M.mtx, C.mtx, K.mtx (real n×n), f.mtx (real n×1); with harmonics H ≥ 1 also K_<m>.mtx,
/// C_<m>.mtx (complex n×n) and f_<m>.mtx (complex n×1) for m = 1 … H, where
/// K(θ) = K_0 + Σ_{m≥1} (K_m e^{imθ/P} + conj(K_m) e^{−imθ/P}) and θ/P advances 2π per period of
/// P mesh cycles (harmonic m is at m/P times the mesh frequency); dofs.json indexes them.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "geardyn/analyses/mean_system.hpp"
#include "geardyn/common/eigen_types.hpp"
#include "geardyn/models/scene/scene.hpp"
#include "geardyn/system/system_harmonics.hpp"

namespace geardyn::app {

/// Largest number of harmonics of `geardyn matrices` (the harmonics are dense n×n).
inline constexpr int kMaxExportHarmonics = 256;

/// The matrices of one scene.
struct SystemMatrices {
  MeanSystemMatrices mean;  ///< M, C̄, K̄ (exactly what `geardyn modes` solves)
  VectorX mean_load;        ///< (n) f̄ [N, N·m]: the θ-mean of f(θ) (no tooth errors: f0)
  /// K_m, C_m, f_m for m = 0 … H (empty when harmonics = 0). K_0 and C_0 are the θ-means of
  /// K(θ), C(θ): K_0 = K̄ for linear cores (slice cores: the all-loaded mean).
  SystemHarmonics harmonics;
  std::vector<std::string> dof_names;       ///< (n) "<body>.<component>"
  std::vector<std::string> dof_bodies;      ///< (n) body name
  std::vector<std::string> dof_components;  ///< (n) "x", "y", "z", "θx", "θy", "θz"
  std::vector<std::string> dof_kinds;       ///< (n) DofKind names
  double mesh_frequency_hz = 0.0;           ///< the scene's first mesh frequency [Hz]
  nlohmann::json report;  ///< dofs.json: scene, n, units, dofs, period, file names, warnings
};

/// @brief The matrices of `scene` with `harmonics` Fourier harmonics (0 = the mean system only).
/// @throws InvalidInput naming --harmonics (outside 0 … kMaxExportHarmonics) or as
///   BuildSceneSystem.
SystemMatrices ExportSystemMatrices(const Scene& scene, int harmonics);

/// @brief MatrixMarket coordinate text of a real or complex matrix (all stored entries, 1-based,
/// "%.17g"); `comment` becomes a "%" line.
std::string FormatMatrixMarket(const SparseMatrix& a, const std::string& comment);
std::string FormatMatrixMarket(const MatrixXc& a, const std::string& comment);
std::string FormatMatrixMarket(const VectorX& v, const std::string& comment);
std::string FormatMatrixMarket(const VectorXc& v, const std::string& comment);

/// @brief Writes every file of the @file to `dir` (created), atomically.
void WriteSystemMatrices(const SystemMatrices& matrices, const std::string& dir);

}  // namespace geardyn::app
