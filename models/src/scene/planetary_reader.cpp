// Reading one [[planetary]] table: the sun, ring and planet gears, the two template meshes, the
// planet angles (assembly condition), the carrier and the planet bearings; expanding the set into
// the scene's gears, meshes and bearings (docs/scene-format.md, "[[planetary]]").
#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "geardyn/common/units.hpp"
#include "geardyn/models/scene/planetary.hpp"
#include "scene/element_names.hpp"
#include "scene/section_readers.hpp"
#include "scene/suggestions.hpp"
#include "scene/toml_fields.hpp"

namespace geardyn::internal {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;
constexpr int kMaxPlanets = 64;
// (z_s + z_r) ψ / 2π must be an integer; angles typed in degrees with ~10 digits are accepted
// within 1e-6 of a tooth pitch.
constexpr double kAssemblyTol = 1e-6;

bool Has(const std::vector<GearDef>& gears, const std::string& name) {
  return std::any_of(gears.begin(), gears.end(), [&](const GearDef& g) { return g.name == name; });
}

bool HasMesh(const std::vector<MeshDef>& meshes, const std::string& name) {
  return std::any_of(meshes.begin(), meshes.end(),
                     [&](const MeshDef& m) { return m.name == name; });
}

// The planet angles ψ_n [rad]: `planets` equally spaced from 0, or `planet_angles_deg`.
std::vector<double> ReadAngles(const Fields& f, bool* equally_spaced) {
  const std::optional<int> count = f.OptInt("planets", 1, kMaxPlanets);
  const auto angles = f.OptNumberArray("planet_angles_deg");
  if (!count && !angles) {
    f.Missing("planets", "the number of equally spaced planets (or planet_angles_deg)");
  }
  std::vector<double> psi;
  *equally_spaced = !angles.has_value();
  if (!angles) {
    for (int n = 0; n < *count; ++n) psi.push_back(kTwoPi * n / *count);
    return psi;
  }
  if (angles->empty() || angles->size() > static_cast<std::size_t>(kMaxPlanets)) {
    f.Fail("planet_angles_deg", "must have 1 to " + std::to_string(kMaxPlanets) +
                                    " entries (one per planet), got " +
                                    std::to_string(angles->size()));
  }
  if (count && static_cast<std::size_t>(*count) != angles->size()) {
    f.Fail("planet_angles_deg", "has " + std::to_string(angles->size()) +
                                    " entries but planets = " + std::to_string(*count));
  }
  for (const Number& a : *angles) psi.push_back(DegToRad(a.value));
  for (std::size_t i = 0; i < psi.size(); ++i) {
    for (std::size_t j = 0; j < i; ++j) {
      const double d = std::remainder(psi[i] - psi[j], kTwoPi);
      if (std::abs(d) < 1e-9) {
        f.Fail("planet_angles_deg", "planets " + std::to_string(j) + " and " + std::to_string(i) +
                                        " are at the same angle " +
                                        FormatNumber((*angles)[i].value) + " deg");
      }
    }
  }
  return psi;
}

// Assembly condition (Parker & Lin 2004): (z_s + z_r)(ψ_n − ψ_0)/2π must be an integer.
void CheckAssembly(const Fields& f, const PlanetaryDef& p) {
  const int sum = p.sun_teeth + p.ring_teeth;
  const int count = static_cast<int>(p.planet_angles.size());
  if (p.equally_spaced) {
    if (sum % count != 0) {
      f.Fail("planets", std::to_string(count) +
                            " equally spaced planets cannot be assembled: (z_s + z_r)/N = (" +
                            std::to_string(p.sun_teeth) + " + " + std::to_string(p.ring_teeth) +
                            ")/" + std::to_string(count) + " = " +
                            FormatNumber(static_cast<double>(sum) / count) +
                            " is not an integer (choose N dividing z_s + z_r, or give "
                            "planet_angles_deg with (z_s + z_r) psi/360 integer)");
    }
    return;
  }
  for (int n = 1; n < count; ++n) {
    const double q = sum * (p.planet_angles[n] - p.planet_angles[0]) / kTwoPi;
    if (std::abs(q - std::round(q)) > kAssemblyTol) {
      f.Fail("planet_angles_deg",
             "planet " + std::to_string(n) + " at " + FormatNumber(RadToDeg(p.planet_angles[n])) +
                 " deg cannot be assembled: (z_s + z_r)(psi_n - psi_0)/360 = " + FormatNumber(q) +
                 " is not an integer (nearest assemblable angle: " +
                 FormatNumber(RadToDeg(p.planet_angles[0]) + 360.0 * std::round(q) / sum) +
                 " deg)");
    }
  }
}

// Neighbouring planets must not touch: centre spacing 2 a_w sin(Δψ/2) > 2 r_a (tip radius).
void CheckPlanetClearance(const Fields& f, const PlanetaryDef& p, double tip_radius) {
  std::vector<double> psi = p.planet_angles;
  for (double& a : psi) a = std::fmod(std::fmod(a, kTwoPi) + kTwoPi, kTwoPi);
  std::sort(psi.begin(), psi.end());
  if (psi.size() < 2) return;
  for (std::size_t i = 0; i < psi.size(); ++i) {
    const double next = i + 1 < psi.size() ? psi[i + 1] : psi[0] + kTwoPi;
    const double spacing = 2.0 * p.center_distance * std::sin(0.5 * (next - psi[i]));
    if (spacing <= 2.0 * tip_radius) {
      f.Fail(p.equally_spaced ? "planets" : "planet_angles_deg",
             "neighbouring planets overlap: their centres are " + FormatNumber(spacing) +
                 " m apart but the planet tip diameter is " + FormatNumber(2.0 * tip_radius) +
                 " m");
    }
  }
}

PlanetaryFixedMember ReadFixed(const Fields& f) {
  const std::optional<std::string> fixed = f.OptString("fixed");
  if (!fixed || *fixed == "ring") return PlanetaryFixedMember::kRing;
  if (*fixed == "carrier") return PlanetaryFixedMember::kCarrier;
  if (*fixed == "sun") return PlanetaryFixedMember::kSun;
  const std::vector<std::string> names = {"ring", "carrier", "sun"};
  f.Fail("fixed", "must be \"ring\", \"carrier\" or \"sun\", got \"" + *fixed + "\"" +
                      DidYouMean(*fixed, names));
}

// The carrier sub-table: a body without teeth.
GearDef ReadCarrier(const Fields& f, const Scene& scene) {
  const toml::table* t = f.OptTable("carrier");
  if (t == nullptr) f.Missing("carrier", "a table {name, mass, inertia, transverse_inertia}");
  const Fields c(f.context(), *t, f.Key("carrier"));
  c.CheckKnown({"name", "mass", "inertia", "transverse_inertia"});
  GearDef g;
  g.name = c.OptString("name").value_or("carrier");
  if (g.name.empty() || Has(scene.gears, g.name)) {
    c.Fail("name", "'" + g.name + "' is empty or already the name of a gear");
  }
  g.blank.teeth = 0;
  ReadMassProperties(c, &g);
  return g;
}

// The index of the template mesh between gears a and b (either order), or −1.
int FindMesh(const Scene& scene, const std::string& a, const std::string& b) {
  for (std::size_t k = 0; k < scene.meshes.size(); ++k) {
    const MeshDef& m = scene.meshes[k];
    if ((m.pinion == a && m.gear == b) || (m.pinion == b && m.gear == a)) {
      return static_cast<int>(k);
    }
  }
  return -1;
}

// T = blockdiag(R, R), R the rotation by ψ about z: K_global = T K_local Tᵀ.
Matrix6 RotateAboutZ(const Matrix6& local, double psi) {
  Matrix6 T = Matrix6::Zero();
  Matrix3 R;
  R << std::cos(psi), -std::sin(psi), 0.0, std::sin(psi), std::cos(psi), 0.0, 0.0, 0.0, 1.0;
  T.topLeftCorner<3, 3>() = R;
  T.bottomRightCorner<3, 3>() = R;
  return T * local * T.transpose();
}

}  // namespace

