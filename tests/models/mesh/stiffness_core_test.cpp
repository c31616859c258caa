// Tests of the linear (B–S) mesh algebra (spec 01 §3, §5, §6): the invariants of K_mesh over
// every scene and model level, the energy that defines K2 and ε, B–S's K_o (Eq. 41b) and its
// transmission error (Eq. 42), damping (Eq. 39), the torsional SDOF reduction and bad input.
#include "geardyn/models/mesh/stiffness_core.hpp"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <cmath>
#include <limits>
#include <string>
#include <tuple>
#include <vector>

#include "geardyn/common/errors.hpp"
#include "geardyn/common/units.hpp"
#include "geardyn/models/mesh/mesh_frame.hpp"
#include "geardyn/models/mesh/mesh_jacobian.hpp"
#include "support/expect_throws.hpp"
#include "support/matrix_compare.hpp"
#include "support/mesh_scenes.hpp"

namespace geardyn {
namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();
// 12×12 products of O(0.1 m) geometry with K ≈ 1e8 N/m: a few roundings per entry, relative to
// the largest entry.
constexpr double kAlgebraTol = 1e3 * kEps;
// Eigenvalues below this fraction of the largest are zero to rounding; the smallest physical one
// here is K (μ − κ²) b² ≈ 1e-5 K, far above it.
constexpr double kRankTol = 1e-10;

// Mesh data shared by all levels: K [N/m], h [m], μ [-], b [m]. μ = κ² + F²/(12 b²) for one
// uniformly loaded line of length F = 1.6 b centred at h (spec 01 §3).
struct CoreData {
  double K = 3.7e8;
  double h = 0.003;
  double mu = 0.0625 + 1.6 * 1.6 / 12.0;
  double b = 0.012;
};

// ---------------------------------------------------------------------------------------------
// Scenes: the shared mesh scenes (support/mesh_scenes.hpp).
using Scene = test::MeshScene;

std::vector<Scene> SpurScenes() {
  std::vector<Scene> spur;
  for (const Scene& scene : test::AllMeshScenes()) {
    if (scene.placement.base_helix_angle == 0.0) spur.push_back(scene);
  }
  return spur;
}

std::vector<Scene> HelicalScenes() {
  std::vector<Scene> helical;
  for (const Scene& scene : test::AllMeshScenes()) {
    if (scene.placement.base_helix_angle != 0.0) helical.push_back(scene);
  }
  return helical;
}

HelixHand OtherHand(HelixHand hand) {
  return hand == HelixHand::kRight
             ? HelixHand::kLeft
             : (hand == HelixHand::kLeft ? HelixHand::kRight : HelixHand::kNone);
}

// K_mesh of a level: the level's core on the level's view of the same G.
Matrix12 LevelStiffness(MeshCoreLevel level, const MeshFrame& f, const CoreData& d) {
  const Matrix2x12 G = CalcLevelJacobian(level, CalcMeshJacobian(f));
  return CalcMeshStiffness(G, CalcLevelCore(level, d.K, d.h, d.mu, d.b));
}

int ExpectedRank(MeshCoreLevel level) { return level == MeshCoreLevel::kBlankenshipSingh ? 2 : 1; }

// 12×12 block-diagonal change of coordinates with `A` on translations and `B` on rotations.
Matrix12 BlockTransform(const Matrix3& A, const Matrix3& B) {
  Matrix12 T = Matrix12::Zero();
  T.block<3, 3>(0, 0) = A;
  T.block<3, 3>(3, 3) = B;
  T.block<3, 3>(6, 6) = A;
  T.block<3, 3>(9, 9) = B;
  return T;
}

Eigen::Matrix<double, 12, 1> Eigenvalues(const Matrix12& K) {
  return Eigen::SelfAdjointEigenSolver<Matrix12>(K, Eigen::EigenvaluesOnly).eigenvalues();
}

// Relative residual ‖K q‖ / (‖K‖ ‖q‖).
double RelativeResidual(const Matrix12& K, const Vector12& q) {
  return (K * q).norm() / (K.norm() * q.norm());
}

Vector12 CommonRotation(const MeshFrame& f, const Vector3& omega, const Vector3& p) {
  Vector12 q;
  q << omega.cross(f.pinion_center - p), omega, omega.cross(f.gear_center - p), omega;
  return q;
}

// A pinion rotation that gives δ = [1 m, 0]: the unit normal approach (ζ ⟂ Z so no twist).
Vector12 UnitApproach(const Matrix2x12& G) {
  Vector12 q = Vector12::Zero();
  q(5) = 1.0 / G(0, 5);
  return q;
}

using SceneLevel = std::tuple<Scene, MeshCoreLevel>;

std::string SceneLevelName(const ::testing::TestParamInfo<SceneLevel>& param_info) {
  return std::get<0>(param_info.param).name + "_" + ToString(std::get<1>(param_info.param));
}

class MeshStiffnessInvariantTest : public ::testing::TestWithParam<SceneLevel> {
 protected:
  const MeshPlacement& placement() const { return std::get<0>(GetParam()).placement; }
  MeshCoreLevel level() const { return std::get<1>(GetParam()); }
  CoreData data_;
};

TEST_P(MeshStiffnessInvariantTest, IsSymmetricPsdWithTheLevelsRank) {
  const Matrix12 K = LevelStiffness(level(), CalcMeshFrame(placement()), data_);
  EXPECT_TRUE(K.isApprox(K.transpose(), 0.0));  // exactly symmetric by construction
  const Eigen::Matrix<double, 12, 1> lambda = Eigenvalues(K);
  const double lambda_max = lambda.maxCoeff();
  EXPECT_GT(lambda_max, 0.0);
  EXPECT_GE(lambda.minCoeff(), -kRankTol * lambda_max);
  const int rank = static_cast<int>((lambda.array() > kRankTol * lambda_max).count());
  EXPECT_EQ(rank, ExpectedRank(level()));
}

TEST_P(MeshStiffnessInvariantTest, RigidAndConjugateMotionsProduceNoForce) {
  const MeshFrame f = CalcMeshFrame(placement());
  const Matrix12 K = LevelStiffness(level(), f, data_);
  std::vector<Vector12> motions;
  // Common translation and tilts of the pair, when the level has those DOFs.
  Vector12 q = Vector12::Zero();
  q << 0.3, -0.7, 0.2, 0.0, 0.0, 0.0, 0.3, -0.7, 0.2, 0.0, 0.0, 0.0;
  motions.push_back(q);
  if (level() != MeshCoreLevel::kTorsional) {
    // Common rotation about any axis through any point (the torsional level has no
    // translations, so only rotations that need none belong to it).
    for (const Vector3& omega : {Vector3(0.0, 0.0, 1.0), Vector3(1.0, 0.0, 0.0),
                                 Vector3(0.3, -0.5, 0.8), Vector3(f.u), Vector3(f.v)}) {
      for (const Vector3& point :
           {Vector3(f.pinion_center), Vector3(f.reference_point), Vector3(0.4, 0.9, -0.6)}) {
        motions.push_back(CommonRotation(f, omega, point));
      }
    }
  } else {
    q.setZero();
    q << 0.0, 0.0, 0.0, 0.2, -0.4, 0.0, 0.0, 0.0, 0.0, 0.7, 0.1, 0.0;  // tilts only
    motions.push_back(q);
  }
  // Conjugate rotation: a_i θ_iz = −a_j θ_jz (external), a_i θ_iz = +a_j θ_jz (internal).
  q.setZero();
  q(5) = 1.0 / placement().pinion_base_radius;
  q(11) = (placement().internal ? 1.0 : -1.0) / placement().gear_base_radius;
  motions.push_back(q);
  for (const Vector12& motion : motions) {
    EXPECT_LE(RelativeResidual(K, motion), kAlgebraTol) << "q = " << motion.transpose();
  }
}

TEST_P(MeshStiffnessInvariantTest, TorqueIsForceTimesBaseRadiusAndThrustIsFSinPsi) {
  const MeshPlacement& p = placement();
  const MeshFrame f = CalcMeshFrame(p);
  const Matrix2x12 G = CalcLevelJacobian(level(), CalcMeshJacobian(f));
  const Matrix12 K = LevelStiffness(level(), f, data_);
  const Vector12 force = -K * UnitApproach(G);  // generalized force of a 1 m normal approach
  const double F = data_.K * 1.0;               // normal mesh force [N]
  const double s = p.drive_sign;
  const double psi_b = p.base_helix_angle;
  const double tol = kAlgebraTol * F;
  // Torques about the own axes: the transverse force F cos ψ_b times the base radius; the
  // pinion's opposes its drive, the gear's turns it against (external) or with (internal).
  EXPECT_NEAR(force(5), -s * F * std::cos(psi_b) * p.pinion_base_radius, tol * 0.1);
  EXPECT_NEAR(force(11), (p.internal ? s : -s) * F * std::cos(psi_b) * p.gear_base_radius,
              tol * 0.1);
  if (level() == MeshCoreLevel::kTorsional) {
    EXPECT_MATRIX_NEAR(force.segment<3>(0), Vector3::Zero(), 0.0);
    return;
  }
  // Forces: F η on the gear, −F η on the pinion; torque = |transverse force| × base radius.
  EXPECT_MATRIX_NEAR(force.segment<3>(6), F * f.eta, kAlgebraTol);
  EXPECT_MATRIX_NEAR(force.segment<3>(0), -F * f.eta, kAlgebraTol);
  const double transverse = force.segment<2>(6).norm();
  EXPECT_NEAR(std::abs(force(5)), transverse * p.pinion_base_radius, tol * 0.1);
  EXPECT_NEAR(std::abs(force(11)), transverse * p.gear_base_radius, tol * 0.1);
  // Axial force F sin ψ_b, towards −s h Z on the gear.
  EXPECT_NEAR(std::abs(force(8)), F * std::sin(psi_b), tol);
  const int hand =
      p.pinion_hand == HelixHand::kRight ? 1 : (p.pinion_hand == HelixHand::kLeft ? -1 : 0);
  EXPECT_NEAR(force(8), -s * hand * F * std::sin(psi_b), tol);
}

TEST_P(MeshStiffnessInvariantTest, RotatingOrReplacingTheSceneTransformsKMesh) {
  const MeshPlacement& p = placement();
  const Matrix12 K = LevelStiffness(level(), CalcMeshFrame(p), data_);
  const Eigen::Matrix<double, 12, 1> lambda = Eigenvalues(K);
  // (1) Rotation about Z by any angle about any point, plus any translation: q' = T q with
  //     T = blockdiag(R), so K' = T K Tᵀ.
  {
    const Matrix3 R = Eigen::AngleAxisd(-0.77, Vector3::UnitZ()).toRotationMatrix();
    const Vector3 shift(-1.2, 0.4, 0.35);
    MeshPlacement q = p;
    q.pinion_center = R * p.pinion_center + shift;
    q.gear_center = R * p.gear_center + shift;
    const Matrix12 K_moved = LevelStiffness(level(), CalcMeshFrame(q), data_);
    const Matrix12 T = BlockTransform(R, R);
    EXPECT_MATRIX_NEAR(K_moved, T * K * T.transpose(), kAlgebraTol);
    EXPECT_MATRIX_NEAR(Eigenvalues(K_moved), lambda, kAlgebraTol);
  }
  // (2) Turned over (rotation by π about X): the same mesh with the drive sign reversed about
  //     the new +Z and the same hands.
  {
    const Matrix3 R = Vector3(1.0, -1.0, -1.0).asDiagonal();
    MeshPlacement q = p;
    q.pinion_center = R * p.pinion_center;
    q.gear_center = R * p.gear_center;
    q.drive_sign = -p.drive_sign;
    const Matrix12 K_turned = LevelStiffness(level(), CalcMeshFrame(q), data_);
    const Matrix12 T = BlockTransform(R, R);
    EXPECT_MATRIX_NEAR(K_turned, T * K * T.transpose(), kAlgebraTol);
  }
  // (3) Mirror image (z → −z): the hands flip, the torque about Z (axial) keeps its sign,
  //     rotations transform as axial vectors (θ' = det(M) M θ) and σ flips, so h' = −h.
  {
    const Matrix3 M = Vector3(1.0, 1.0, -1.0).asDiagonal();
    MeshPlacement q = p;
    q.pinion_center = M * p.pinion_center;
    q.gear_center = M * p.gear_center;
    q.pinion_hand = OtherHand(p.pinion_hand);
    CoreData mirrored = data_;
    mirrored.h = -data_.h;
    const Matrix12 K_mirrored = LevelStiffness(level(), CalcMeshFrame(q), mirrored);
    const Matrix12 T = BlockTransform(M, -M);
    EXPECT_MATRIX_NEAR(K_mirrored, T * K * T.transpose(), kAlgebraTol);
  }
}

INSTANTIATE_TEST_SUITE_P(ScenesAndLevels, MeshStiffnessInvariantTest,
                         ::testing::Combine(::testing::ValuesIn(test::AllMeshScenes()),
                                            ::testing::Values(MeshCoreLevel::kBlankenshipSingh,
                                                              MeshCoreLevel::kCoupling4Dof,
                                                              MeshCoreLevel::kTorsional)),
                         SceneLevelName);

// ---------------------------------------------------------------------------------------------
// Helical: reversing the torque or the hand flips the thrust; a double-helical pair has none.
class HelicalThrustTest : public ::testing::TestWithParam<SceneLevel> {
 protected:
  // Generalized force of a 1 m normal approach in the mesh placed by `p`.
  Vector12 UnitApproachForce(const MeshPlacement& p, const CoreData& d) const {
    const MeshFrame f = CalcMeshFrame(p);
    const Matrix2x12 G = CalcLevelJacobian(std::get<1>(GetParam()), CalcMeshJacobian(f));
    return -LevelStiffness(std::get<1>(GetParam()), f, d) * UnitApproach(G);
  }
};

TEST_P(HelicalThrustTest, ReversingTorqueOrHandFlipsTheAxialForce) {
  const MeshPlacement& p = std::get<0>(GetParam()).placement;
  const CoreData d;
  const Vector12 force = UnitApproachForce(p, d);
  MeshPlacement reversed = p;
  reversed.drive_sign = -p.drive_sign;
  MeshPlacement other_hand = p;
  other_hand.pinion_hand = OtherHand(p.pinion_hand);
  const double tol = kAlgebraTol * d.K;
  for (int axial : {2, 8}) {
    EXPECT_GT(std::abs(force(axial)), 0.1 * d.K);
    EXPECT_NEAR(UnitApproachForce(reversed, d)(axial), -force(axial), tol);
    EXPECT_NEAR(UnitApproachForce(other_hand, d)(axial), -force(axial), tol);
  }
}

TEST_P(HelicalThrustTest, DoubleHelicalPairHasNoNetThrust) {
  // Two meshes of opposite hands, mid faces ±30 mm from the centres' plane, same normal load;
  // load centred on each half (h = 0).
  const MeshPlacement& p = std::get<0>(GetParam()).placement;
  CoreData d;
  d.h = 0.0;
  MeshPlacement half_a = p;
  half_a.face_offset = 0.03;
  MeshPlacement half_b = p;
  half_b.face_offset = -0.03;
  half_b.pinion_hand = OtherHand(p.pinion_hand);
  const Vector12 force_a = UnitApproachForce(half_a, d);
  const Vector12 net = force_a + UnitApproachForce(half_b, d);
  const double tol = kAlgebraTol * d.K;
  EXPECT_GT(std::abs(force_a(8)), 0.1 * d.K);  // each half does carry thrust
  EXPECT_NEAR(net(2), 0.0, tol);
  EXPECT_NEAR(net(8), 0.0, tol);
  // The halves' tilting moments cancel as well; the torques add.
  EXPECT_MATRIX_NEAR((net.segment<2>(3)), Eigen::Vector2d::Zero(), kAlgebraTol * d.K);
  EXPECT_MATRIX_NEAR((net.segment<2>(9)), Eigen::Vector2d::Zero(), kAlgebraTol * d.K);
  EXPECT_NEAR(net(5), 2.0 * force_a(5), tol);
}

INSTANTIATE_TEST_SUITE_P(HelicalScenes, HelicalThrustTest,
                         ::testing::Combine(::testing::ValuesIn(HelicalScenes()),
                                            ::testing::Values(MeshCoreLevel::kBlankenshipSingh,
                                                              MeshCoreLevel::kCoupling4Dof)),
                         SceneLevelName);

// ---------------------------------------------------------------------------------------------
// Spur limit: one full-face line (h = 0, F = 2b ⇒ μ = 1/3): K2 = K diag(1, b²/3), and the
// axial/rocking DOFs {z, θx, θy} decouple from the torsional/transverse ones {x, y, θz}.
class SpurLimitTest : public ::testing::TestWithParam<SceneLevel> {};

TEST_P(SpurLimitTest, AxialAndRockingDecoupleFromTorsionalAndTransverse) {
  const MeshFrame f = CalcMeshFrame(std::get<0>(GetParam()).placement);
  CoreData d;
  d.h = 0.0;
  d.mu = 1.0 / 3.0;
  const Matrix2 K2 = CalcStiffnessCore(d.K, d.h, d.mu, d.b);
  EXPECT_MATRIX_NEAR(K2, (Matrix2() << d.K, 0.0, 0.0, d.K * d.b * d.b / 3.0).finished(),
                     kAlgebraTol);
  const Matrix12 K = LevelStiffness(std::get<1>(GetParam()), f, d);
  // Permute to [x, y, θz | z, θx, θy] of both bodies.
  const std::vector<int> order = {0, 1, 5, 6, 7, 11, 2, 3, 4, 8, 9, 10};
  Matrix12 K_perm;
  for (int r = 0; r < 12; ++r) {
    for (int c = 0; c < 12; ++c) K_perm(r, c) = K(order[r], order[c]);
  }
  const double scale = K.cwiseAbs().maxCoeff();
  EXPECT_LE((K_perm.block<6, 6>(0, 6).cwiseAbs().maxCoeff()), kAlgebraTol * scale);
  EXPECT_LE((K_perm.block<6, 6>(6, 0).cwiseAbs().maxCoeff()), kAlgebraTol * scale);
  EXPECT_LE(K.row(2).cwiseAbs().maxCoeff(), kAlgebraTol * scale);  // no axial stiffness at all
  EXPECT_LE(K.row(8).cwiseAbs().maxCoeff(), kAlgebraTol * scale);
  EXPECT_GT((K_perm.block<6, 6>(0, 0).norm()), 0.1 * scale);
  if (std::get<1>(GetParam()) == MeshCoreLevel::kBlankenshipSingh) {
    // The rocking block is the twist stiffness K b²/3 about ζ = u.
    const Vector3& u = f.u;
    Vector12 q = Vector12::Zero();
    q.segment<3>(3) = u;
    EXPECT_NEAR(q.dot(K * q), d.K * d.b * d.b / 3.0, kAlgebraTol * scale);
  }
}

INSTANTIATE_TEST_SUITE_P(SpurScenes, SpurLimitTest,
                         ::testing::Combine(::testing::ValuesIn(SpurScenes()),
                                            ::testing::Values(MeshCoreLevel::kBlankenshipSingh,
                                                              MeshCoreLevel::kCoupling4Dof,
                                                              MeshCoreLevel::kTorsional)),
                         SceneLevelName);

// ---------------------------------------------------------------------------------------------
// B–S's K_o (Eq. 41b) and its coordinates.
class BsKoTest : public ::testing::TestWithParam<Scene> {};

TEST_P(BsKoTest, KoEqualsGtK2GInTheScaledCoordinates) {
  const MeshFrame f = CalcMeshFrame(GetParam().placement);
  const CoreData d;
  const double kappa = d.h / d.b;
  const double c = std::cos(f.signed_helix_angle);
  const double s = std::sin(f.signed_helix_angle);
  const Matrix6 Ko = CalcBsKo(d.K, kappa, d.mu, c, s);
  const Matrix2 K2 = CalcStiffnessCore(d.K, d.h, d.mu, d.b);
  const Matrix2x6 P = CalcBsDeflectionProjection(c, s, d.b);
  // (1) The core identity: K_o = Pᵀ K2 P, i.e. g = (0, c, s, κ, −s, c) with δ_η = g₀·δ_BS and
  //     δ_ζ = −δ_BS,4 / b reproduces the energy ½ δᵀ K2 δ.
  EXPECT_MATRIX_NEAR(Ko, P.transpose() * K2 * P, kAlgebraTol);
  // (2) In the pair's coordinates: Tᵀ K_o T = G_BSᵀ K2 G_BS with G_BS = P T; for spur gears in
  //     the centres' plane G_BS = G, so K_o reproduces K_mesh exactly (for helical gears B–S's
  //     arm projection drops the tilt terms checked in mesh_jacobian_test).
  const Matrix6x12 T = CalcBsRelativeDisplacementMap(f, d.b);
  const Matrix12 K_bs = T.transpose() * Ko * T;
  EXPECT_MATRIX_NEAR(K_bs, CalcMeshStiffness(P * T, K2), kAlgebraTol);
  const Matrix2x12 G = CalcMeshJacobian(f);
  if (f.base_helix_angle == 0.0) {
    EXPECT_MATRIX_NEAR(K_bs, CalcMeshStiffness(G, K2), kAlgebraTol);
  }
  // (3) The load: with the 6-vector transmission error of Eq. (41c)/(42), Tᵀ K_o δ̃ = (PT)ᵀ K2 ε.
  const Vector2 epsilon(2.0e-6, -3.0e-5);
  const Vector6 te = CalcBsTransmissionError(epsilon, d.b, c);
  EXPECT_MATRIX_NEAR(Ko * te, P.transpose() * K2 * epsilon, kAlgebraTol);
  if (f.base_helix_angle == 0.0) {
    EXPECT_MATRIX_NEAR(T.transpose() * Ko * te, CalcMeshLoad(G, K2, epsilon), kAlgebraTol);
  }
}

INSTANTIATE_TEST_SUITE_P(Scenes, BsKoTest, ::testing::ValuesIn(test::AllMeshScenes()),
                         [](const ::testing::TestParamInfo<Scene>& param_info) {
                           return param_info.param.name;
                         });

TEST(BsKoTest, HasThePaperSignPatternAndRank) {
  const double c = std::cos(0.3);
  const double s = std::sin(0.3);
  const Matrix6 Ko = CalcBsKo(2.0, 0.25, 0.3, c, s);
  Vector6 g;
  g << 0.0, c, s, 0.25, -s, c;
  Matrix6 expected = 2.0 * g * g.transpose();
  expected(3, 3) += 2.0 * (0.3 - 0.0625);
  EXPECT_MATRIX_NEAR(Ko, expected, kAlgebraTol);
  EXPECT_MATRIX_NEAR(Ko.row(0), Vector6::Zero().transpose(), 0.0);  // nothing normal to the plane
  const Vector6 lambda = Eigen::SelfAdjointEigenSolver<Matrix6>(Ko).eigenvalues();
  EXPECT_EQ((lambda.array() > kRankTol * lambda.maxCoeff()).count(), 2);
}

TEST(BsKoTest, ScalarTransmissionErrorHasOnlyTheLineOfActionEntry) {
  // B–S Eq. (42): a scalar (uniform) error e gives ε = [e, 0] and δ̃ = (0, e / cos ψ_b, 0, 0, 0, 0).
  const CoreData d;
  const Matrix2 K2 = CalcStiffnessCore(d.K, d.h, d.mu, d.b);
  const double e = 7.5e-6;
  const double line_length = 1.6 * d.b;
  const double k = d.K / line_length;  // uniform stiffness per length on one line centred at h
  const Vector2 epsilon =
      CalcTransmissionErrorPair(K2, k * e * line_length, k * e * line_length * d.h);
  EXPECT_MATRIX_NEAR(epsilon, Vector2(e, 0.0), kAlgebraTol);
  const double c = std::cos(0.3);
  Vector6 expected = Vector6::Zero();
  expected(1) = e / c;
  EXPECT_MATRIX_NEAR(CalcBsTransmissionError(epsilon, d.b, c), expected, kAlgebraTol);
}

// ---------------------------------------------------------------------------------------------
// The energy behind K2 and ε (spec 01 §3), on a discretised contact line.
TEST(StiffnessCoreTest, CoreAndTransmissionErrorReproduceTheMeshEnergy) {
  // Two contact-line pieces with varying k(σ) and separation e(σ), midpoint rule on n cells.
  const double b = 0.012;
  const int n = 400;
  std::vector<double> sigma, weight, sep;
  for (const auto& [lo, hi] : {std::pair{-0.011, -0.002}, std::pair{0.001, 0.0095}}) {
    for (int m = 0; m < n; ++m) {
      const double x = lo + (hi - lo) * (m + 0.5) / n;
      sigma.push_back(x);
      weight.push_back((1.0e10 + 3.0e11 * x) * (hi - lo) / n);  // k dℓ [N/m]
      sep.push_back(4e-6 + 2e-4 * x - 0.05 * x * x);            // e [m]
    }
  }
  double K = 0.0, ks = 0.0, kss = 0.0, ke = 0.0, kse = 0.0;
  for (std::size_t m = 0; m < sigma.size(); ++m) {
    K += weight[m];
    ks += weight[m] * sigma[m];
    kss += weight[m] * sigma[m] * sigma[m];
    ke += weight[m] * sep[m];
    kse += weight[m] * sigma[m] * sep[m];
  }
  const double h = ks / K;
  const double mu = kss / (K * b * b);
  const Matrix2 K2 = CalcStiffnessCore(K, h, mu, b);
  const Vector2 epsilon = CalcTransmissionErrorPair(K2, ke, kse);
  // ∇U(δ) = Σ k dℓ (δ_η − σ δ_ζ − e) [1, −σ] must equal K2 (δ − ε) for any δ.
  for (const Vector2& delta : {Vector2(0.0, 0.0), Vector2(3e-6, 0.0), Vector2(-1e-6, 2e-4)}) {
    Vector2 gradient = Vector2::Zero();
    for (std::size_t m = 0; m < sigma.size(); ++m) {
      const double stretch = delta(0) - sigma[m] * delta(1) - sep[m];
      gradient += weight[m] * stretch * Vector2(1.0, -sigma[m]);
    }
    EXPECT_MATRIX_NEAR(gradient, K2 * (delta - epsilon), 1e-9);
  }
}

TEST(StiffnessCoreTest, MeshLoadIsGtK2Epsilon) {
  const MeshFrame f = CalcMeshFrame(test::MakeMeshPlacement(true, HelixHand::kLeft, -1, true));
  const CoreData d;
  const Matrix2x12 G = CalcMeshJacobian(f);
  const Matrix2 K2 = CalcStiffnessCore(d.K, d.h, d.mu, d.b);
  const Vector2 epsilon(1e-6, 2e-5);
  EXPECT_MATRIX_NEAR(CalcMeshLoad(G, K2, epsilon), G.transpose() * (K2 * epsilon), kAlgebraTol);
  // The load balances the stiffness force at the deflection δ = ε: for q with G q = ε the net
  // generalized force −K q + f vanishes.
  const Vector12 q = G.transpose() * (G * G.transpose()).inverse() * epsilon;
  EXPECT_LE((CalcMeshLoad(G, K2, epsilon) - CalcMeshStiffness(G, K2) * q).norm(),
            kAlgebraTol * CalcMeshLoad(G, K2, epsilon).norm());
}

TEST(StiffnessCoreTest, ReducedCoresUseOnlyTheNormalApproachInTheTransmissionError) {
  const CoreData d;
  const double ke = 4e3, kse = 25.0;
  for (MeshCoreLevel level : {MeshCoreLevel::kCoupling4Dof, MeshCoreLevel::kTorsional}) {
    const Matrix2 K2 = CalcLevelCore(level, d.K, d.h, d.mu, d.b);
    EXPECT_MATRIX_NEAR(K2, (Matrix2() << d.K, 0.0, 0.0, 0.0).finished(), 0.0);
    EXPECT_MATRIX_NEAR(CalcTransmissionErrorPair(K2, ke, kse), Vector2(ke / d.K, 0.0), kAlgebraTol);
  }
  // A rank-1 B–S core (point load at σ = h: μ = κ², ∫kσe = h ∫ke) reproduces the load of the
  // uniform separation e = ke/K, and ε = [e, 0]; an empty mesh gives zero.
  const Matrix2 point = CalcStiffnessCore(d.K, d.h, (d.h / d.b) * (d.h / d.b), d.b);
  const Vector2 eps_point = CalcTransmissionErrorPair(point, ke, d.h * ke);
  EXPECT_MATRIX_NEAR(point * eps_point, Vector2(ke, -d.h * ke), kAlgebraTol);
  EXPECT_MATRIX_NEAR(eps_point, Vector2(ke / d.K, 0.0), kAlgebraTol);
  EXPECT_MATRIX_NEAR(CalcTransmissionErrorPair(Matrix2::Zero(), 0.0, 0.0), Vector2::Zero(), 0.0);
}

TEST(StiffnessCoreTest, DampingIsProportionalToTheStiffnessCore) {
  const MeshFrame f = CalcMeshFrame(test::MakeMeshPlacement(false, HelixHand::kRight, 1, true));
  const CoreData d;
  const Matrix2x12 G = CalcMeshJacobian(f);
  const Matrix2 K2 = CalcStiffnessCore(d.K, d.h, d.mu, d.b);
  const double c_m = 1.8e3;
  EXPECT_MATRIX_NEAR(CalcMeshDamping(G, K2, c_m), (c_m / d.K) * CalcMeshStiffness(G, K2),
                     kAlgebraTol);
  EXPECT_MATRIX_NEAR(CalcDampingCore(CalcStiffnessCore(0.0, d.h, d.mu, d.b), c_m), Matrix2::Zero(),
                     0.0);
  EXPECT_NEAR(CalcMeshDampingCoefficient(0.05, d.K, 0.8), 2.0 * 0.05 * std::sqrt(d.K * 0.8),
              kAlgebraTol * c_m);
}

TEST(StiffnessCoreTest, TorsionalCoreIsTheThetaZBlockOfThe4DofLevel) {
  for (const Scene& scene : test::AllMeshScenes()) {
    const MeshPlacement& p = scene.placement;
    const MeshFrame f = CalcMeshFrame(p);
    const CoreData d;
    const Matrix2x12 G = CalcMeshJacobian(f);
    const TorsionalCore core = CalcTorsionalCore(G, d.K);
    const double s = p.drive_sign;
    EXPECT_NEAR(core.k, d.K * std::pow(std::cos(p.base_helix_angle), 2), kAlgebraTol * d.K);
    EXPECT_NEAR(core.pinion_arm, s * p.pinion_base_radius, kAlgebraTol) << scene.name;
    EXPECT_NEAR(core.gear_arm, (p.internal ? -s : s) * p.gear_base_radius, kAlgebraTol)
        << scene.name;
    const Matrix12 K_sdof = CalcTorsionalMeshStiffness(core);
    EXPECT_MATRIX_NEAR(K_sdof, LevelStiffness(MeshCoreLevel::kTorsional, f, d), kAlgebraTol);
    const Matrix12 K_4dof = LevelStiffness(MeshCoreLevel::kCoupling4Dof, f, d);
    EXPECT_NEAR(K_sdof(5, 5), K_4dof(5, 5), kAlgebraTol * K_4dof(5, 5));
    EXPECT_NEAR(K_sdof(5, 11), K_4dof(5, 11), kAlgebraTol * K_4dof(5, 5));
    EXPECT_NEAR(K_sdof(11, 11), K_4dof(11, 11), kAlgebraTol * K_4dof(11, 11));
  }
}

TEST(StiffnessCoreTest, CoreHasThePaperForm) {
  const CoreData d;
  const Matrix2 K2 = CalcStiffnessCore(d.K, d.h, d.mu, d.b);
  EXPECT_MATRIX_NEAR(
      K2, (Matrix2() << d.K, -d.K * d.h, -d.K * d.h, d.K * d.mu * d.b * d.b).finished(), 0.0);
  EXPECT_MATRIX_NEAR(CalcLevelCore(MeshCoreLevel::kBlankenshipSingh, d.K, d.h, d.mu, d.b), K2, 0.0);
  EXPECT_STREQ(ToString(MeshCoreLevel::kCoupling4Dof), "coupling_4dof");
}

// ---------------------------------------------------------------------------------------------
// Bad input.
TEST(StiffnessCoreTest, RejectsACoreThatIsNotPositiveSemiDefinite) {
  // μ < κ²: h = 6 mm on b = 12 mm gives κ² = 0.25.
  EXPECT_THROWS_MESSAGE(CalcStiffnessCore(1e8, 0.006, 0.2, 0.012), InvalidInput,
                        "mu: 0.2 is below kappa\\^2 = \\(h/b\\)\\^2 = 0.25");
  EXPECT_THROWS_MESSAGE(CalcLevelCore(MeshCoreLevel::kCoupling4Dof, 1e8, 0.006, 0.2, 0.012),
                        InvalidInput, "mu:");
  EXPECT_THROWS_MESSAGE(CalcBsKo(1e8, 0.5, 0.2, 1.0, 0.0), InvalidInput, "mu: 0.2 is below");
  EXPECT_NO_THROW(CalcStiffnessCore(1e8, 0.006, 0.25, 0.012));  // μ = κ²: rank 1, still PSD
}

TEST(StiffnessCoreTest, RejectsBadCoreArguments) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROWS_MESSAGE(CalcStiffnessCore(-1.0, 0.0, 0.3, 0.01), InvalidInput, "K: mesh stiffness");
  EXPECT_THROWS_MESSAGE(CalcStiffnessCore(nan, 0.0, 0.3, 0.01), InvalidInput, "K:");
  EXPECT_THROWS_MESSAGE(CalcStiffnessCore(1e8, nan, 0.3, 0.01), InvalidInput, "h:");
  EXPECT_THROWS_MESSAGE(CalcStiffnessCore(1e8, 0.0, nan, 0.01), InvalidInput, "mu:");
  EXPECT_THROWS_MESSAGE(CalcStiffnessCore(1e8, 0.0, 0.3, 0.0), InvalidInput, "half_face_width:");
  EXPECT_THROWS_MESSAGE(CalcStiffnessCore(1e8, 0.0, 0.3, -0.01), InvalidInput, "half_face_width:");
  EXPECT_THROWS_MESSAGE(CalcBsKo(1e8, 0.0, 0.3, 0.9, 0.1), InvalidInput, "sin_psi_b:");
  EXPECT_THROWS_MESSAGE(CalcBsKo(1e8, 0.0, 0.3, -1.0, 0.0), InvalidInput, "cos_psi_b:");
  EXPECT_THROWS_MESSAGE(CalcBsKo(-1e8, 0.0, 0.3, 1.0, 0.0), InvalidInput, "K:");
  EXPECT_THROWS_MESSAGE(CalcBsDeflectionProjection(1.0, 0.0, 0.0), InvalidInput,
                        "half_face_width:");
  EXPECT_THROWS_MESSAGE(CalcBsTransmissionError(Vector2(1.0, 0.0), 0.01, 0.0), InvalidInput,
                        "cos_psi_b:");
}

