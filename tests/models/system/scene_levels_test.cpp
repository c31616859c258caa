// Tests of the model levels "bs_projected" (B–S's projected-arm mesh Jacobian) and "five_dof"
// (B–S §5.3, scalar transmission error) on assembled scenes, each against an independent truth:
// the exact G and the closed-form θ_u arm terms of mesh_jacobian.hpp, the theory P T = G for a
// spur pair, the rigid motions derived there, and the unmodified B–S level's channels.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <string>
#include <variant>
#include <vector>

#include "geardyn/common/units.hpp"
#include "geardyn/models/mesh/mesh_frame.hpp"
#include "geardyn/models/mesh/mesh_jacobian.hpp"
#include "geardyn/models/mesh/stiffness_core.hpp"
#include "geardyn/models/scene/mesh_model.hpp"
#include "geardyn/models/scene/scene.hpp"
#include "geardyn/models/scene/scene_reader.hpp"
#include "geardyn/models/system/scene_system.hpp"
#include "geardyn/system/workspace.hpp"
#include "support/matrix_compare.hpp"

namespace geardyn {
namespace {

constexpr double kEps = 2.220446049250313e-16;
// G's entries: cross products of O(0.1 m) arms with unit vectors, a few roundings each.
constexpr double kJacobianTol = 1e3 * kEps;
// Assembled stiffness and eigenvalues: sums over 12×12 products, relative.
constexpr double kAssemblyTol = 1e-12;

const std::vector<double> kThetas = {0.0, 0.37, 1.1, 2.5, 3.9, 5.6};

Scene Load(const std::string& builtin, const std::string& level,
           std::vector<std::string> overrides = {}) {
  Scene probe = LoadScene(builtin);
  for (const MeshDef& m : probe.meshes) overrides.push_back("mesh." + m.name + ".model=" + level);
  return LoadScene(builtin, overrides);
}

VectorX MeanEigenvalues(const SystemModel& model) {
  SystemWorkspace ws(model, StorageKind::kDense);
  const MatrixX K = AssembleMeanStiffness(model, ws);
  Eigen::GeneralizedSelfAdjointEigenSolver<MatrixX> eig(K, model.DenseMass(),
                                                        Eigen::EigenvaluesOnly);
  VectorX values = eig.eigenvalues();
  std::sort(values.data(), values.data() + values.size());
  return values;
}

MatrixX MeanStiffness(const SystemModel& model) {
  SystemWorkspace ws(model, StorageKind::kDense);
  return AssembleMeanStiffness(model, ws);
}

int GearIndex(const Scene& scene, const std::string& name) {
  for (std::size_t g = 0; g < scene.gears.size(); ++g) {
    if (scene.gears[g].name == name) return static_cast<int>(g);
  }
  return -1;
}

// The mesh frame of scene mesh k, rebuilt from what BuildSceneSystem reports.
MeshFrame FrameOf(const Scene& scene, const SceneSystem& built, int k) {
  const MeshDef& m = scene.meshes[static_cast<std::size_t>(k)];
  return CalcMeshFrame(m.geometry,
                       built.centres[static_cast<std::size_t>(GearIndex(scene, m.pinion))],
                       built.mesh_angles[static_cast<std::size_t>(k)],
                       built.drive_signs[static_cast<std::size_t>(k)]);
}

const LinearMeshCore& Linear(const MeshCore& core) { return std::get<LinearMeshCore>(core); }

// --- bs_projected ---------------------------------------------------------------------------

// Spur pair with p0 in the centres' plane: B–S's projected arms are the exact arms (P T = G,
// mesh_jacobian.hpp), so G, K̄ and the modes are those of "blankenship_singh".
TEST(SceneLevelsTest, BsProjectedEqualsBlankenshipSinghOnASpurPair) {
  const std::string rig = "builtin:kahraman-blankenship-rig";
  const Scene bs_scene = Load(rig, "blankenship_singh");
  const Scene pr_scene = Load(rig, "bs_projected");
  ASSERT_EQ(pr_scene.meshes[0].model.level, MeshModelLevel::kBsProjected);
  const SceneSystem bs = BuildSceneSystem(bs_scene);
  const SceneSystem pr = BuildSceneSystem(pr_scene);
  ASSERT_EQ(bs.model.num_meshes(), pr.model.num_meshes());
  for (int k = 0; k < bs.model.num_meshes(); ++k) {
    const SystemMesh& a = bs.model.meshes()[static_cast<std::size_t>(k)];
    const SystemMesh& b = pr.model.meshes()[static_cast<std::size_t>(k)];
    const MeshFrame f = FrameOf(bs_scene, bs, k);
    ASSERT_EQ(f.base_helix_angle, 0.0);
    const double scale = a.G.cwiseAbs().maxCoeff();
    EXPECT_MATRIX_NEAR(a.G, CalcMeshJacobian(f), kJacobianTol * scale);
    EXPECT_MATRIX_NEAR(b.G, a.G, kJacobianTol * scale) << a.name;
    EXPECT_MATRIX_NEAR(b.mean_core_stiffness, a.mean_core_stiffness, 0.0);
  }
  const MatrixX Ka = MeanStiffness(bs.model);
  EXPECT_MATRIX_NEAR(MeanStiffness(pr.model), Ka, kAssemblyTol * Ka.cwiseAbs().maxCoeff());
  const VectorX la = MeanEigenvalues(bs.model);
  const VectorX lb = MeanEigenvalues(pr.model);
  ASSERT_EQ(la.size(), lb.size());
  for (Eigen::Index i = 0; i < la.size(); ++i) {
    EXPECT_NEAR(lb[i], la[i], kAssemblyTol * la.cwiseAbs().maxCoeff()) << "mode " << i;
  }
}

// Helical pair: G_BS = G minus the θ_u arm terms (closed form from the frame's vectors); the
// core is B–S's, K_mesh = G_BSᵀ K2 G_BS symmetric PSD of rank ≤ 2, and it loads no common
// translation, no conjugate rotation and no common rotation about Z or v — but a common tilt about
// u (the moment error of the projected arms).
TEST(SceneLevelsTest, BsProjectedOnAHelicalPairDropsTheThetaUArmTerms) {
  const Scene bs_scene = Load("builtin:helical-pair", "blankenship_singh");
  const Scene pr_scene = Load("builtin:helical-pair", "bs_projected");
  const SceneSystem bs = BuildSceneSystem(bs_scene);
  const SceneSystem pr = BuildSceneSystem(pr_scene);
  const SystemMesh& mesh = pr.model.meshes()[0];
  const MeshFrame f = FrameOf(pr_scene, pr, 0);
  ASSERT_GT(f.base_helix_angle, 0.0);
  const Matrix2x12 G = CalcMeshJacobian(f);
  const double scale = G.cwiseAbs().maxCoeff();
  EXPECT_MATRIX_NEAR(bs.model.meshes()[0].G, G, kJacobianTol * scale);

  // G − G_BS: row 0 = s (sin ψ r·v − cos ψ r·w) uᵀ on θ_i, minus the same with r_j on θ_j.
  const double s = f.drive_sign;
  const double sin_psi = std::sin(f.signed_helix_angle);
  const double cos_psi = std::cos(f.signed_helix_angle);
  const auto arm = [&](const Vector3& r) { return sin_psi * r.dot(f.v) - cos_psi * r.dot(f.w); };
  Matrix2x12 difference = Matrix2x12::Zero();
  difference.block<1, 3>(0, 3) = s * arm(f.pinion_lever_arm) * f.u.transpose();
  difference.block<1, 3>(0, 9) = -s * arm(f.gear_lever_arm) * f.u.transpose();
  EXPECT_MATRIX_NEAR(G - mesh.G, difference, kJacobianTol * scale);
  EXPECT_GT(difference.norm(), 1e-3 * G.norm());  // first order, not round-off

  // Same core as blankenship_singh (channels, b, damping, ε).
  const LinearMeshCore& core = Linear(mesh.core);
  const LinearMeshCore& ref = Linear(bs.model.meshes()[0].core);
  EXPECT_EQ(core.level(), MeshCoreLevel::kBlankenshipSingh);
  EXPECT_EQ(core.half_face_width(), ref.half_face_width());
  for (const double th : kThetas) {
    EXPECT_MATRIX_NEAR(EvalStiffnessCore(core, th), EvalStiffnessCore(ref, th), 0.0);
  }

  // Rigid motions (pinion body first, then the wheel's, both 6 DOF of this 12-DOF model).
  const Vector3 ci = f.pinion_center, cj = f.gear_center;
  const auto rotation = [&](const Vector3& omega, const Vector3& point) {
    Vector12 q;
    q << omega.cross(ci - point), omega, omega.cross(cj - point), omega;
    return q;
  };
  Vector12 translation;
  translation << 0.3, -0.7, 0.2, 0, 0, 0, 0.3, -0.7, 0.2, 0, 0, 0;
  Vector12 conjugate = Vector12::Zero();
  conjugate(5) = 1.0 / f.pinion_base_radius;
  conjugate(11) = -1.0 / f.gear_base_radius;
  const Vector3 far_point(0.4, 0.9, -0.6);
  const std::vector<Vector12> unloaded = {
      translation, conjugate, rotation(Vector3::UnitZ(), far_point),
      rotation(Vector3::UnitZ(), f.reference_point), rotation(f.v, far_point)};
  for (const double th : kThetas) {
    const Matrix12 K = CalcMeshStiffness(mesh.G, EvalStiffnessCore(core, th));
    const double k_scale = K.cwiseAbs().maxCoeff();
    EXPECT_MATRIX_NEAR(K, K.transpose(), 0.0);
    Eigen::SelfAdjointEigenSolver<Matrix12> eig(K);
    const VectorX lambda = eig.eigenvalues();
    EXPECT_GE(lambda.minCoeff(), -kAssemblyTol * k_scale);
    EXPECT_LE((lambda.array() > kAssemblyTol * k_scale).count(), 2) << "theta " << th;
    for (std::size_t n = 0; n < unloaded.size(); ++n) {
      EXPECT_LE((K * unloaded[n]).norm(), kAssemblyTol * k_scale * unloaded[n].norm() * 10.0)
          << "motion " << n << ", theta " << th;
    }
    // A common tilt about u: δ_η = −s (sin ψ C·v − cos ψ C·w), C = c_j − c_i.
    const Vector12 tilt = rotation(f.u, far_point);
    const double delta_eta = -s * arm(cj - ci);
    EXPECT_NEAR((mesh.G * tilt)(0), delta_eta, kJacobianTol * scale * tilt.norm());
    EXPECT_NEAR((mesh.G * tilt)(1), 0.0, kJacobianTol * scale * tilt.norm());
    EXPECT_GT(std::abs(delta_eta), 1e-3 * (cj - ci).norm());
  }
}

// --- five_dof -------------------------------------------------------------------------------

// Without modifications or errors ε ≡ 0 for both levels: five_dof is blankenship_singh.
TEST(SceneLevelsTest, FiveDofEqualsBlankenshipSinghWithoutTransmissionError) {
  const Scene bs_scene = Load("builtin:helical-pair", "blankenship_singh");
  const Scene fd_scene = Load("builtin:helical-pair", "five_dof");
  ASSERT_EQ(fd_scene.meshes[0].model.level, MeshModelLevel::kFiveDof);
  const SceneSystem bs = BuildSceneSystem(bs_scene);
  const SceneSystem fd = BuildSceneSystem(fd_scene);
  const SystemMesh& a = bs.model.meshes()[0];
  const SystemMesh& b = fd.model.meshes()[0];
  EXPECT_MATRIX_NEAR(b.G, a.G, 0.0);
  const LinearMeshCore& ca = Linear(a.core);
  const LinearMeshCore& cb = Linear(b.core);
  EXPECT_EQ(cb.level(), MeshCoreLevel::kBlankenshipSingh);
  EXPECT_FALSE(ca.has_transmission_error());
  EXPECT_FALSE(cb.has_transmission_error());
  VectorX xa(3), xb(3);
  for (const double th : kThetas) {
    Evaluate(ca.stiffness(), th, xa);
    Evaluate(cb.stiffness(), th, xb);
    EXPECT_MATRIX_NEAR(xb, xa, 0.0);
  }
  const VectorX la = MeanEigenvalues(bs.model);
  EXPECT_MATRIX_NEAR(MeanEigenvalues(fd.model), la, kAssemblyTol * la.cwiseAbs().maxCoeff());
  EXPECT_MATRIX_NEAR(fd.model.constant_load(), bs.model.constant_load(), 0.0);
}

// A helical tip relief makes ε_ζ ≠ 0 (the relieved lines are inclined across the face):
// five_dof keeps the same ε_η channel and drops ε_ζ (B–S Eq. 42).
TEST(SceneLevelsTest, FiveDofKeepsOnlyTheLineOfActionErrorOfAHelicalTipRelief) {
  const std::vector<std::string> relief = {
      "mesh.pinion-wheel.modifications.pinion_tip_relief=20e-6",
      "mesh.pinion-wheel.modifications.pinion_tip_relief_length=2e-3"};
  const Scene bs_scene = Load("builtin:helical-pair", "blankenship_singh", relief);
  const Scene fd_scene = Load("builtin:helical-pair", "five_dof", relief);
  const SceneSystem bs = BuildSceneSystem(bs_scene);
  const SceneSystem fd = BuildSceneSystem(fd_scene);
  const LinearMeshCore& ca = Linear(bs.model.meshes()[0].core);
  const LinearMeshCore& cb = Linear(fd.model.meshes()[0].core);
  ASSERT_TRUE(ca.transmission_error().has_value());
  ASSERT_TRUE(cb.transmission_error().has_value());
  double max_eta = 0.0, max_zeta = 0.0;
  for (int i = 0; i < 64; ++i) {
    const double th = 2.0 * kPi * i / 64.0;
    const Vector2 ea = EvalTransmissionError(ca, th);
    const Vector2 eb = EvalTransmissionError(cb, th);
    EXPECT_EQ(eb[0], ea[0]) << "theta " << th;
    EXPECT_EQ(eb[1], 0.0) << "theta " << th;
    max_eta = std::max(max_eta, std::abs(ea[0]));
    max_zeta = std::max(max_zeta, std::abs(ea[1]));
    // The mesh load of five_dof is Gᵀ K2 [ε_η, 0]ᵀ.
    const Matrix2 K2 = EvalStiffnessCore(ca, th);
    EXPECT_MATRIX_NEAR(EvalTransmissionErrorLoad(cb, th), K2 * Vector2(ea[0], 0.0),
                       kAssemblyTol * (K2 * Vector2(ea[0], 0.0)).norm());
  }
  EXPECT_GT(max_eta, 1e-7);  // a few µm of relief reach the line of action
  // ε_ζ of the B–S level: a rotation of the order of ε_η / face width (3.5e-4 rad here, where
  // one relieved line carries a small share), far above round-off.
  EXPECT_GT(max_zeta, 0.1 * max_eta / bs_scene.meshes[0].geometry.face_width);
  // Stiffness (and hence the modes) untouched.
  const VectorX la = MeanEigenvalues(bs.model);
  EXPECT_MATRIX_NEAR(MeanEigenvalues(fd.model), la, kAssemblyTol * la.cwiseAbs().maxCoeff());
}

}  // namespace
}  // namespace geardyn