void ReadPlanetary(const ErrorContext& ctx, const toml::table& t, std::size_t index, Scene* scene) {
  CheckElementKeys(ctx, t, "planetary", index,
                   {"name", "sun", "ring", "planet", "planets", "planet_angles_deg", "fixed",
                    "carrier", "planet_bearing_stiffness", "planet_bearing_damping"});
  PlanetaryDef p;
  p.name = ReadElementName(ctx, t, "planetary", index);
  const std::string prefix = "planetary." + p.name;
  const Fields f(ctx, t, prefix);
  for (const PlanetaryDef& other : scene->planetaries) {
    if (other.name == p.name) f.Fail("name", "duplicate planetary name '" + p.name + "'");
  }
  p.sun = ReadGearName(f, "sun", "name of the sun [[gear]]", *scene);
  p.ring = ReadGearName(f, "ring", "name of the ring [[gear]] (internal = true)", *scene);
  const std::string planet =
      ReadGearName(f, "planet", "name of the planet [[gear]] (a template for all planets)", *scene);
  const GearDef& sun = scene->gear(p.sun);
  const GearDef& ring = scene->gear(p.ring);
  const GearDef planet_gear = scene->gear(planet);
  if (ring.blank.kind != GearKind::kInternal) {
    f.Fail("ring", "'" + p.ring + "' must be an internal gear (internal = true)");
  }
  if (sun.blank.kind != GearKind::kExternal) f.Fail("sun", "'" + p.sun + "' must be external");
  if (planet_gear.blank.kind != GearKind::kExternal) {
    f.Fail("planet", "'" + planet + "' must be external");
  }
  if (p.sun == planet) f.Fail("planet", "must differ from the sun ('" + p.sun + "')");
  for (const PlanetaryDef& other : scene->planetaries) {
    for (const std::string& member : {p.sun, p.ring}) {
      if (member == other.sun || member == other.ring) {
        f.Fail(member == p.sun ? "sun" : "ring",
               "'" + member + "' is already a member of planetary '" + other.name + "'");
      }
    }
  }
  p.sun_teeth = sun.blank.teeth;
  p.ring_teeth = ring.blank.teeth;
  p.planet_teeth = planet_gear.blank.teeth;

  // The two template meshes; the planet template meshes with nothing else.
  const int sun_mesh = FindMesh(*scene, p.sun, planet);
  const int ring_mesh = FindMesh(*scene, planet, p.ring);
  if (sun_mesh < 0) {
    ctx.Fail(&t, prefix,
             "no [[mesh]] between the sun '" + p.sun + "' and the planet '" + planet +
                 "' (give one with pinion = \"" + p.sun +
                 "\": it sets the mesh model of every sun-planet mesh)");
  }
  if (ring_mesh < 0) {
    ctx.Fail(&t, prefix,
             "no [[mesh]] between the planet '" + planet + "' and the ring '" + p.ring +
                 "' (give one with pinion = \"" + planet +
                 "\": it sets the mesh model of every ring-planet mesh)");
  }
  const MeshDef sp = scene->meshes[sun_mesh];
  const MeshDef rp = scene->meshes[ring_mesh];
  if (sp.pinion != p.sun) {
    ctx.Fail(&t, prefix,
             "mesh '" + sp.name + "': the sun '" + p.sun +
                 "' must be its pinion (the sun drives the planets in geardyn's convention)");
  }
  for (const MeshDef& m : scene->meshes) {
    if ((m.pinion == planet || m.gear == planet) && m.name != sp.name && m.name != rp.name) {
      ctx.Fail(&t, prefix,
               "mesh '" + m.name + "' meshes the planet template '" + planet +
                   "' with another gear; planets mesh only with the sun and the ring");
    }
  }
  const double a_sp = sp.geometry.center_distance;
  const double a_rp = rp.geometry.center_distance;
  if (std::abs(a_sp - a_rp) > kEqualTol * a_sp) {
    ctx.Fail(&t, prefix,
             "the sun-planet centre distance " + FormatNumber(a_sp) + " m (mesh '" + sp.name +
                 "') differs from the ring-planet one " + FormatNumber(a_rp) + " m (mesh '" +
                 rp.name + "'); standard gears need z_r = z_s + 2 z_p (here " +
                 std::to_string(p.ring_teeth) + " vs " +
                 std::to_string(p.sun_teeth + 2 * p.planet_teeth) +
                 "), otherwise give profile shifts or the same center_distance on both meshes");
  }
  p.center_distance = a_sp;

  p.planet_angles = ReadAngles(f, &p.equally_spaced);
  CheckAssembly(f, p);
  CheckPlanetClearance(f, p, sp.geometry.gear.tip_radius);
  p.fixed = ReadFixed(f);
  GearDef carrier = ReadCarrier(f, *scene);
  p.carrier = carrier.name;
  if (carrier.name == planet) f.Fail("carrier", "its name must differ from the planet's");
  p.planet_bearing_stiffness =
      ReadMatrix6(f, "planet_bearing_stiffness", "planet bearing stiffness in N/m, N/rad, N m/rad");
  if (p.planet_bearing_stiffness(5, 5) != 0.0) {
    f.Fail("planet_bearing_stiffness",
           "the rz entry must be 0 (a planet turns freely on its bearing), got " +
               FormatNumber(p.planet_bearing_stiffness(5, 5)));
  }
  if (f.Find("planet_bearing_damping") != nullptr) {
    p.planet_bearing_damping = ReadMatrix6(f, "planet_bearing_damping",
                                           "planet bearing damping in N s/m, N s/rad, N m s/rad");
  }
  p.sun_ring_phase = CalcSunRingMeshPhase(sp.geometry, rp.geometry);

  // Expansion: planets and carrier replace the template gear, per-planet meshes the templates.
  std::erase_if(scene->gears, [&](const GearDef& g) { return g.name == planet; });
  std::erase_if(scene->meshes,
                [&](const MeshDef& m) { return m.name == sp.name || m.name == rp.name; });
  for (std::size_t n = 0; n < p.planet_angles.size(); ++n) {
    const std::string suffix = "_" + std::to_string(n + 1);
    GearDef g = planet_gear;
    g.name = planet + suffix;
    MeshDef s = sp;
    s.name = sp.name + suffix;
    s.gear = g.name;
    MeshDef r = rp;
    r.name = rp.name + suffix;
    r.pinion = g.name;
    if (Has(scene->gears, g.name) || g.name == carrier.name) {
      ctx.Fail(&t, prefix, "planet '" + g.name + "': a gear of that name already exists");
    }
    for (const std::string& name : {s.name, r.name}) {
      if (HasMesh(scene->meshes, name)) {
        ctx.Fail(&t, prefix, "planet mesh '" + name + "': a mesh of that name already exists");
      }
    }
    p.planets.push_back(g.name);
    p.sun_meshes.push_back(s.name);
    p.ring_meshes.push_back(r.name);
    p.planet_bearings.push_back(g.name + "-" + carrier.name);
    scene->gears.push_back(std::move(g));
    scene->meshes.push_back(std::move(s));
    scene->meshes.push_back(std::move(r));
  }
  scene->gears.push_back(std::move(carrier));
  scene->planetaries.push_back(std::move(p));
}

