// A rack in the scene format (issue 19): examples/rack/rack-and-pinion.toml read, placed and
// assembled, against independent truths — the closed-form torsional–translational frequency of
// the pinion's rotation and the rack's travel with the scene's own mean mesh stiffness, the static
// balance of the operating torque and the rack's load through the mesh (F_η = T / r_b1), and the
// pinion's pitch-line speed — and its bad inputs, each refused at the key that is wrong.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "geardyn/analyses/modal.hpp"
#include "geardyn/models/scene/scene_reader.hpp"
#include "geardyn/models/system/scene_system.hpp"
#include "geardyn/system/probes.hpp"
#include "geardyn/system/static_deflection.hpp"
#include "support/scene_text.hpp"

namespace geardyn {
namespace {

const std::string kExample = GEARDYN_SOURCE_DIR "/examples/rack/rack-and-pinion.toml";

std::string ExampleText() {
  std::ifstream in(kExample);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(RackSceneTest, ExampleIsAPinionOnARackBelowIt) {
  const Scene scene = LoadScene(kExample);
  ASSERT_EQ(scene.meshes.size(), 1u);
  const GearPairGeometry& g = scene.meshes[0].geometry;
  ASSERT_TRUE(g.rack);
  const SceneSystem built = BuildSceneSystem(scene);
  // The rack's reference point is the pitch point, r_1 below the pinion's axis.
  EXPECT_NEAR(
      (built.centres[1] - built.centres[0] - Vector3(0, -g.pinion.reference_radius, 0)).norm(), 0.0,
      1e-15);
  // The mesh frequency is the pinion's: z_1 Ω / 2π.
  EXPECT_NEAR(scene.MeshFrequencyHz(scene.meshes[0]), 20 * 300.0 / 60.0, 1e-9);
}

// Pinion θz (inertia J) and rack x (mass m) alone: ω² = K̄ (r_b1²/J + cos²α_t/m), K̄ the mean
// mesh stiffness the scene assembled (spur: cos β_b = 1).
TEST(RackSceneTest, TorsionalTranslationalModeIsTheClosedForm) {
  const Scene scene = LoadScene(kExample);
  const SystemModel model = BuildSceneSystem(scene).model;
  const SystemModel pair = model.Restrict({5, 6});  // pinion θz, rack x
  const ModalResult modes = ComputeModes(pair);
  ASSERT_TRUE(modes.summary.ok()) << modes.summary.BriefReport();
  ASSERT_EQ(modes.num_rigid_body_modes, 1);
  const GearPairGeometry& g = scene.meshes[0].geometry;
  const double K = model.meshes()[0].mean_core_stiffness(0, 0);
  const double rb = g.pinion.base_radius, ca = std::cos(g.operating_pressure_angle);
  const double closed =
      std::sqrt(K * (rb * rb / *scene.gears[0].inertia + ca * ca / *scene.gears[1].mass)) /
      (2.0 * std::numbers::pi);
  EXPECT_NEAR(modes.frequencies_hz(1), closed, 1e-9 * closed);
}

// The operating torque T on the pinion and the load −T/r_1 on the rack balance through the
// mesh: the static mesh force is T / r_b1 (the line of action's lever arm about the pinion).
TEST(RackSceneTest, StaticMeshForceBalancesTheTorqueAndTheRackLoad) {
  const Scene scene = LoadScene(kExample);
  const SystemModel model = BuildSceneSystem(scene).model;
  const StaticDeflectionResult st = SolveStaticDeflection(model);
  ASSERT_TRUE(st.summary.ok()) << st.summary.BriefReport();
  const Vector2 delta = CalcMeshDeflection(model, MeshIndex(0), st.deflection);
  const double force = model.meshes()[0].mean_core_stiffness(0, 0) * delta(0);
  const double rb = scene.meshes[0].geometry.pinion.base_radius;
  EXPECT_NEAR(force, scene.operating_point.torque / rb, 1e-6 * force);
}

struct BadRack {
  std::string name, from, to, key, reason;
};

TEST(RackSceneTest, BadRackInputIsRefusedAtItsKey) {
  const std::string text = ExampleText();
  const std::vector<BadRack> cases = {
      {"RackAsPinion", "pinion = \"pinion\"\ngear = \"rack\"",
       "pinion = \"rack\"\ngear = \"pinion\"", "mesh.rack-pinion.pinion", "is a rack"},
      {"RackWithTeeth", "rack = true\n", "rack = true\nteeth = 50\n", "gear.rack.teeth",
       "not used"},
      {"RackAndInternal", "rack = true\n", "rack = true\ninternal = true\n", "gear.rack.rack",
       "internal"},
      {"TorqueOnRack", "force = -1000.0", "torque = 5.0", "load.actuator-load.torque",
       "force along its direction"},
      {"OperatingPointOnRack", "body = \"pinion\"\nspeed_rpm", "body = \"rack\"\nspeed_rpm",
       "operating_point.body", "is a rack"},
      {"TorsionalOnRack", "damping_ratio = 0.05", "damping_ratio = 0.05\nmodel = \"torsional\"",
       "mesh.pinion-rack.model", "not available on a rack"},
      {"RunoutOnRack", "damping_ratio = 0.05",
       "damping_ratio = 0.05\nerrors = { gear_runout = 5e-6 }", "gear_runout", "is a rack"},
      {"ShiftOnRack", "rack = true\n", "rack = true\nprofile_shift = 0.1\n", "mesh.pinion-rack",
       "gear.profile_shift"},
  };
  for (const BadRack& c : cases) {
    const std::string scene = test::Replace(text, c.from, c.to);
    try {
      (void)ParseScene(scene, "rack.toml");
      ADD_FAILURE() << c.name << ": accepted";
    } catch (const SceneError& e) {
      EXPECT_NE(e.key().find(c.key), std::string::npos) << c.name << ": " << e.what();
      EXPECT_NE(std::string(e.what()).find(c.reason), std::string::npos)
          << c.name << ": " << e.what();
    }
  }
  // A force on a gear (not a rack).
  const std::string on_gear =
      test::Replace(test::Replace(text, "body = \"rack\"\nforce", "body = \"pinion\"\nforce"),
                    "name = \"actuator-load\"", "name = \"actuator-load\"");
  EXPECT_THROW((void)ParseScene(on_gear, "rack.toml"), SceneError);
}

}  // namespace
}  // namespace geardyn
