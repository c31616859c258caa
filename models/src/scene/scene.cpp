#include "geardyn/models/scene/scene.hpp"

#include <cmath>
#include <string>

#include "geardyn/common/check.hpp"
#include "geardyn/common/units.hpp"
#include "scene/speed_ratios.hpp"

namespace geardyn {

double ShaftDef::length() const {
  double total = 0.0;
  for (const ShaftSectionDef& s : sections) total += s.length;
  return total;
}

int ShaftDef::SectionAt(double a, double b) const {
  // The section containing the element's midpoint (elements never straddle a section end).
  const double mid = 0.5 * (a + b);
  double end = 0.0;
  for (std::size_t k = 0; k < sections.size(); ++k) {
    end += sections[k].length;
    if (mid < end) return static_cast<int>(k);
  }
  return static_cast<int>(sections.size()) - 1;
}

std::optional<std::pair<const ShaftDef*, double>> Scene::FindGearShaft(
    std::string_view gear_name) const {
  for (const ShaftDef& shaft : shafts) {
    for (const ShaftGearDef& g : shaft.gears) {
      if (g.gear == gear_name) return std::make_pair(&shaft, g.station);
    }
  }
  return std::nullopt;
}

const GearDef& Scene::gear(std::string_view name) const {
  for (const GearDef& g : gears) {
    if (g.name == name) return g;
  }
  throw InvalidInput("gear: no gear named '" + std::string(name) + "' in scene '" + source + "'");
}

const char* ToString(OscillatorModel model) {
  switch (model) {
    case OscillatorModel::kSlices:
      return "slices";
    case OscillatorModel::kTorsional:
      return "torsional";
    case OscillatorModel::kLti:
      return "lti";
  }
  return "?";
}

double Scene::GearSpeed(std::string_view name) const {
  (void)gear(name);  // throws if absent
  const internal::SpeedRatios ratios = internal::CalcSpeedRatios(*this, operating_point.body);
  const auto it = ratios.ratio.find(name);
  GEARDYN_THROW_UNLESS(it != ratios.ratio.end(),
                       "gear '" << name << "': not connected through meshes to the operating "
                                << "point's gear '" << operating_point.body
                                << "', so its speed is undefined");
  return it->second * operating_point.speed;
}

std::optional<std::pair<const PlanetaryDef*, int>> Scene::FindPlanetaryMesh(
    std::string_view mesh_name) const {
  for (const PlanetaryDef& set : planetaries) {
    for (std::size_t n = 0; n < set.planets.size(); ++n) {
      if (set.sun_meshes[n] == mesh_name || set.ring_meshes[n] == mesh_name) {
        return std::make_pair(&set, static_cast<int>(n));
      }
    }
  }
  return std::nullopt;
}

double Scene::MeshFrequencyHz(const MeshDef& mesh) const {
  double omega = GearSpeed(mesh.pinion);
  // Inside a planetary set the teeth pass at the speed relative to the carrier.
  if (const auto set = FindPlanetaryMesh(mesh.name)) omega -= GearSpeed(set->first->carrier);
  return std::abs(omega) * static_cast<double>(gear(mesh.pinion).blank.teeth) / (2.0 * kPi);
}

double Scene::NominalMeshFrequencyHz() const {
  if (oscillator) return oscillator->frequency_ratio;
  if (meshes.empty()) return 0.0;
  return MeshFrequencyHz(meshes.front());
}

}  // namespace geardyn
