#include "geardyn/models/system/scene_system.hpp"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

#include "geardyn/common/errors.hpp"
#include "geardyn/models/scene/scene_reader.hpp"
#include "geardyn/system/static_deflection.hpp"
#include "geardyn/system/workspace.hpp"
#include "support/expect_throws.hpp"

namespace geardyn {
namespace {

VectorX MeanEigenvalues(const SystemModel& model) {
  SystemWorkspace ws(model, StorageKind::kDense);
  const MatrixX K = AssembleMeanStiffness(model, ws);
  Eigen::GeneralizedSelfAdjointEigenSolver<MatrixX> eig(K, model.DenseMass(),
                                                        Eigen::EigenvaluesOnly);
  VectorX values = eig.eigenvalues();
  std::sort(values.data(), values.data() + values.size());
  return values;
}

Scene HelicalPair() { return LoadScene("builtin:helical-pair"); }

TEST(SceneSystemTest, BuildsBodiesBearingsMeshAndLoads) {
  const Scene scene = HelicalPair();
  const SceneSystem built = BuildSceneSystem(scene);
  const SystemModel& model = built.model;
  EXPECT_EQ(model.num_dofs(), 12);
  EXPECT_EQ(model.dof_map().dof_name(11), "wheel.θz");
  ASSERT_EQ(model.num_meshes(), 1);
  EXPECT_EQ(model.elements().size(), 4u);
  // Placement: pinion at the origin, wheel at a_w along +X (γ0 = 0).
  EXPECT_TRUE(built.centres[0].isZero());
  EXPECT_NEAR(built.centres[1].x(), scene.meshes[0].geometry.center_distance, 1e-15);
  EXPECT_NEAR(built.centres[1].y(), 0.0, 1e-15);
  EXPECT_EQ(built.drive_signs[0], 1);
  // Loads add: +150 N·m on the pinion, +366 N·m on the wheel.
  EXPECT_DOUBLE_EQ(model.constant_load()(5), 150.0);
  EXPECT_DOUBLE_EQ(model.constant_load()(11), 366.0);
  // Mass: diag(m, m, m, I_d, I_d, J).
  const MatrixX M = model.DenseMass();
  EXPECT_DOUBLE_EQ(M(0, 0), *scene.gears[0].mass);
  EXPECT_DOUBLE_EQ(M(3, 3), *scene.gears[0].transverse_inertia);
  EXPECT_DOUBLE_EQ(M(5, 5), *scene.gears[0].inertia);
  EXPECT_NE(model.time_dependence(), TimeDependence::kConstant);
}

TEST(SceneSystemTest, MissingTransverseInertiaIsHalfThePolarInertia) {
  Scene scene = HelicalPair();
  scene.gears[1].transverse_inertia.reset();
  const SystemModel model = MakeSystemModel(scene);
  EXPECT_DOUBLE_EQ(model.DenseMass()(9, 9), 0.5 * *scene.gears[1].inertia);
}

// spec 01 §6: a rigid re-placement of the whole scene leaves the eigenvalues unchanged.
TEST(SceneSystemTest, RigidReplacementLeavesEigenvaluesUnchanged) {
  const Scene scene = HelicalPair();
  const VectorX reference = MeanEigenvalues(MakeSystemModel(scene));
  for (double gamma : {0.7, M_PI / 2, -2.1}) {
    SceneSystemOptions options;
    options.line_of_centres_angle = gamma;
    options.origin = Vector3(0.3, -1.2, 0.05);
    const VectorX moved = MeanEigenvalues(MakeSystemModel(scene, options));
    for (int i = 0; i < reference.size(); ++i) {
      EXPECT_NEAR(moved(i), reference(i), 1e-9 * reference.cwiseAbs().maxCoeff())
          << "γ = " << gamma << ", i = " << i;
    }
  }
}

TEST(SceneSystemTest, StaticDeflectionKeepsTheContactClosed) {
  const Scene scene = HelicalPair();
  const StaticDeflectionResult r = SolveStaticDeflection(MakeSystemModel(scene));
  ASSERT_EQ(r.meshes.size(), 1u);
  EXPECT_GT(r.meshes[0].delta_eta, 0.0);
  EXPECT_FALSE(r.meshes[0].contact_open);
  EXPECT_EQ(r.num_rigid_modes, 1);
  // The pinion's torque balance: F_η r_b1 cos ψ_b ... checked through the mesh force being the
  // transmitted tangential load F_t / cos β_b (normal force) within the ε load's contribution.
  const double r_b1 = scene.meshes[0].geometry.pinion.base_radius;
  const double beta_b = scene.meshes[0].geometry.base_helix_angle;
  EXPECT_NEAR(r.meshes[0].force_eta, 150.0 / (r_b1 * std::cos(beta_b)), 1e-6 * 150.0 / r_b1);
  EXPECT_LE(r.unbalanced_load, 1e-6 * 150.0);
}

TEST(SceneSystemTest, PlanarOptionKeepsXYAndThetaZ) {
  SceneSystemOptions options;
  options.planar = true;
  const SystemModel model = MakeSystemModel(HelicalPair(), options);
  EXPECT_EQ(model.num_dofs(), 6);
  for (int i = 0; i < model.num_dofs(); ++i) {
    const BodyDof c = model.dof_map().dof_component(i);
    EXPECT_TRUE(c == BodyDof::kX || c == BodyDof::kY || c == BodyDof::kThetaZ);
  }
}

TEST(SceneSystemTest, TorsionalLevelMatchesClosedForm) {
  Scene scene = HelicalPair();
  scene.meshes[0].model.level = MeshModelLevel::kTorsional;
  const SystemModel model = MakeSystemModel(scene);
  // Only θz enters G: the torsional 2-DOF block is exact.
  std::vector<int> torsional = {model.dof_map().dof(BodyIndex(0), BodyDof::kThetaZ),
                                model.dof_map().dof(BodyIndex(1), BodyDof::kThetaZ)};
  bool found = false;
  for (const std::vector<int>& block : model.blocks()) found = found || block == torsional;
  ASSERT_TRUE(found);
  const SystemModel pair = model.Restrict(torsional);
  const double k = pair.meshes()[0].mean_core_stiffness(0, 0);
  const double rb1 = scene.meshes[0].geometry.pinion.base_radius;
  const double rb2 = scene.meshes[0].geometry.gear.base_radius;
  const VectorX values = MeanEigenvalues(pair);
  // The torsional core acts on the helical normal: G's θz entries are r_b cos ψ_b.
  const double g1 = std::abs(pair.meshes()[0].G(0, 5));
  const double g2 = std::abs(pair.meshes()[0].G(0, 11));
  EXPECT_NEAR(values(1),
              k * (g1 * g1 / *scene.gears[0].inertia + g2 * g2 / *scene.gears[1].inertia),
              1e-10 * values(1));
  const double cb = std::cos(scene.meshes[0].geometry.base_helix_angle);
  EXPECT_NEAR(g1, rb1 * cb, 1e-12);
  EXPECT_NEAR(g2, rb2 * cb, 1e-12);
  EXPECT_NEAR(values(0), 0.0, 1e-9 * values(1));
}

TEST(SceneSystemTest, RejectsBadOptions) {
  SceneSystemOptions options;
  options.mesh_angles["nope"] = 0.0;
  EXPECT_THROWS_MESSAGE(MakeSystemModel(HelicalPair(), options), InvalidInput,
                        "mesh_angles.nope: no mesh");
  options.mesh_angles.clear();
  options.line_of_centres_angle = NAN;
  EXPECT_THROWS_MESSAGE(MakeSystemModel(HelicalPair(), options), InvalidInput,
                        "line_of_centres_angle");
}

}  // namespace
}  // namespace geardyn
