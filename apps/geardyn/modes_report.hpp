/// @file
/// @brief The `geardyn modes` report: the modes of a scene's mean (LTI) system (ComputeModes on
/// MakeSystemModel) as JSON, a text table, and the CSV files of `--out`.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "geardyn/analyses/modal.hpp"
#include "geardyn/models/system/scene_system.hpp"

namespace geardyn::app {

/// Default number of modes of `geardyn modes` (all of them for systems with fewer DOFs).
inline constexpr int kDefaultCommandModes = 20;

/// The command-line settings of `geardyn modes`.
struct ModesSettings {
  int num_modes = kDefaultCommandModes;  ///< --modes N, ≥ 1 (capped at the number of DOFs)
  std::string method = "auto";           ///< --method auto|dense|arpack
  bool shapes = false;                   ///< --shapes: mode shapes in the JSON and mode_shapes.csv
  bool damped = false;                   ///< --damped: damped complex modes
  /// --loaded: the tangent stiffness about the loaded operating point (each mesh's preload
  /// K_g(F̄_η), SceneSystemOptions::mesh_preload); the report gains "mesh_preload".
  bool loaded = false;
};

/// @brief ModalOptions for a system of `num_dofs` DOFs: num_modes = N, or 0 (all, dense) when
/// N ≥ num_dofs; energy fractions always; shapes and damped modes on request.
/// @throws InvalidInput naming --modes (N < 1) or --method (unknown name).
ModalOptions MakeModesOptions(const ModesSettings& settings, int num_dofs);

/// @brief Adds report["mesh_preload"]: per mesh its name, static force "force_n" [N], preload
/// stiffness "coefficient_n_per_m" κ [N/m] and "line_length_m" L_s [m] (SceneSystem::mesh_preloads;
/// FormatModesText prints them under the header), and report["mesh_preload_rigid_modes"], the
/// number of rigid-body modes the preload was projected off
/// (SceneSystem::mesh_preload_rigid_modes).
void AddMeshPreloadReport(const SceneSystem& built, nlohmann::json* report);

/// @brief The JSON report: ModalResultToJson's fields (method_used, status, message, warnings,
/// frequencies_hz, modes[] with label, kinetic/strain fractions, multiplicity, damped_modes …)
/// plus "scene", "num_dofs", "num_modes", "multiplicity_groups" (lists of mode indices) and per
/// mode "group" (index into multiplicity_groups). `scene_warnings` (from the scene → system
/// builder) are appended to "warnings" with the prefix "scene: ".
nlohmann::json MakeModesReport(const std::string& scene_source, int num_dofs,
                               const ModalResult& result,
                               const std::vector<std::string>& scene_warnings);

/// @brief The text table: one line per mode with index, f [Hz], type label, the dominant
/// kinetic-energy kind and its %, the largest strain-energy owner and its %, and the
/// multiplicity group; then the damped modes (if any) and the warnings.
std::string FormatModesText(const nlohmann::json& report);

/// @brief Mode shapes as CSV: header "dof,mode_0,mode_1,…", one row per DOF (name, then the
/// M-normalized shape entries [m or rad per √(kg·m²)]). Empty without shapes.
std::string FormatModeShapesCsv(const ModalResult& result);

}  // namespace geardyn::app
