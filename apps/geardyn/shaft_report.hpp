/// @file
/// @brief Shafts and system damping in the `geardyn info` and `geardyn modes` reports: the
/// shaft list (sections, material, mass, nodes, DOFs, gears and bearings at their stations), the
/// [damping] table, and the strain energy of each mode grouped per shaft.
#pragma once

#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "geardyn/models/scene/scene.hpp"

namespace geardyn::app {

/// @brief One JSON object per [[shaft]] (SI: m, Pa, kg/m³, kg) with its nodes and DOFs.
nlohmann::json MakeShaftsReport(const Scene& scene);

/// @brief The [damping] table as JSON: {"kind": "none" | "modal" | "rayleigh", ...}.
nlohmann::json MakeSystemDampingReport(const Scene& scene);

/// @brief Appends the text blocks of the "shafts" and "damping" entries of an info report.
void FormatShaftsText(const nlohmann::json& report, std::ostringstream& out);

/// @brief Replaces the strain-energy entries "element:<shaft>.e<k>" of each mode of a modes
/// report by their sum "shaft:<shaft>" (one column per shaft instead of one per element).
void GroupShaftStrain(const Scene& scene, nlohmann::json* modes_report);

}  // namespace geardyn::app
