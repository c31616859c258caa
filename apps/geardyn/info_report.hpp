/// @file
/// @brief The `geardyn info` report: derived geometry, ISO 6336-1 stiffness and model facts of a
/// scene, as JSON (SI units, angles in degrees where the key ends in `_deg`) and as text.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "geardyn/models/scene/scene.hpp"

namespace geardyn::app {

/// @brief Builds the info report of a validated scene (pure; no I/O).
nlohmann::json MakeInfoReport(const Scene& scene);

/// @brief Formats the info report for a person: one block per gear and per mesh, with units.
std::string FormatInfoText(const nlohmann::json& report);

}  // namespace geardyn::app
