// Planetary sets: Willis kinematics, drive sign and mesh phasing (formulas in
// geardyn/models/scene/planetary.hpp).
#include "geardyn/models/scene/planetary.hpp"

#include <cmath>
#include <numbers>

#include "geardyn/common/check.hpp"

namespace geardyn {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;

double Involute(double alpha) { return std::tan(alpha) - alpha; }

// x mod 2π in [0, 2π).
double Wrap(double x) {
  double r = std::fmod(x, kTwoPi);
  if (r < 0.0) r += kTwoPi;
  return r >= kTwoPi ? 0.0 : r;
}

}  // namespace

const std::string& PlanetaryDef::fixed_member() const {
  switch (fixed) {
    case PlanetaryFixedMember::kRing:
      return ring;
    case PlanetaryFixedMember::kCarrier:
      return carrier;
    case PlanetaryFixedMember::kSun:
      return sun;
  }
  return ring;
}

std::map<std::string, double, std::less<>> PlanetarySpeedFactors(const PlanetaryDef& set) {
  GEARDYN_THROW_UNLESS(set.sun_teeth > 0 && set.ring_teeth > 0 && set.planet_teeth > 0,
                       "planetary." << set.name << ": tooth counts must be positive");
  // Ω_m = Ω_c + c_m t with t = Ω_s − Ω_c; the fixed member F gives Ω_c = −c_F t.
  const double zs = set.sun_teeth;
  const double c_sun = 1.0;
  const double c_ring = -zs / set.ring_teeth;
  const double c_planet = -zs / set.planet_teeth;
  double c_fixed = 0.0;
  switch (set.fixed) {
    case PlanetaryFixedMember::kRing:
      c_fixed = c_ring;
      break;
    case PlanetaryFixedMember::kCarrier:
      c_fixed = 0.0;
      break;
    case PlanetaryFixedMember::kSun:
      c_fixed = c_sun;
      break;
  }
  std::map<std::string, double, std::less<>> a;
  a[set.sun] = c_sun - c_fixed;
  a[set.ring] = c_ring - c_fixed;
  a[set.carrier] = -c_fixed;
  for (const std::string& p : set.planets) a[p] = c_planet - c_fixed;
  return a;
}

int PlanetarySunDriveSign(const Scene& scene, const PlanetaryDef& set,
                          std::vector<std::string>* warnings) {
  const OperatingPointDef& op = scene.operating_point;
  const auto fallback = [&](const std::string& why) {
    if (warnings != nullptr) {
      warnings->push_back("planetary." + set.name + ": sun-mesh drive sign +1 assumed (" + why +
                          ")");
    }
    return 1;
  };
  if (op.torque == 0.0) return fallback("the operating-point torque is 0: no loaded flank");
  // Static torque ratios T_s : T_r : T_c = 1 : z_r/z_s : −(1 + z_r/z_s).
  const double zr_over_zs = static_cast<double>(set.ring_teeth) / set.sun_teeth;
  double ratio = 0.0;
  if (op.body == set.sun) ratio = 1.0;
  if (op.body == set.ring) ratio = zr_over_zs;
  if (op.body == set.carrier) ratio = -(1.0 + zr_over_zs);
  if (ratio == 0.0) {
    return fallback("the operating point's body '" + op.body +
                    "' is not a central member of the set");
  }
  return op.torque / ratio > 0.0 ? 1 : -1;
}

double CalcSunRingMeshPhase(const GearPairGeometry& sun_planet,
                            const GearPairGeometry& planet_ring) {
  const GearGeometry& planet = sun_planet.gear;
  GEARDYN_THROW_UNLESS(planet.reference_radius > 0.0 && planet.teeth > 0,
                       "sun_planet: the planet geometry is empty");
  // Θ_b = s_t / r + 2 inv α_t: the planet's tooth thickness angle at its base circle.
  const double theta_b = planet.tooth_thickness_transverse / planet.reference_radius +
                         2.0 * Involute(sun_planet.transverse_pressure_angle);
  const double z_p = planet.teeth;
  return Wrap(-z_p * (Involute(sun_planet.operating_pressure_angle) +
                      Involute(planet_ring.operating_pressure_angle) + std::numbers::pi - theta_b));
}

PlanetaryMeshPhases CalcPlanetaryMeshPhases(const PlanetaryDef& set, int sun_drive_sign) {
  GEARDYN_THROW_UNLESS(sun_drive_sign == 1 || sun_drive_sign == -1,
                       "sun_drive_sign: must be ±1, got " << sun_drive_sign);
  PlanetaryMeshPhases out;
  for (double psi : set.planet_angles) {
    // z_s (ψ_n − ψ_0) reduced before scaling: exact for the integer multiples of 2π/z_s.
    const double sun = Wrap(-sun_drive_sign * set.sun_teeth * (psi - set.planet_angles.front()));
    out.sun.push_back(sun);
    out.ring.push_back(Wrap(sun + set.sun_ring_phase));
  }
  return out;
}

}  // namespace geardyn
