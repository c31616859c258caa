// Reading [mesh.contact] (tooth contact, spec 03) into a ContactMeshDef; keys documented in
// docs/scene-format.md, "Tooth contact".
#include <algorithm>
#include <array>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "scene/mesh_model_reader.hpp"
#include "scene/suggestions.hpp"

namespace geardyn::internal {
namespace {

/// Densities below this are probably g/cm³ (steel 7.85) [kg/m³]; above the upper bound no
/// engineering material (osmium 22 600).
constexpr double kMinDensity = 100.0;
constexpr double kMaxDensity = 3.0e4;
/// Upper bounds that catch wrong units or meaningless values.
constexpr double kMaxFrictionCoefficient = 1.0;
constexpr double kMaxFrictionSpeed = 1.0;  // m/s: above it the whole sliding range is smoothed
constexpr int kMaxArcs = 64;
constexpr int kMaxFaceSlices = 1000;

template <typename T, std::size_t N>
T ReadChoice(const Fields& f, std::string_view key, const std::array<T, N>& values,
             const char* (*name)(T), T fallback) {
  const std::optional<std::string> given = f.OptString(key);
  if (!given) return fallback;
  std::vector<std::string> names;
  for (const T v : values) {
    if (*given == name(v)) return v;
    names.emplace_back(name(v));
  }
  f.Fail(key, "unknown value '" + *given + "'" + DidYouMean(*given, names) +
                  "; values: " + JoinNames(names));
}

// Fails at `key` when it is given although `applies` is false.
void OnlyWhen(const Fields& f, std::string_view key, bool applies, const std::string& reason) {
  if (!applies && f.Find(key) != nullptr) f.Fail(key, reason);
}

}  // namespace

ContactMeshDef ReadContactMesh(const Fields& f, const GearPairGeometry& geometry) {
  f.CheckKnown({"teeth",
                "bending_stiffness",
                "bending_damping",
                "bushing_radial_stiffness",
                "bushing_tangential_stiffness",
                "bushing_radial_damping",
                "bushing_tangential_damping",
                "density",
                "tooth_mass",
                "tooth_inertia",
                "law",
                "stiffness",
                "stiffness_exponent",
                "damping",
                "damping_exponent",
                "indentation_exponent",
                "young_modulus",
                "poisson",
                "friction_coefficient",
                "friction_speed",
                "profile",
                "arcs",
                "tip_corner_radius",
                "face_slices"});
  ContactMeshDef def;

  // ---- tooth bodies
  def.teeth = ReadChoice(
      f, "teeth",
      std::array{ToothBodyType::kRigid, ToothBodyType::kRevolute, ToothBodyType::kBushing},
      &ToString, ToothBodyType::kRigid);
  const bool flexible = def.teeth != ToothBodyType::kRigid;
  const bool bushing = def.teeth == ToothBodyType::kBushing;
  const std::string teeth_text = std::string("teeth = \"") + ToString(def.teeth) + "\"";
  for (const std::string_view key :
       {"bending_stiffness", "bending_damping", "density", "tooth_mass", "tooth_inertia"}) {
    OnlyWhen(f, key, flexible,
             "only used by teeth = \"revolute\" or \"bushing\" (" + teeth_text +
                 ": the teeth are part of the gear bodies)");
  }
  for (const std::string_view key : {"bushing_radial_stiffness", "bushing_tangential_stiffness",
                                     "bushing_radial_damping", "bushing_tangential_damping"}) {
    OnlyWhen(f, key, bushing, "only used by teeth = \"bushing\" (" + teeth_text + ")");
  }
  if (flexible) {
    if (geometry.pinion.kind != GearKind::kExternal || geometry.gear.kind != GearKind::kExternal) {
      f.Fail("teeth",
             "tooth bodies are modelled on external gears only (this mesh has an "
             "internal gear); use teeth = \"rigid\"");
    }
    def.bending_stiffness =
        f.ReqPositive("bending_stiffness",
                      "the root joint's rotational stiffness k_b [N m/rad] of the " + teeth_text +
                          " teeth; Kim et al. give 11.5e3 N m/rad for the module-3 rig");
    if (const std::optional<Number> c = f.OptNumber("bending_damping")) {
      f.NonNegative("bending_damping", *c);
      def.bending_damping = c->value;
    }
    def.bushing_radial_stiffness = f.OptPositive("bushing_radial_stiffness");
    def.bushing_tangential_stiffness = f.OptPositive("bushing_tangential_stiffness");
    for (const auto& [key, out] :
         {std::pair{"bushing_radial_damping", &def.bushing_radial_damping},
          std::pair{"bushing_tangential_damping", &def.bushing_tangential_damping}}) {
      if (const std::optional<Number> c = f.OptNumber(key)) {
        f.NonNegative(key, *c);
        *out = c->value;
      }
    }
    const std::optional<Number> mass = f.OptNumber("tooth_mass");
    const std::optional<Number> inertia = f.OptNumber("tooth_inertia");
    if (mass || inertia) {
      if (!mass) f.Missing("tooth_mass", "given with tooth_inertia: the mass of one tooth [kg]");
      if (!inertia) {
        f.Missing("tooth_inertia",
                  "given with tooth_mass: one tooth's inertia about its centroid [kg m^2]");
      }
      OnlyWhen(f, "density", false,
               "not used with tooth_mass and tooth_inertia (give either the density or the "
               "tooth's mass properties)");
      f.Positive("tooth_mass", *mass);
      f.Positive("tooth_inertia", *inertia);
      def.tooth_mass = mass->value;
      def.tooth_inertia = inertia->value;
    }
    if (const std::optional<Number> rho = f.OptNumber("density")) {
      f.Positive("density", *rho);
      if (rho->value < kMinDensity || rho->value > kMaxDensity) {
        f.Fail("density", FormatNumber(rho->value) + " kg/m^3 is outside [" +
                              FormatNumber(kMinDensity) + ", " + FormatNumber(kMaxDensity) +
                              "] (units are kg/m^3: steel 7850, not 7.85 g/cm^3)");
      }
      def.density = rho->value;
    }
  }

  // ---- contact law
  def.law.kind = ReadChoice(
      f, "law", std::array{ContactLawKind::kKim, ContactLawKind::kLinear, ContactLawKind::kLine},
      &ToString, ContactLawKind::kKim);
  const ContactLawKind kind = def.law.kind;
  const std::string law_text = std::string("law = \"") + ToString(kind) + "\"";
  if (kind == ContactLawKind::kLinear) {
    def.law = LinearContactLaw(1.0, 0.0);  // stiffness replaced below (required)
  }
  OnlyWhen(f, "stiffness", kind != ContactLawKind::kLine,
           "not used by law = \"line\" (its stiffness follows from young_modulus, poisson and "
           "the flank curvatures)");
  OnlyWhen(f, "stiffness_exponent", kind == ContactLawKind::kKim,
           "only used by law = \"kim\" (" + law_text + ")");
  for (const std::string_view key : {"damping_exponent", "indentation_exponent"}) {
    OnlyWhen(f, key, kind != ContactLawKind::kLinear,
             "not used by law = \"linear\" (its damping is c times the penetration rate)");
  }
  if (kind == ContactLawKind::kLinear) {
    def.law.stiffness = f.ReqPositive("stiffness", "the linear contact stiffness k [N/m]");
  } else if (kind == ContactLawKind::kKim) {
    if (const std::optional<double> k = f.OptPositive("stiffness")) def.law.stiffness = *k;
    if (const std::optional<double> m1 = f.OptPositive("stiffness_exponent")) {
      def.law.stiffness_exponent = *m1;
    }
  }
  if (const std::optional<Number> c = f.OptNumber("damping")) {
    f.NonNegative("damping", *c);
    def.law.damping = c->value;
  }
  if (const std::optional<Number> m2 = f.OptNumber("damping_exponent")) {
    if (!(m2->value >= 1.0)) {
      f.Fail("damping_exponent",
             "must be >= 1, got " + FormatNumber(m2->value) +
                 " (below 1 the damping force has an unbounded derivative at zero penetration "
                 "rate)");
    }
    def.law.damping_exponent = m2->value;
  }
  if (const std::optional<double> m3 = f.OptPositive("indentation_exponent")) {
    def.law.indentation_exponent = *m3;
  }

  // ---- material
  const bool default_bushing =
      bushing && (!def.bushing_radial_stiffness || !def.bushing_tangential_stiffness);
  for (const std::string_view key : {"young_modulus", "poisson"}) {
    OnlyWhen(f, key, kind == ContactLawKind::kLine || default_bushing,
             "only used by law = \"line\" and by the default bushing stiffnesses (" + law_text +
                 ", " + teeth_text + ")");
  }
  if (const std::optional<double> e = f.OptPositive("young_modulus")) def.young_modulus = *e;
  if (const std::optional<Number> nu = f.OptNumber("poisson")) {
    if (!(nu->value >= 0.0 && nu->value < 0.5)) {
      f.Fail("poisson", "must be in [0, 0.5), got " + FormatNumber(nu->value));
    }
    def.poisson = nu->value;
  }
  if (kind == ContactLawKind::kLine) {
    def.law.contact_modulus = ContactModulusSameMaterial(def.young_modulus, def.poisson);
  }
  std::string why;
  if (!def.law.IsValid(&why)) f.context().Fail(&f.table(), f.prefix(), why);

  // ---- friction
  if (const std::optional<Number> mu = f.OptNumber("friction_coefficient")) {
    f.NonNegative("friction_coefficient", *mu);
    if (mu->value > kMaxFrictionCoefficient) {
      f.Fail("friction_coefficient", "must be at most " + FormatNumber(kMaxFrictionCoefficient) +
                                         ", got " + FormatNumber(mu->value));
    }
    def.friction_coefficient = mu->value;
  }
  OnlyWhen(f, "friction_speed", def.friction_coefficient > 0.0,
           "only used with friction_coefficient > 0 (the mesh is frictionless)");
  if (const std::optional<double> eps = f.OptPositive("friction_speed")) {
    if (*eps > kMaxFrictionSpeed) {
      f.Fail("friction_speed", "must be at most " + FormatNumber(kMaxFrictionSpeed) +
                                   " m/s (the regularisation would smooth the whole sliding "
                                   "range), got " +
                                   FormatNumber(*eps));
    }
    def.friction_speed = *eps;
  }

  // ---- profile and slices
  def.profile =
      ReadChoice(f, "profile", std::array{ContactProfile::kInvolute, ContactProfile::kBiarc},
                 &ToString, ContactProfile::kInvolute);
  OnlyWhen(f, "arcs", def.profile == ContactProfile::kBiarc,
           "only used by profile = \"biarc\" (profile = \"involute\" is exact)");
  if (const std::optional<int> arcs = f.OptInt("arcs", 1, kMaxArcs)) def.arcs = *arcs;
  if (const std::optional<Number> rc = f.OptNumber("tip_corner_radius")) {
    f.NonNegative("tip_corner_radius", *rc);
    const double bound = 0.5 * std::min(geometry.pinion.tip_thickness_transverse,
                                        geometry.gear.tip_thickness_transverse);
    if (!(rc->value < bound)) {
      f.Fail("tip_corner_radius", "must be below half the thinner tip thickness, " +
                                      FormatNumber(bound) + " m, got " + FormatNumber(rc->value) +
                                      " m");
    }
    def.tip_corner_radius = rc->value;
  }
  if (const std::optional<int> n = f.OptInt("face_slices", 1, kMaxFaceSlices)) {
    def.face_slices = *n;
  }
  return def;
}

}  // namespace geardyn::internal
