// A project outside geardyn: links the installed geardyn::geardyn and checks one closed form
// (base radius of the Kim et al. rig gear, r_b = m z cos α / 2 = 70.477 mm).
#include <cmath>
#include <cstdio>

#include "geardyn/common/units.hpp"
#include "geardyn/models/gear/gear_geometry.hpp"

int main() {
  geardyn::GearPairSpec spec;
  spec.normal_module = 0.003;
  spec.normal_pressure_angle = geardyn::DegToRad(20.0);
  spec.pinion.teeth = 50;
  spec.pinion.face_width = 0.02;
  spec.gear = spec.pinion;
  const geardyn::GearPairGeometry g = geardyn::CalcGearPairGeometry(spec);
  const double expected = 0.075 * std::cos(geardyn::DegToRad(20.0));
  if (std::abs(g.pinion.base_radius - expected) > 1e-12) {
    std::printf("base radius %.9f, expected %.9f\n", g.pinion.base_radius, expected);
    return 1;
  }
  std::printf("consumer OK: base radius %.6f mm\n", 1e3 * g.pinion.base_radius);
  return 0;
}
