/// @file
/// @brief Readers of the sections of a scene file: one [[gear]], [[mesh]], [[bearing]] or
/// [[load]] table, and the [operating_point] (internal to the scene reader).
///
/// Each reader rejects unknown keys, reads and checks every value (failing with
/// `FILE:LINE: KEY: REASON`, see toml_fields.hpp) and returns the SI definition. The plausibility
/// bounds are documented in docs/scene-format.md.
#pragma once

#include <toml++/toml.h>

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "geardyn/models/scene/scene.hpp"
#include "scene/error_context.hpp"
#include "scene/toml_fields.hpp"

namespace geardyn::internal {

/// Relative tolerance under which two values typed for the same quantity count as equal: equal
/// data typed twice parse to identical doubles; this only absorbs the rounding of the degree →
/// radian conversion.
inline constexpr double kEqualTol = 1e-9;

/// @brief Reads element `index` of [[gear]] (gear_reader.cpp).
GearDef ReadGear(const ErrorContext& ctx, const toml::table& t, std::size_t index);

/// @brief The optional mass, inertia and transverse_inertia of a body table (gear or carrier),
/// and the table's key and line (GearDef::key, GearDef::line).
void ReadMassProperties(const Fields& f, GearDef* g);

/// @brief Reads element `index` of [[mesh]] and derives its pair geometry (mesh_reader.cpp).
/// @param[in] scene the gears read so far and the meshes before this one
MeshDef ReadMesh(const ErrorContext& ctx, const toml::table& t, std::size_t index,
                 const Scene& scene);

/// @brief Reads element `index` of [[shaft]] (shaft_reader.cpp): sections, material and the
/// gears at their stations (ShaftDef::nodes are placed later by PlaceShaftNodes).
/// @param[in] scene the gears and the shafts before this one (a gear sits on one shaft)
ShaftDef ReadShaft(const ErrorContext& ctx, const toml::table& t, std::size_t index,
                   const Scene& scene);

/// @brief An axial position under `key` of `f`'s table, in [0, shaft.length()] [m]
/// (shaft_reader.cpp).
double ReadStation(const Fields& f, std::string_view key, const ShaftDef& shaft);

/// @brief Sets ShaftDef::nodes of every shaft from its sections and the stations of its gears
/// and bearings (shaft_reader.cpp; see ShaftDef).
void PlaceShaftNodes(Scene* scene);

/// @brief Reads element `index` of [[bearing]] (bearing_reader.cpp).
/// @param[in] scene its gears and shafts are the bodies the bearing may connect
BearingDef ReadBearing(const ErrorContext& ctx, const toml::table& t, std::size_t index,
                       const Scene& scene);

/// @brief A symmetric positive semi-definite 6×6 matrix under `key` of `f`'s table: 6 numbers
/// (diagonal) or 6 rows of 6 (bearing_reader.cpp; `what` describes it in a "missing" error).
Matrix6 ReadMatrix6(const Fields& f, std::string_view key, const std::string& what);

/// @brief Reads element `index` of [[planetary]] and expands it into `scene`
/// (planetary_reader.cpp): appends the planets and the carrier to scene->gears, replaces the two
/// template meshes by one copy per planet, and appends the PlanetaryDef. The planet bearings are
/// appended later by AddPlanetBearings (after the [[bearing]] tables, whose names they must not
/// repeat).
void ReadPlanetary(const ErrorContext& ctx, const toml::table& t, std::size_t index, Scene* scene);

/// @brief Appends the planet-on-carrier bearings of `scene->planetaries` to scene->bearings,
/// rejecting a name already used by a [[bearing]] (reported at the planetary table tables[i]).
void AddPlanetBearings(const ErrorContext& ctx, const std::vector<const toml::table*>& tables,
                       Scene* scene);

/// @brief Rejects an operating point on a planetary set's fixed member (it has no speed).
void CheckPlanetaryOperatingPoint(const ErrorContext& ctx,
                                  const std::vector<const toml::table*>& tables,
                                  const Scene& scene);

/// @brief Reads element `index` of [[load]] (load_reader.cpp).
TorqueLoadDef ReadLoad(const ErrorContext& ctx, const toml::table& t, std::size_t index,
                       const Scene& scene);

/// @brief Reads the required [operating_point] table of `root` (operating_point_reader.cpp).
/// @param[in] scene with its gears and meshes (the default reference is the first mesh's pinion)
OperatingPointDef ReadOperatingPoint(const ErrorContext& ctx, const toml::table& root,
                                     const Scene& scene);

/// @brief Reads the optional top-level [damping] table of `root` (damping_reader.cpp): modal
/// ratios or Rayleigh coefficients; an empty SystemDamping when absent.
SystemDamping ReadSystemDamping(const ErrorContext& ctx, const toml::table& root);

/// @brief Reads the [oscillator] table `t` of an oscillator scene (oscillator_reader.cpp).
OscillatorDef ReadOscillator(const ErrorContext& ctx, const toml::table& t);

}  // namespace geardyn::internal
