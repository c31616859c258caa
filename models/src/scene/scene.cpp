#include "geardyn/models/scene/scene.hpp"

#include <cmath>
#include <string>

#include "geardyn/common/check.hpp"
#include "geardyn/common/units.hpp"
#include "scene/speed_ratios.hpp"

namespace geardyn {

const GearDef& Scene::gear(std::string_view name) const {
  for (const GearDef& g : gears) {
    if (g.name == name) return g;
  }
  throw InvalidInput("gear: no gear named '" + std::string(name) + "' in scene '" + source + "'");
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

double Scene::MeshFrequencyHz(const MeshDef& mesh) const {
  const double omega = GearSpeed(mesh.pinion);
  return std::abs(omega) * static_cast<double>(gear(mesh.pinion).blank.teeth) / (2.0 * kPi);
}

}  // namespace geardyn
