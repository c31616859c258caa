/// @file
/// @brief Reading the mesh-model keys of one [[mesh]] table and its sub-tables
/// [mesh.modifications], [mesh.errors] and [mesh.parameters] into a MeshModelDef (internal to
/// the scene reader; the keys are documented in docs/scene-format.md, "Mesh model").
#pragma once

#include <toml++/toml.h>

#include "geardyn/models/scene/scene.hpp"
#include "scene/toml_fields.hpp"

namespace geardyn::internal {

/// Largest magnitude of a flank deviation, runout or pitch deviation [m]: 1 mm catches
/// micrometres typed as metres (20 µm is 2e-5).
inline constexpr double kMaxDeviation = 1e-3;

/// @brief Reads the mesh model of the [[mesh]] table of `f` (mesh_model_reader.cpp).
/// @param[in] f the mesh table, prefixed "mesh.NAME"
/// @param[in] pinion, gear the mesh's gears; @param[in] geometry their pair geometry
MeshModelDef ReadMeshModel(const Fields& f, const GearDef& pinion, const GearDef& gear,
                           const GearPairGeometry& geometry);

/// @brief Reads [mesh.contact] (contact_mesh_reader.cpp): unknown keys, keys that do not apply
/// to the chosen teeth, law, friction or profile, and values out of range fail.
/// @param[in] f the sub-table, prefixed "mesh.NAME.contact"
/// @param[in] geometry the pair (gear kinds, tip thicknesses)
ContactMeshDef ReadContactMesh(const Fields& f, const GearPairGeometry& geometry);

/// @brief Reads [mesh.modifications] (tooth_data_reader.cpp).
/// @param[in] f the sub-table, prefixed "mesh.NAME.modifications"
/// @param[in] geometry the pair (relief lengths are at most its path of contact g_α)
ToothModifications ReadToothModifications(const Fields& f, const GearPairGeometry& geometry);

/// @brief Reads [mesh.errors] (tooth_data_reader.cpp); pinion_teeth and gear_teeth are set
/// from the gears.
ToothErrors ReadToothErrors(const Fields& f, const GearDef& pinion, const GearDef& gear);

/// @brief True when the modifications or errors give a non-zero unloaded separation (any active
/// relief, crowning, slope, non-zero pitch deviation or runout) (tooth_data_reader.cpp).
bool HasUnloadedSeparation(const ToothModifications& modifications, const ToothErrors& errors);

/// @brief Reads [mesh.parameters] (mesh_parameters_reader.cpp): checked K ≥ 0 and μ ≥ κ² where
/// K > 0, converted to the channels (K, K·h, K·μ·b²) and (ε_η, ε_ζ).
/// @param[in] half_face_width b [m] of κ = h/b and the channel K·μ·b²
/// @param[in] max_load_centre bound on |h| [m]: the width of the zone of action along the
///   contact lines (g_α|sin β_b| + B cos β_b), which contains every σ of the contact
UserMeshParameters ReadUserMeshParameters(const Fields& f, double half_face_width,
                                          double max_load_centre);

}  // namespace geardyn::internal