void AddPlanetBearings(const ErrorContext& ctx, const std::vector<const toml::table*>& tables,
                       Scene* scene) {
  for (std::size_t i = 0; i < scene->planetaries.size(); ++i) {
    const PlanetaryDef& p = scene->planetaries[i];
    for (std::size_t n = 0; n < p.planets.size(); ++n) {
      BearingDef b;
      b.name = p.planet_bearings[n];
      for (const BearingDef& other : scene->bearings) {
        if (other.name == b.name) {
          ctx.Fail(tables[i], "planetary." + p.name,
                   "the planet bearing '" + b.name + "' has the name of a [[bearing]]");
        }
      }
      b.body = p.planets[n];
      b.other = p.carrier;
      b.stiffness = RotateAboutZ(p.planet_bearing_stiffness, p.planet_angles[n]);
      b.damping = RotateAboutZ(p.planet_bearing_damping, p.planet_angles[n]);
      scene->bearings.push_back(std::move(b));
    }
  }
}

void CheckPlanetaryOperatingPoint(const ErrorContext& ctx,
                                  const std::vector<const toml::table*>& tables,
                                  const Scene& scene) {
  for (std::size_t i = 0; i < scene.planetaries.size(); ++i) {
    const PlanetaryDef& p = scene.planetaries[i];
    if (scene.operating_point.body == p.fixed_member()) {
      const toml::node* fixed = tables[i]->get("fixed");
      ctx.Fail(fixed != nullptr ? fixed : tables[i], "planetary." + p.name + ".fixed",
               "'" + p.fixed_member() +
                   "' is held fixed (zero speed) but it is the operating point's body; make "
                   "another member the reference or fix another member");
    }
  }
}

}  // namespace geardyn::internal
