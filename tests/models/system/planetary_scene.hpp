// Test fixture: a spur planetary set as scene text (z_s = 40, z_p = 20, z_r = 80, m = 2 mm,
// 20°, b = 20 mm: standard centre distance 60 mm, (z_s + z_r) = 120 divisible by 2 … 6, planets
// never overlap for N ≤ 6). Every member has isotropic supports, so the set is cyclically
// symmetric for equally spaced planets (Lin & Parker 1999). The axial support frequencies of
// sun, ring and carrier differ (no accidental degeneracy between them).
#pragma once

#include <iomanip>
#include <sstream>
#include <string>
#include <vector>

namespace geardyn::testing {

struct PlanetaryFixture {
  int planets = 3;
  std::vector<double> angles_deg;  ///< explicit planet angles; empty = `planets` equally spaced
  bool planar = false;
  std::string model = "lti";  ///< mesh level of both templates
  std::string fixed = "ring";
  double sun_torsion = 1e5;      ///< sun rz support [N m/rad] (0: free)
  double carrier_torsion = 1e6;  ///< carrier rz support [N m/rad]
  double torque = 100.0;         ///< operating-point torque on the sun [N m]
  std::string mesh_extra;        ///< lines added to both template [[mesh]] tables
  std::string extra;             ///< appended at the end (e.g. more tables)
};

inline std::string PlanetarySceneText(const PlanetaryFixture& f) {
  std::ostringstream s;
  s << "title = \"test planetary\"\nplanar = " << (f.planar ? "true" : "false") << "\n";
  s << R"(
[[gear]]  # sun
name = "sun"
teeth = 40
normal_module = 0.002
face_width = 0.02
mass = 1.0
inertia = 8e-4
transverse_inertia = 5e-4

[[gear]]  # planet
name = "planet"
teeth = 20
normal_module = 0.002
face_width = 0.02
mass = 0.3
inertia = 6e-5
transverse_inertia = 4e-5

[[gear]]  # ring
name = "ring"
teeth = 80
normal_module = 0.002
face_width = 0.02
internal = true
mass = 2.0
inertia = 1.5e-2
transverse_inertia = 8e-3

[[mesh]]  # sun-planet
pinion = "sun"
gear = "planet"
model = ")"
    << f.model << "\"\n"
    << f.mesh_extra << R"(
[[mesh]]  # planet-ring
pinion = "planet"
gear = "ring"
model = ")"
    << f.model << "\"\n"
    << f.mesh_extra << R"(
[[planetary]]  # stage
name = "stage"
sun = "sun"
ring = "ring"
planet = "planet"
)";
  if (f.angles_deg.empty()) {
    s << "planets = " << f.planets << "\n";
  } else {
    s << "planet_angles_deg = [";
    for (std::size_t i = 0; i < f.angles_deg.size(); ++i) {
      s << (i ? ", " : "") << std::setprecision(17) << f.angles_deg[i];
    }
    s << "]\n";
  }
  s << "fixed = \"" << f.fixed << "\"\n";
  s << R"(carrier = { name = "carrier", mass = 3.0, inertia = 0.02, transverse_inertia = 0.012 }
planet_bearing_stiffness = [2e8, 2e8, 1e8, 1e6, 1e6, 0]

[[bearing]]  # sun-support
name = "sun-support"
body = "sun"
stiffness = [5e7, 5e7, 1e8, 5e5, 5e5, )"
    << f.sun_torsion << R"(]

[[bearing]]  # ring-support
name = "ring-support"
body = "ring"
stiffness = [3e8, 3e8, 2.5e8, 3e6, 3e6, 1e7]

[[bearing]]  # carrier-support
name = "carrier-support"
body = "carrier"
stiffness = [4e8, 4e8, 3.5e8, 4e6, 4e6, )"
    << f.carrier_torsion << R"(]

[operating_point]
body = "sun"
speed_rpm = 1500
torque = )"
    << f.torque << "\n"
    << f.extra;
  return s.str();
}

}  // namespace geardyn::testing