TEST(StiffnessCoreTest, RejectsBadDampingTransmissionErrorAndTorsionalInput) {
  const Matrix2 K2 = CalcStiffnessCore(1e8, 0.001, 0.3, 0.01);
  EXPECT_THROWS_MESSAGE(CalcDampingCore(K2, -1.0), InvalidInput, "c_m: mesh damping");
  EXPECT_THROWS_MESSAGE(CalcMeshDamping(Matrix2x12::Zero(), K2, std::nan("")), InvalidInput,
                        "c_m:");
  EXPECT_THROWS_MESSAGE(CalcMeshDampingCoefficient(0.05, 1e8, 0.0), InvalidInput,
                        "equivalent_mass:");
  EXPECT_THROWS_MESSAGE(CalcMeshDampingCoefficient(-0.05, 1e8, 1.0), InvalidInput,
                        "damping_ratio:");
  Matrix2 asymmetric = K2;
  asymmetric(0, 1) *= 2.0;
  EXPECT_THROWS_MESSAGE(CalcTransmissionErrorPair(asymmetric, 1.0, 0.0), InvalidInput,
                        "K2: must be symmetric");
  EXPECT_THROWS_MESSAGE(CalcTransmissionErrorPair(K2, std::nan(""), 0.0), InvalidInput,
                        "k_e_integral:");
  EXPECT_THROWS_MESSAGE(CalcTransmissionErrorPair(K2, 0.0, HUGE_VAL), InvalidInput,
                        "k_sigma_e_integral:");
  EXPECT_THROWS_MESSAGE(CalcTorsionalCore(Matrix2x12::Zero(), 1e8), InvalidInput, "G:");
  const MeshFrame f = CalcMeshFrame(test::MakeMeshPlacement(false, HelixHand::kNone, 1, false));
  EXPECT_THROWS_MESSAGE(CalcTorsionalCore(CalcMeshJacobian(f), -1.0), InvalidInput, "K:");
}

}  // namespace
}  // namespace geardyn
