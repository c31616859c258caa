// Reading one [[mesh]] table: the two gears, their compatibility, the pair geometry and the mesh
// model (mesh_model_reader.cpp).
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>

#include "geardyn/common/units.hpp"
#include "scene/element_names.hpp"
#include "scene/mesh_model_reader.hpp"
#include "scene/section_readers.hpp"
#include "scene/toml_fields.hpp"

namespace geardyn::internal {
namespace {

// An angle in radians shown in degrees, rounded to 10 significant digits (hides the rounding of
// the degree → radian → degree round trip).
std::string FormatDegrees(double rad) {
  std::array<char, 64> buf{};
  std::snprintf(buf.data(), buf.size(), "%.10g", RadToDeg(rad));
  return std::string(buf.data()) + " deg";
}

// Rejects gears that cannot mesh: different normal module, pressure angle or helix angle, or
// hands that do not match (external: opposite, internal: equal).
void CheckCompatible(const ErrorContext& ctx, const toml::table& t, const std::string& prefix,
                     const GearDef& p, const GearDef& g) {
  const auto differs = [](double a, double b) {
    return std::abs(a - b) > kEqualTol * std::max(std::abs(a), std::abs(b));
  };
  const auto mismatch = [&](const std::string& what, const std::string& vp, const std::string& vg) {
    ctx.Fail(&t, prefix,
             what + " differs: pinion '" + p.name + "' has " + vp + " but gear '" + g.name +
                 "' has " + vg + " (meshing gears need the same)");
  };
  if (differs(p.normal_module, g.normal_module)) {
    mismatch("normal_module", FormatNumber(p.normal_module) + " m",
             FormatNumber(g.normal_module) + " m");
  }
  if (differs(p.normal_pressure_angle, g.normal_pressure_angle)) {
    mismatch("normal_pressure_angle_deg", FormatDegrees(p.normal_pressure_angle),
             FormatDegrees(g.normal_pressure_angle));
  }
  if (differs(p.helix_angle, g.helix_angle)) {
    mismatch("helix_angle_deg", FormatDegrees(p.helix_angle), FormatDegrees(g.helix_angle));
  }
  const bool internal = g.blank.kind == GearKind::kInternal;
  if (p.hand != HelixHand::kNone) {
    const char* hand = p.hand == HelixHand::kRight ? "right" : "left";
    if (!internal && p.hand == g.hand) {
      ctx.Fail(&t, prefix,
               std::string("external helical gears need opposite hands, but pinion '") + p.name +
                   "' and gear '" + g.name + "' are both " + hand + "-handed");
    }
    if (internal && p.hand != g.hand) {
      ctx.Fail(&t, prefix,
               "an internal helical mesh needs equal hands, but pinion '" + p.name + "' is " +
                   hand + "-handed and ring '" + g.name + "' is not");
    }
  }
}

// The pair geometry of two compatible gears at the mesh's (optional) centre distance; a
// rejection is reported at the mesh, or at its center_distance if that is what it concerns.
GearPairGeometry ReadGeometry(const Fields& f, const std::string& prefix, const GearDef& p,
                              const GearDef& g) {
  GearPairSpec spec;
  spec.normal_module = p.normal_module;
  spec.normal_pressure_angle = p.normal_pressure_angle;
  spec.helix_angle = p.helix_angle;
  spec.pinion_hand = p.hand;
  spec.pinion = p.blank;
  spec.gear = g.blank;
  spec.center_distance = f.OptPositive("center_distance");
  try {
    return CalcGearPairGeometry(spec);
  } catch (const InvalidInput& e) {
    const std::string reason = e.what();
    // A centre-distance problem is reported where the centre distance was given.
    const toml::node* given = f.Find("center_distance");
    const bool at_given = given != nullptr && reason.rfind("center_distance", 0) == 0;
    f.context().Fail(at_given ? given : &f.table(), prefix, reason);
  }
}

}  // namespace

MeshDef ReadMesh(const ErrorContext& ctx, const toml::table& t, std::size_t index,
                 const Scene& scene) {
  MeshDef m;
  CheckElementKeys(
      ctx, t, "mesh", index,
      {"name", "pinion", "gear", "center_distance", "model", "slices", "stiffness_per_length",
       "damping_ratio", "damping", "coefficient_form", "fourier_terms", "fourier_tolerance",
       "table_samples", "modifications", "errors", "parameters", "contact"});
  const Fields named(ctx, t, ElementPrefix(t, "mesh", index));
  m.pinion = named.ReqString("pinion", "name of the driving [[gear]]");
  m.gear = named.ReqString("gear", "name of the driven [[gear]]");
  m.name = ReadElementName(ctx, t, "mesh", index);
  const std::string prefix = "mesh." + m.name;
  const Fields f(ctx, t, prefix);
  const GearDef& p = GearByName(f, "pinion", m.pinion, scene);
  const GearDef& g = GearByName(f, "gear", m.gear, scene);
  if (m.pinion == m.gear) f.Fail("gear", "a gear cannot mesh with itself ('" + m.gear + "')");
  if (p.blank.kind == GearKind::kInternal) {
    f.Fail("pinion", "'" + p.name +
                         "' is an internal gear; the pinion of a mesh must be external (make "
                         "the ring the mesh's gear)");
  }
  if (p.blank.kind == GearKind::kRack) {
    f.Fail("pinion", "'" + p.name +
                         "' is a rack; the pinion of a mesh must be a gear (make the rack the "
                         "mesh's gear: the drive sign follows the operating point either way)");
  }
  if (g.blank.kind == GearKind::kRack) {
    for (const MeshDef& other : scene.meshes) {
      if (other.gear == m.gear || other.pinion == m.gear) {
        f.Fail("gear", "rack '" + m.gear + "' already meshes in mesh '" + other.name +
                           "'; a rack meshes with one pinion here");
      }
    }
  }
  for (const MeshDef& other : scene.meshes) {
    if ((other.pinion == m.pinion && other.gear == m.gear) ||
        (other.pinion == m.gear && other.gear == m.pinion)) {
      ctx.Fail(&t, prefix,
               "gears '" + m.pinion + "' and '" + m.gear + "' already mesh in mesh '" + other.name +
                   "'");
    }
  }
  CheckCompatible(ctx, t, prefix, p, g);
  m.geometry = ReadGeometry(f, prefix, p, g);
  m.model = ReadMeshModel(f, p, g, m.geometry);
  if (m.geometry.rack &&
      (m.model.level == MeshModelLevel::kTorsional || m.model.level == MeshModelLevel::kContact)) {
    f.Fail("model", std::string("\"") + ToString(m.model.level) +
                        "\" is not available on a rack (" +
                        (m.model.level == MeshModelLevel::kTorsional
                             ? "the torsional model has no translation for it"
                             : "the tooth-contact simulator has no rack geometry yet") +
                        "); use \"blankenship_singh\" or \"slices\"");
  }
  return m;
}

}  // namespace geardyn::internal
