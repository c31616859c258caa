/// @file
/// @brief The model levels `geardyn compare` runs (spec 01 §5, B–S §5.3, issue 15): their names
/// in order of detail, what each is, which analyses it has, and the scene at a level.
///
/// Every level is a reduction of the one mesh interface (B–S 1995 §5.3): the levels share the
/// bodies, supports and data and differ only in the mesh core, so a scene at a level is the scene
/// with every mesh's `model` set to it (SceneAtLevel).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "geardyn/models/scene/scene.hpp"

namespace geardyn::app {

/// The analyses compare runs.
enum class CompareAnalysis { kModes, kFloquet, kHb, kSimulate };

/// "modes", "floquet", "hb", "simulate".
const char* ToString(CompareAnalysis analysis);

/// @brief One level of the hierarchy.
struct CompareLevelInfo {
  std::string name;              ///< the scene's `model` value, e.g. "blankenship_singh"
  std::string description;       ///< what it is and where it comes from (one line)
  bool linear = true;            ///< an LTV/LTI core (linear HB); false: slices, contact
  bool frequency_domain = true;  ///< modes, Floquet and HB (false: contact, time domain only)
};

/// @brief Every level compare knows, most detailed first (the default reference is the most
/// detailed requested level that ran an analysis).
const std::vector<CompareLevelInfo>& CompareLevels();

/// @brief The level named `name`, or nullptr.
const CompareLevelInfo* FindCompareLevel(const std::string& name);

/// @brief Parses a comma-separated level list (duplicates, unknown names and an empty list are
/// InvalidInput naming --levels, the name and the valid names), in the order of detail.
std::vector<std::string> ParseCompareLevels(const std::string& list);

/// @brief Parses a comma-separated analysis list ("modes,floquet,hb,simulate"; InvalidInput
/// naming --analyses on unknown or duplicate names or an empty list).
std::vector<CompareAnalysis> ParseCompareAnalyses(const std::string& list);

/// @brief The scene with every mesh at `level`; for an oscillator scene (Scene::oscillator) its
/// model: slices (the clearance, with backlash only), torsional (linear LTV) or lti.
/// @throws InvalidInput when the scene has nothing the level applies to.
Scene SceneAtLevel(const Scene& scene, const std::string& level);

}  // namespace geardyn::app
