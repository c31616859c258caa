#include "geardyn/compare_levels.hpp"

#include <algorithm>
#include <sstream>

#include "geardyn/common/check.hpp"
#include "geardyn/common/errors.hpp"
#include "geardyn/models/mesh/mesh_cores.hpp"

namespace geardyn::app {
namespace {

std::vector<std::string> SplitList(const std::string& list) {
  std::vector<std::string> out;
  std::string item;
  std::istringstream in(list);
  while (std::getline(in, item, ',')) {
    const auto first = item.find_first_not_of(" \t");
    const auto last = item.find_last_not_of(" \t");
    out.push_back(first == std::string::npos ? "" : item.substr(first, last - first + 1));
  }
  return out;
}

std::string ValidLevelNames() {
  std::string names;
  for (const CompareLevelInfo& l : CompareLevels()) names += (names.empty() ? "" : ", ") + l.name;
  return names;
}

}  // namespace

const char* ToString(CompareAnalysis analysis) {
  switch (analysis) {
    case CompareAnalysis::kModes:
      return "modes";
    case CompareAnalysis::kFloquet:
      return "floquet";
    case CompareAnalysis::kHb:
      return "hb";
    case CompareAnalysis::kSimulate:
      return "simulate";
  }
  return "?";
}

const std::vector<CompareLevelInfo>& CompareLevels() {
  static const std::vector<CompareLevelInfo> levels = {
      {"contact", "tooth contact with tooth bodies (Kim et al. 2015; time domain only)", false,
       false},
      {"slices", "nonlinear slices: contact loss, back flank (spec 01 §4.4)", false, true},
      {"blankenship_singh", "B–S 6-DOF LTV, exact mesh Jacobian G (B–S Eq. 41)", true, true},
      {"bs_projected", "B–S 6-DOF LTV, B–S's projected moment arms (B–S Eqs. 24–25)", true, true},
      {"five_dof", "B–S §5.3 five-DOF form: κ, μ kept, scalar TE (B–S Eq. 42)", true, true},
      {"coupling_4dof", "4-DOF coupling, κ = 0 and μ dropped (Kiyono 1978, Küçükay 1984)", true,
       true},
      {"lti", "LTI: mean K̄2 of the B–S core, ε(θ) kept (Kahraman 1993)", true, true},
      {"torsional", "torsional SDOF k(θ) on the base-circle rotations (Kahraman & Singh 1990)",
       true, true},
  };
  return levels;
}

const CompareLevelInfo* FindCompareLevel(const std::string& name) {
  for (const CompareLevelInfo& l : CompareLevels()) {
    if (l.name == name) return &l;
  }
  return nullptr;
}

std::vector<std::string> ParseCompareLevels(const std::string& list) {
  const std::vector<std::string> names = SplitList(list);
  GEARDYN_THROW_UNLESS(!names.empty(),
                       "--levels: empty; give one or more of " << ValidLevelNames());
  for (const std::string& n : names) {
    GEARDYN_THROW_UNLESS(FindCompareLevel(n) != nullptr, "--levels: unknown level '"
                                                             << n << "'; the levels are "
                                                             << ValidLevelNames());
    GEARDYN_THROW_UNLESS(std::count(names.begin(), names.end(), n) == 1,
                         "--levels: '" << n << "' is listed twice");
  }
  std::vector<std::string> ordered;
  for (const CompareLevelInfo& l : CompareLevels()) {
    if (std::find(names.begin(), names.end(), l.name) != names.end()) ordered.push_back(l.name);
  }
  return ordered;
}

std::vector<CompareAnalysis> ParseCompareAnalyses(const std::string& list) {
  const std::vector<std::string> names = SplitList(list);
  static const std::vector<CompareAnalysis> all = {CompareAnalysis::kModes,
                                                   CompareAnalysis::kFloquet, CompareAnalysis::kHb,
                                                   CompareAnalysis::kSimulate};
  GEARDYN_THROW_UNLESS(!names.empty(),
                       "--analyses: empty; give one or more of modes, floquet, hb, simulate");
  std::vector<CompareAnalysis> out;
  for (const std::string& n : names) {
    const auto it =
        std::find_if(all.begin(), all.end(), [&](CompareAnalysis a) { return n == ToString(a); });
    GEARDYN_THROW_UNLESS(it != all.end(), "--analyses: unknown analysis '"
                                              << n
                                              << "'; the analyses are modes, floquet, hb, "
                                                 "simulate");
    GEARDYN_THROW_UNLESS(std::find(out.begin(), out.end(), *it) == out.end(),
                         "--analyses: '" << n << "' is listed twice");
    out.push_back(*it);
  }
  std::sort(out.begin(), out.end());
  return out;
}

Scene SceneAtLevel(const Scene& scene, const std::string& level) {
  if (scene.oscillator) {
    // The literature's oscillator (Kahraman & Singh; Blankenship & Kahraman): its own levels.
    Scene out = scene;
    if (level == "slices") {
      GEARDYN_THROW_UNLESS(scene.oscillator->backlash,
                           "the oscillator has backlash = false, so it has no clearance (slices) "
                           "level");
      out.oscillator->model = OscillatorModel::kSlices;
    } else if (level == "torsional") {
      out.oscillator->model = OscillatorModel::kTorsional;
    } else if (level == "lti") {
      out.oscillator->model = OscillatorModel::kLti;
    } else {
      throw InvalidInput(
          "an oscillator scene has the levels slices (the clearance), torsional "
          "(linear, k(1 + α cos Ωt)) and lti (linear, α dropped), not '" +
          level + "'");
    }
    return out;
  }
  const std::optional<MeshModelLevel> parsed = ParseMeshModelLevel(level);
  GEARDYN_THROW_UNLESS(parsed.has_value(),
                       "level '" << level << "': not a mesh model of this build of geardyn");
  GEARDYN_THROW_UNLESS(!scene.meshes.empty(),
                       scene.source << ": the scene has no mesh, so it has no model levels");
  Scene out = scene;
  for (MeshDef& mesh : out.meshes) {
    mesh.model.level = *parsed;
    mesh.model.core_options.level = *parsed;
  }
  return out;
}

}  // namespace geardyn::app
