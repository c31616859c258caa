// Scene reader, the tooth-contact model: model = "contact" and its [mesh.contact] table (keys,
// defaults in SI, Kim's values), each bad input reported as FILE:LINE: KEY: REASON; and the
// analyses that need a linear or slice core refusing such a mesh with the way out.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "geardyn/common/errors.hpp"
#include "geardyn/models/scene/mesh_model.hpp"
#include "geardyn/models/scene/scene_reader.hpp"
#include "geardyn/models/system/scene_system.hpp"
#include "scene_reader_cases.hpp"
#include "support/expect_throws.hpp"

namespace geardyn {
namespace {

using test::BadCase;
using test::kBase;
using test::Replace;

const std::string kMeshEnd = "gear = \"wheel\"\n";

// The base pair with `extra` at the end of its [[mesh]] table.
std::string Mesh(const std::string& extra) { return Replace(kBase, kMeshEnd, kMeshEnd + extra); }

// model = "contact" with a [mesh.contact] table holding `keys`.
std::string Contact(const std::string& keys) {
  return Mesh("model = \"contact\"\n[mesh.contact]\n" + keys);
}

std::vector<BadCase> ContactCases() {
  std::vector<BadCase> c;
  const auto add = [&](std::string name, std::string text, std::string line_of, std::string regex) {
    c.push_back({std::move(name), std::move(text), {}, std::move(line_of), std::move(regex)});
  };
  const std::string p = R"(^t\.toml:{line}: mesh\.pinion-wheel\.contact\.)";
  // --- keys of other levels with model = "contact"
  add("ContactWithDampingRatio", Mesh("model = \"contact\"\ndamping_ratio = 0.05\n"),
      "damping_ratio",
      R"(^t\.toml:{line}: mesh\.pinion-wheel\.damping_ratio: not used by model = "contact" )");
  add("ContactWithStiffnessPerLength", Mesh("model = \"contact\"\nstiffness_per_length = 2e10\n"),
      "stiffness_per_length",
      R"(^t\.toml:{line}: mesh\.pinion-wheel\.stiffness_per_length: not used by model = )");
  // --- [mesh.contact] keys
  add("ContactUnknownKey", Contact("bending_stifness = 1e4\n"), "bending_stifness",
      p + R"(bending_stifness: unknown key \(did you mean 'bending_stiffness'\?\)$)");
  add("ContactUnknownTeeth", Contact("teeth = \"revolut\"\n"), "revolut",
      p + R"(teeth: unknown value 'revolut' \(did you mean 'revolute'\?\); values: rigid, )"
          R"(revolute, bushing$)");
  add("ContactRevoluteWithoutBendingStiffness", Contact("teeth = \"revolute\"\n"), "[mesh.contact]",
      p + R"(bending_stiffness: missing \(required: the root joint's rotational stiffness k_b )");
  add("ContactZeroBendingStiffness", Contact("teeth = \"revolute\"\nbending_stiffness = 0\n"),
      "bending_stiffness", p + R"(bending_stiffness: must be > 0, got 0$)");
  add("ContactNegativeBendingDamping",
      Contact("teeth = \"revolute\"\nbending_stiffness = 1e4\nbending_damping = -1\n"),
      "bending_damping", p + R"(bending_damping: must be >= 0, got -1$)");
  add("ContactBendingStiffnessWithRigidTeeth", Contact("bending_stiffness = 1e4\n"),
      "bending_stiffness",
      p + R"(bending_stiffness: only used by teeth = "revolute" or "bushing" \(teeth = "rigid")");
  add("ContactBushingKeyWithRevolute",
      Contact("teeth = \"revolute\"\nbending_stiffness = 1e4\nbushing_radial_stiffness = 1e9\n"),
      "bushing_radial_stiffness",
      p + R"(bushing_radial_stiffness: only used by teeth = "bushing" \(teeth = "revolute"\)$)");
  add("ContactNegativeBushingStiffness",
      Contact("teeth = \"bushing\"\nbending_stiffness = 1e4\nbushing_tangential_stiffness = -3\n"),
      "bushing_tangential_stiffness", p + R"(bushing_tangential_stiffness: must be > 0, got -3$)");
  add("ContactDensityInGramsPerCubicCentimetre",
      Contact("teeth = \"revolute\"\nbending_stiffness = 1e4\ndensity = 7.85\n"), "density",
      p + R"(density: 7\.85 kg/m\^3 is outside \[100, 30000\] \(units are kg/m\^3)");
  add("ContactZeroDensity", Contact("teeth = \"revolute\"\nbending_stiffness = 1e4\ndensity = 0\n"),
      "density", p + R"(density: must be > 0, got 0$)");
  add("ContactToothMassWithoutInertia",
      Contact("teeth = \"revolute\"\nbending_stiffness = 1e4\ntooth_mass = 0.005\n"),
      "[mesh.contact]", p + R"(tooth_inertia: missing \(required: given with tooth_mass)");
  add("ContactToothMassAndDensity",
      Contact("teeth = \"revolute\"\nbending_stiffness = 1e4\ntooth_mass = 0.005\n"
              "tooth_inertia = 3e-8\ndensity = 7850\n"),
      "density = 7850", p + R"(density: not used with tooth_mass and tooth_inertia)");
  add("ContactUnknownLaw", Contact("law = \"hertz\"\n"), "hertz",
      p + R"(law: unknown value 'hertz'.*; values: kim, linear, line$)");
  add("ContactLinearWithoutStiffness", Contact("law = \"linear\"\n"), "[mesh.contact]",
      p + R"(stiffness: missing \(required: the linear contact stiffness k \[N/m\]\)$)");
  add("ContactNegativeStiffness", Contact("stiffness = -1e12\n"), "stiffness",
      p + R"(stiffness: must be > 0, got -1e\+12$)");
  add("ContactZeroStiffnessExponent", Contact("stiffness_exponent = 0\n"), "stiffness_exponent",
      p + R"(stiffness_exponent: must be > 0, got 0$)");
  add("ContactDampingExponentBelowOne", Contact("damping_exponent = 0.5\n"), "damping_exponent",
      p + R"(damping_exponent: must be >= 1, got 0\.5 \(below 1 the damping force)");
  add("ContactZeroIndentationExponent", Contact("indentation_exponent = 0\n"),
      "indentation_exponent", p + R"(indentation_exponent: must be > 0, got 0$)");
  add("ContactStiffnessExponentWithLinearLaw",
      Contact("law = \"linear\"\nstiffness = 1e9\nstiffness_exponent = 1.5\n"),
      "stiffness_exponent",
      p + R"(stiffness_exponent: only used by law = "kim" \(law = "linear"\)$)");
  add("ContactStiffnessWithLineLaw", Contact("law = \"line\"\nstiffness = 1e9\n"), "stiffness",
      p + R"(stiffness: not used by law = "line")");
  add("ContactYoungModulusWithKimLaw", Contact("young_modulus = 2e11\n"), "young_modulus",
      p + R"(young_modulus: only used by law = "line" and by the default bushing stiffnesses)");
  add("ContactPoissonOutOfRange", Contact("law = \"line\"\npoisson = 0.5\n"), "poisson",
      p + R"(poisson: must be in \[0, 0\.5\), got 0\.5$)");
  add("ContactNegativeFriction", Contact("friction_coefficient = -0.1\n"), "friction_coefficient",
      p + R"(friction_coefficient: must be >= 0, got -0\.1$)");
  add("ContactFrictionSpeedWithoutFriction", Contact("friction_speed = 0.01\n"), "friction_speed",
      p + R"(friction_speed: only used with friction_coefficient > 0 \(the mesh is frictionless\)$)");
  add("ContactFrictionSpeedTooLarge", Contact("friction_coefficient = 0.05\nfriction_speed = 5\n"),
      "friction_speed", p + R"(friction_speed: must be at most 1 m/s)");
  add("ContactArcsWithInvolute", Contact("arcs = 3\n"), "arcs",
      p + R"(arcs: only used by profile = "biarc")");
  add("ContactUnknownProfile", Contact("profile = \"biarcs\"\n"), "biarcs",
      p + R"(profile: unknown value 'biarcs' \(did you mean 'biarc'\?\))");
  add("ContactTipCornerTooLarge", Contact("tip_corner_radius = 0.01\n"), "tip_corner_radius",
      p + R"(tip_corner_radius: must be below half the thinner tip thickness)");
  add("ContactZeroFaceSlices", Contact("face_slices = 0\n"), "face_slices",
      p + R"(face_slices: must be >= 1, got 0$)");
  return c;
}

class SceneReaderContactInputTest : public ::testing::TestWithParam<BadCase> {};

TEST_P(SceneReaderContactInputTest, ReportsFileLineKeyAndReason) {
  test::ExpectSceneError(GetParam());
}

INSTANTIATE_TEST_SUITE_P(Cases, SceneReaderContactInputTest, ::testing::ValuesIn(ContactCases()),
                         test::CaseName);

TEST(SceneReaderContactTest, CaseNamesAreUnique) { test::ExpectUniqueNames(ContactCases()); }

// Defaults: rigid teeth, Kim's law in SI (k = 39.3e6 N/mm^1.5 · 1000^1.5, c = 1.0 · 1000^1.25),
// frictionless, exact involutes, one face slice.
TEST(SceneReaderContactTest, DefaultsAreKimsLawInSi) {
  const Scene s = ParseScene(Mesh("model = \"contact\"\n"), test::kSource);
  const MeshModelDef& m = s.meshes.at(0).model;
  EXPECT_EQ(m.level, MeshModelLevel::kContact);
  EXPECT_FALSE(m.contact.has_value());
  const ContactMeshDef def;  // what BuildMeshCore takes without a table
  EXPECT_EQ(def.teeth, ToothBodyType::kRigid);
  EXPECT_EQ(def.law.kind, ContactLawKind::kKim);
  EXPECT_DOUBLE_EQ(def.law.stiffness, 39.3e6 * std::pow(1000.0, 1.5));
  EXPECT_DOUBLE_EQ(def.law.damping, std::pow(1000.0, 1.25));
  EXPECT_EQ(def.law.stiffness_exponent, 1.5);
  EXPECT_EQ(def.law.indentation_exponent, 0.25);
  EXPECT_EQ(def.friction_coefficient, 0.0);
  EXPECT_EQ(def.profile, ContactProfile::kInvolute);
  EXPECT_EQ(def.face_slices, 1);
}

TEST(SceneReaderContactTest, ReadsEveryKey) {
  const Scene s = ParseScene(Contact(R"(teeth = "bushing"
bending_stiffness = 11.5e3
bending_damping = 2e-4
bushing_radial_stiffness = 3e9
bushing_tangential_damping = 0.5
tooth_mass = 0.005
tooth_inertia = 2.9e-8
law = "line"
damping = 100.0
damping_exponent = 1.5
indentation_exponent = 0.5
young_modulus = 2.1e11
poisson = 0.29
friction_coefficient = 0.06
friction_speed = 0.02
profile = "biarc"
arcs = 3
tip_corner_radius = 2e-4
face_slices = 5
)"),
                             test::kSource);
  const ContactMeshDef& d = s.meshes.at(0).model.contact.value();
  EXPECT_EQ(d.teeth, ToothBodyType::kBushing);
  EXPECT_EQ(d.bending_stiffness, 11.5e3);
  EXPECT_EQ(d.bending_damping, 2e-4);
  EXPECT_EQ(d.bushing_radial_stiffness, 3e9);
  EXPECT_FALSE(d.bushing_tangential_stiffness.has_value());
  EXPECT_EQ(d.bushing_tangential_damping, 0.5);
  EXPECT_EQ(d.tooth_mass, 0.005);
  EXPECT_EQ(d.tooth_inertia, 2.9e-8);
  EXPECT_EQ(d.law.kind, ContactLawKind::kLine);
  EXPECT_EQ(d.law.damping, 100.0);
  EXPECT_EQ(d.law.damping_exponent, 1.5);
  EXPECT_EQ(d.law.indentation_exponent, 0.5);
  EXPECT_DOUBLE_EQ(d.law.contact_modulus, 2.1e11 / (2.0 * (1.0 - 0.29 * 0.29)));
  EXPECT_EQ(d.friction_coefficient, 0.06);
  EXPECT_EQ(d.friction_speed, 0.02);
  EXPECT_EQ(d.profile, ContactProfile::kBiarc);
  EXPECT_EQ(d.arcs, 3);
  EXPECT_EQ(d.tip_corner_radius, 2e-4);
  EXPECT_EQ(d.face_slices, 5);
  // Tooth set and bushing from the geometry: the given values win, the others are derived.
  const GearGeometry& g = s.meshes.at(0).geometry.pinion;
  const ToothSet set = ResolveToothSet(d, g);
  EXPECT_EQ(set.teeth, 20);
  EXPECT_EQ(set.inertia.mass, 0.005);
  const BushingJoint j = ResolveBushing(d, g);
  EXPECT_EQ(j.radial_stiffness, 3e9);
  const ToothSection sec = CalcToothSection(g);
  const double shear = 2.1e11 / (2.0 * 1.29);
  EXPECT_DOUBLE_EQ(j.tangential_stiffness,
                   5.0 / 6.0 * shear * sec.root_thickness * g.face_width / sec.height);
  EXPECT_DOUBLE_EQ(j.radial_damping, 2e-4 / 11.5e3 * 3e9);  // k·c_b/k_b
  EXPECT_EQ(j.tangential_damping, 0.5);
}

// The table is read with any model, so --set switches the level without editing the file.
TEST(SceneReaderContactTest, TableIsKeptWhenTheModelIsSwitched) {
  const std::string text =
      Contact("teeth = \"revolute\"\nbending_stiffness = 11.5e3\nbending_damping = 2e-4\n");
  const Scene s = ParseScene(text, test::kSource, {"mesh.pinion-wheel.model=slices"});
  EXPECT_EQ(s.meshes.at(0).model.level, MeshModelLevel::kNonlinearSlices);
  EXPECT_EQ(s.meshes.at(0).model.contact->teeth, ToothBodyType::kRevolute);
  const Scene t = ParseScene(kBase, test::kSource, {"mesh.pinion-wheel.model=contact"});
  EXPECT_EQ(t.meshes.at(0).model.level, MeshModelLevel::kContact);
}

// Analyses that need a linear operator name the mesh, the analysis and the way out.
TEST(SceneReaderContactTest, LinearAnalysesRefuseTheContactModel) {
  const Scene s = ParseScene(Mesh("model = \"contact\"\n"), test::kSource);
  SceneSystemOptions options;
  options.analysis = "modes";
  EXPECT_THROWS_MESSAGE(
      MakeSystemModel(s, options), InvalidInput,
      R"(^mesh\.pinion-wheel\.model: "contact" is the time-domain tooth-contact model \(geardyn )"
      R"(simulate\); modes needs a linear or slice mesh core: run it with --set )"
      R"(mesh\.pinion-wheel\.model=slices)");
  EXPECT_THROWS_MESSAGE(BuildMeshCore(s, s.meshes.at(0)), InvalidInput,
                        R"(^mesh\.pinion-wheel\.model: "contact".*--set mesh\.pinion-wheel\.)"
                        R"(model=slices)");
  // The way out works on the same scene.
  const Scene slices =
      ParseScene(Mesh("model = \"contact\"\n"), test::kSource, {"mesh.pinion-wheel.model=slices"});
  EXPECT_NO_THROW(MakeSystemModel(slices, options));
}

// Time-domain analyses get the tooth-contact core, placed in the mesh's frame (the built-in rig:
// 12 + 100 coordinates with revolute teeth); a gear too light for its teeth is refused.
TEST(SceneReaderContactTest, TimeDomainAnalysesGetTheContactCore) {
  const Scene s =
      LoadScene("builtin:kahraman-blankenship-rig",
                {"mesh.pinion-wheel.model=contact", "mesh.pinion-wheel.contact.teeth=\"revolute\"",
                 "mesh.pinion-wheel.contact.bending_stiffness=11.5e3"});
  SceneSystemOptions options;
  options.allow_contact_meshes = true;
  const SystemModel model = MakeSystemModel(s, options);
  const auto* core =
      std::get_if<std::shared_ptr<const NonlinearMeshCore>>(&model.meshes().at(0).core);
  ASSERT_NE(core, nullptr);
  EXPECT_EQ((*core)->num_coordinates(), 112);
  EXPECT_EQ((*core)->num_internal_coordinates(), 100);
  const Scene light =
      LoadScene("builtin:kahraman-blankenship-rig",
                {"mesh.pinion-wheel.model=contact", "mesh.pinion-wheel.contact.teeth=\"revolute\"",
                 "mesh.pinion-wheel.contact.bending_stiffness=11.5e3", "gear.wheel.inertia=1e-3"});
  EXPECT_THROWS_MESSAGE(
      MakeSystemModel(light, options), InvalidInput,
      R"(^mesh\.pinion-wheel\.contact: gear\.wheel\.inertia: 0\.001 kg m\^2 must )"
      R"(exceed the 50 teeth's own)");
}

}  // namespace
}  // namespace geardyn
