// Reading one [[gear]] table: teeth, basic-rack and blank data, helix, mass properties; a
// gear with rack = true is a rack (gear_geometry.hpp "Rack").
#include <array>
#include <cstdint>
#include <string_view>

#include "geardyn/common/units.hpp"
#include "scene/element_names.hpp"
#include "scene/section_readers.hpp"
#include "scene/suggestions.hpp"
#include "scene/toml_fields.hpp"

namespace geardyn::internal {
namespace {

// Plausibility bounds (documented in docs/scene-format.md).
constexpr std::int64_t kMaxTeeth = 10000;
constexpr double kMaxModule = 0.1;     // m
constexpr double kMaxFaceWidth = 2.0;  // m
constexpr double kMaxPressureAngleDeg = 45.0;
constexpr double kMaxHelixAngleDeg = 45.0;

// Helix angle [deg] and hand; the hand is required exactly when the gear is helical.
void ReadHelix(const Fields& f, GearDef* g) {
  double helix_deg = 0.0;
  if (auto beta = f.OptNumber("helix_angle_deg")) {
    if (beta->value < 0.0) {
      f.Fail("helix_angle_deg",
             "must be >= 0 (give the direction with hand = \"right\" or \"left\"), got " +
                 FormatNumber(beta->value));
    }
    if (beta->value > kMaxHelixAngleDeg) {
      f.Fail("helix_angle_deg", "must be at most " + FormatNumber(kMaxHelixAngleDeg) +
                                    " degrees, got " + FormatNumber(beta->value));
    }
    helix_deg = beta->value;
  }
  g->helix_angle = DegToRad(helix_deg);

  if (auto hand = f.OptString("hand")) {
    // An explicit helix_angle_deg = 0 with a hand is the spur limit of a helical pair (a sweep
    // over β through 0, `geardyn compare --vary`): the hand is checked and has no effect. A hand
    // on a gear without helix_angle_deg is an error (a spur gear has none).
    if (helix_deg == 0.0 && f.Find("helix_angle_deg") == nullptr) {
      f.Fail("hand",
             "must not be given for a spur gear (no helix_angle_deg), got \"" + *hand + "\"");
    }
    if (*hand == "right") {
      g->hand = helix_deg == 0.0 ? HelixHand::kNone : HelixHand::kRight;
    } else if (*hand == "left") {
      g->hand = helix_deg == 0.0 ? HelixHand::kNone : HelixHand::kLeft;
    } else {
      const std::array<std::string_view, 2> hands = {"right", "left"};
      f.Fail("hand",
             "must be \"right\" or \"left\", got \"" + *hand + "\"" + DidYouMean(*hand, hands));
    }
  } else if (helix_deg != 0.0) {
    f.Missing("hand", "\"right\" or \"left\" for a helical gear (helix_angle_deg = " +
                          FormatNumber(helix_deg) + ")");
  }
}

// The optional rack and blank data of ISO 21771 / ISO 6336 (defaults: GearBlank's).
void ReadBlankOptions(const Fields& f, GearBlank* b) {
  if (auto x = f.OptNumber("profile_shift")) b->profile_shift = x->value;
  if (auto h = f.OptPositive("addendum_coefficient")) b->addendum_coefficient = *h;
  if (auto h = f.OptPositive("dedendum_coefficient")) b->dedendum_coefficient = *h;
  if (auto rho = f.OptNumber("root_radius_coefficient")) {
    f.NonNegative("root_radius_coefficient", *rho);
    b->root_radius_coefficient = rho->value;
  }
  b->tip_diameter = f.OptPositive("tip_diameter");
  if (auto internal = f.OptBool("internal")) {
    b->kind = *internal ? GearKind::kInternal : GearKind::kExternal;
  }
  if (f.OptBool("rack").value_or(false)) {
    if (b->kind == GearKind::kInternal) {
      f.Fail("rack", "a rack has no internal teeth; give at most one of rack and internal");
    }
    b->kind = GearKind::kRack;
  }
  b->web_thickness = f.OptPositive("web_thickness");
  b->rim_thickness = f.OptPositive("rim_thickness");
}

}  // namespace

// Mass, polar and (optional) transverse moment of inertia, and where the body's table is.
void ReadMassProperties(const Fields& f, GearDef* g) {
  // Optional here: only analyses that build the mass matrix need them (BuildSceneSystem).
  g->mass = f.OptPositive("mass");
  g->inertia = f.OptPositive("inertia");
  if (auto it = f.OptPositive("transverse_inertia")) {
    // Triangle inequality of the principal moments of a rigid body: I_zz <= I_xx + I_yy.
    if (g->inertia && *g->inertia > 2.0 * *it * (1.0 + kEqualTol)) {
      f.Fail("transverse_inertia",
             "must be at least inertia/2 = " + FormatNumber(*g->inertia / 2.0) +
                 " kg m² (no rigid body has a polar moment above the sum of the two transverse "
                 "ones), got " +
                 FormatNumber(*it));
    }
    g->transverse_inertia = *it;
  }
  g->key = f.prefix();
  g->line = f.context().Line(&f.table());
}

GearDef ReadGear(const ErrorContext& ctx, const toml::table& t, std::size_t index) {
  GearDef g;
  const Fields f(ctx, t, ElementPrefix(t, "gear", index));
  f.CheckKnown({"name", "teeth", "normal_module", "normal_pressure_angle_deg", "helix_angle_deg",
                "hand", "face_width", "profile_shift", "addendum_coefficient",
                "dedendum_coefficient", "root_radius_coefficient", "tip_diameter", "internal",
                "rack", "web_thickness", "rim_thickness", "mass", "inertia", "transverse_inertia"});
  g.name = ReadElementName(ctx, t, "gear", index);

  GearBlank& b = g.blank;
  // A rack (rack = true) has no tooth count that enters the mesh: its length is not modelled.
  const bool rack = f.OptBool("rack").value_or(false);
  if (!rack) {
    b.teeth = f.ReqPositiveInt("teeth", "number of teeth, a positive integer", kMaxTeeth);
  } else if (f.Find("teeth") != nullptr) {
    f.Fail("teeth",
           "a rack's tooth count is not used (its length does not enter the mesh); leave it out");
  }

  const Number module = f.ReqNumber("normal_module", "normal module in m");
  f.Metres("normal_module", module, kMaxModule);
  g.normal_module = module.value;

  if (auto alpha = f.OptNumber("normal_pressure_angle_deg")) {
    if (!(alpha->value > 0.0 && alpha->value < kMaxPressureAngleDeg)) {
      f.Fail("normal_pressure_angle_deg", "must be in (0, " + FormatNumber(kMaxPressureAngleDeg) +
                                              ") degrees, got " + FormatNumber(alpha->value));
    }
    g.normal_pressure_angle = DegToRad(alpha->value);
  } else {
    g.normal_pressure_angle = DegToRad(20.0);
  }

  ReadHelix(f, &g);

  const Number face = f.ReqNumber("face_width", "face width in m");
  f.Metres("face_width", face, kMaxFaceWidth);
  b.face_width = face.value;

  ReadBlankOptions(f, &b);
  ReadMassProperties(f, &g);
  return g;
}

}  // namespace geardyn::internal
