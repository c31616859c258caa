// Probes (geardyn/system/probes.hpp) against independent truths: the static DTE of a loaded
// torsional pair T/(r_b K), the mesh force = torque / (r_b cos ψ_b) of the helical pair scene,
// the global equilibrium of the bearing forces with the external loads (forces and moments),
// closed-form DTE/torsional TE/damping force of a hand-built pair, the probe operator P q − o(θ)
// against the per-mesh kernel, error messages and the no-allocation rule of the kernels.
#include "geardyn/system/probes.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "geardyn/models/scene/scene_reader.hpp"
#include "geardyn/models/system/scene_system.hpp"
#include "geardyn/system/static_deflection.hpp"
#include "hand_pair.hpp"
#include "support/expect_throws.hpp"
#include "support/no_malloc.hpp"

namespace geardyn {
namespace {

using test::HandPairBuilder;
using test::HandPairParams;

// Static solves of small systems: O(n) round-off relative to the load, K ratios ≲ 1e4.
constexpr double kStaticTol = 1e-9;

Vector6 Torque(double t) {
  Vector6 f = Vector6::Zero();
  f(5) = t;
  return f;
}

// The hand pair (line of action +Y, zero pressure angle) with a B–S spur core and an optional
// constant transmission error ε = (eps_eta, 0).
LinearMeshCore SpurCoreWithError(const HandPairParams& p, double eps_eta, double c_m = 0.0) {
  std::optional<Coefficient> te;
  if (eps_eta != 0.0) te = ConstantCoefficient(Vector2(eps_eta, 0.0));
  return LinearMeshCore(MeshCoreLevel::kBlankenshipSingh,
                        ConstantCoefficient(Vector3(p.k, 0.0, p.k * p.b * p.b / 3.0)), p.b, te,
                        MeshDamping::FromCoefficient(c_m));
}

TEST(ProbesTest, StaticDteOfATorsionalPairIsTorqueOverBaseRadiusTimesStiffness) {
  // Torsional level: G keeps only the θz columns, so DTE = TE_θ = r1 θ1 + r2 θ2 − ε and the
  // static balance of the pinion, T = r1 F_η = r1 K DTE, gives DTE = T / (r1 K).
  HandPairParams p;
  const double T = 120.0;
  SystemBuilder b;
  const BodyIndex i = b.AddBody("pinion", test::DiagMass(p.m1, p.Id1, p.I1));
  const BodyIndex j = b.AddBody("wheel", test::DiagMass(p.m2, p.Id2, p.I2));
  b.AddMesh(
      "mesh", i, j, CalcLevelJacobian(MeshCoreLevel::kTorsional, test::HandPairJacobian(p)),
      LinearMeshCore(MeshCoreLevel::kTorsional, ConstantCoefficient(Vector3(p.k, 0, 0)), p.b));
  b.AddTorque(i, Torque(T));
  b.AddTorque(j, Torque(T * p.r2 / p.r1));
  const SystemModel full = b.Build();
  const SystemModel model = full.Restrict(
      {full.dof_map().dof(i, BodyDof::kThetaZ), full.dof_map().dof(j, BodyDof::kThetaZ)});
  const StaticDeflectionResult s = SolveStaticDeflection(model);
  ASSERT_TRUE(s.summary.ok()) << s.summary.BriefReport();
  const ProbeValues v = EvalProbes(model, 0.0, s.deflection);
  ASSERT_EQ(v.meshes.size(), 1u);
  const double expected = T / (p.r1 * p.k);
  EXPECT_NEAR(v.meshes[0].dte, expected, kStaticTol * expected);
  EXPECT_NEAR(v.meshes[0].torsional_te, expected, kStaticTol * expected);
  EXPECT_NEAR(v.meshes[0].force(0), T / p.r1, kStaticTol * T / p.r1);
}

TEST(ProbesTest, DteSubtractsTheStaticTransmissionErrorAndLoadedTeKeepsIt) {
  // B–S spur core on bearings with a constant ε_η: the pinion's θz balance still fixes
  // F_η = T / r1, so DTE = δ_η − ε_η = T/(r1 k) whatever ε, and the loaded TE is DTE + ε.
  HandPairParams p;
  const double T = 90.0, eps = 7e-6;
  SystemBuilder b = HandPairBuilder(p, SpurCoreWithError(p, eps));
  b.AddTorque(BodyIndex(0), Torque(T));
  b.AddTorque(BodyIndex(1), Torque(T * p.r2 / p.r1));
  const SystemModel model = b.Build();
  const StaticDeflectionResult s = SolveStaticDeflection(model);
  ASSERT_TRUE(s.summary.ok()) << s.summary.BriefReport();
  const ProbeValues v = EvalProbes(model, 0.3, s.deflection);
  const double expected = T / (p.r1 * p.k);
  EXPECT_NEAR(v.meshes[0].dte, expected, kStaticTol * expected);
  EXPECT_NEAR(v.meshes[0].deflection(0), expected + eps, kStaticTol * (expected + eps));
  EXPECT_NEAR(v.meshes[0].force(0), T / p.r1, kStaticTol * T / p.r1);
  // Torsional TE of the hand pair (closed form of its G): r1 θz_i + r2 θz_j − ε.
  const double te_theta = p.r1 * s.deflection(5) + p.r2 * s.deflection(11) - eps;
  EXPECT_NEAR(v.meshes[0].torsional_te, te_theta, 1e-12 * std::abs(te_theta));
  // The bearings carry ∓F_η along y (the mesh pushes the wheel along +y).
  EXPECT_NEAR(v.element_forces[0](1), -T / p.r1, kStaticTol * T / p.r1);
  EXPECT_NEAR(v.element_forces[1](1), T / p.r1, kStaticTol * T / p.r1);
}

TEST(ProbesTest, MeshDampingForceIsCoefficientTimesApproachRate) {
  // C2 = (c_m/K) K2 = c_m diag(1, b²/3) for the spur core (B–S Eq. 39):
  // F = k (δ − ε) + c_m δ̇ with δ_η = y_i − y_j + r1 θz_i + r2 θz_j, δ_ζ = θx_i − θx_j.
  HandPairParams p;
  const double c_m = 2.5e3, eps = -3e-6;
  const SystemModel model = HandPairBuilder(p, SpurCoreWithError(p, eps, c_m)).Build();
  VectorX q(12), v(12);
  for (int a = 0; a < 12; ++a) {
    q(a) = 1e-6 * std::sin(1.0 + a);
    v(a) = 1e-3 * std::cos(2.0 + 0.5 * a);
  }
  const auto eta = [&](const VectorX& x) { return x(1) - x(7) + p.r1 * x(5) + p.r2 * x(11); };
  const auto zeta = [&](const VectorX& x) { return x(3) - x(9); };
  ProbeWorkspace ws(model);
  const MeshProbeValues m = EvalMeshProbe(model, ws, MeshIndex(0), 1.7, q, v);
  const double b2 = p.b * p.b / 3.0;
  EXPECT_NEAR(m.force(0), p.k * (eta(q) - eps) + c_m * eta(v), 1e-12 * p.k * 1e-6);
  EXPECT_NEAR(m.force(1), p.k * b2 * zeta(q) + c_m * b2 * zeta(v), 1e-12 * p.k * b2 * 1e-6);
  EXPECT_NEAR(m.dte, eta(q) - eps, 1e-18);
  // Element forces with damping: the bearings have no damping, so K q only.
  VectorX f(6);
  CalcElementForce(model, ElementIndex(0), q, v, f);
  EXPECT_NEAR(f(1), p.bearing * q(1), 1e-12 * p.bearing * 1e-6);
}

TEST(ProbesTest, HelicalSceneMeshForceAndBearingLoadsBalanceTheTorques) {
  // builtin:helical-pair: 150 N·m on the pinion, 366 N·m on the wheel. Independent truths:
  // (1) the pinion's θz balance: T = a_1 cos ψ_b F_η (the transverse mesh force is T / r_b1);
  // (2) global equilibrium: the grounded bearings carry the external loads, forces and moments
  //     about the origin (the meshes are internal forces).
  // The mean-LTI level: K2 is the constant mean, so the probe at any θ sees the static state's
  // mean mesh force (at other levels K2(θ) δ̄ differs from the mean force K̄2 δ̄).
  const Scene scene = LoadScene("builtin:helical-pair", {"mesh.pinion-wheel.model=lti"});
  const SceneSystem built = BuildSceneSystem(scene);
  const SystemModel& model = built.model;
  const StaticDeflectionResult s = SolveStaticDeflection(model);
  ASSERT_TRUE(s.summary.ok()) << s.summary.BriefReport();
  const ProbeValues v = EvalProbes(model, 0.0, s.deflection);
  const GearPairGeometry& g = scene.meshes[0].geometry;
  const double T = 150.0;
  const double expected_force = T / (g.pinion.base_radius * std::cos(g.base_helix_angle));
  EXPECT_NEAR(v.meshes[0].force(0), expected_force, 1e-8 * expected_force);

  Vector3 load_force = Vector3::Zero(), load_moment = Vector3::Zero();
  const DofMap& map = model.dof_map();
  for (int d = 0; d < model.num_dofs(); ++d) {
    const int body = map.dof_body(d).value();
    const int c = static_cast<int>(map.dof_component(d));
    Vector6 f = Vector6::Zero();
    f(c) = model.constant_load()(d);
    load_force += f.head<3>();
    load_moment += f.tail<3>() + built.centres[body].cross(Vector3(f.head<3>()));
  }
  Vector3 bearing_force = Vector3::Zero(), bearing_moment = Vector3::Zero();
  const std::vector<SystemElement>& elements = model.elements();
  for (std::size_t e = 0; e < elements.size(); ++e) {
    ASSERT_TRUE(elements[e].is_grounded());
    const Vector6 f = v.element_forces[e];
    const Vector3 centre = built.centres[elements[e].bodies[0].value()];
    bearing_force += f.head<3>();
    bearing_moment += f.tail<3>() + centre.cross(Vector3(f.head<3>()));
  }
  // Scale: the mesh force (≈ 4 kN) and its moments about the origin.
  const double force_scale = expected_force, moment_scale = expected_force * 0.2;
  EXPECT_LT((bearing_force - load_force).norm(), 1e-8 * force_scale);
  EXPECT_LT((bearing_moment - load_moment).norm(), 1e-8 * moment_scale);
  // The bearings carry the whole mesh force: the transverse part is not zero.
  EXPECT_GT(bearing_force.norm() + v.element_forces[0].head<2>().norm(), 0.1 * expected_force);
}

TEST(ProbesTest, ProbeMatrixGivesTheKernelValuesAtEveryPhase) {
  // A varying ε (one Fourier harmonic) on the hand pair: y(θ) = P q − o(θ) must equal the
  // per-mesh kernel's DTE, torsional TE and loaded TE at any θ.
  HandPairParams p;
  MatrixX cosines = MatrixX::Zero(2, 1), sines = MatrixX::Zero(2, 1);
  cosines(0, 0) = 4e-6;
  sines(0, 0) = -1e-6;
  const LinearMeshCore core(MeshCoreLevel::kBlankenshipSingh,
                            ConstantCoefficient(Vector3(p.k, 0.0, p.k * p.b * p.b / 3.0)), p.b,
                            FourierCoefficient::FromCosSin(Vector2(1e-6, 0.0), cosines, sines));
  const SystemModel model = HandPairBuilder(p, core).Build();
  const ProbeMatrix probes = MakeProbeMatrix(
      model, {ProbeKind::kMeshDte, ProbeKind::kMeshTorsionalTe, ProbeKind::kMeshLoadedTe});
  ASSERT_EQ(probes.rows(), 3);
  EXPECT_EQ(probes.names[0], "dte:mesh");
  EXPECT_EQ(probes.names[1], "torsional_te:mesh");
  EXPECT_TRUE(probes.has_offset[0]);
  EXPECT_FALSE(probes.has_offset[2]);
  VectorX q(12);
  for (int a = 0; a < 12; ++a) q(a) = 1e-5 * std::cos(0.7 * a + 0.2);
  ProbeWorkspace ws(model);
  VectorX offset(3), dte(1);
  for (const double theta : {0.0, 0.9, 2.5, 5.1}) {
    EvalProbeOffset(model, probes, theta, offset);
    const VectorX y = probes.P * q - offset;
    const MeshProbeValues m = EvalMeshProbe(model, ws, MeshIndex(0), theta, q, VectorX());
    EXPECT_NEAR(y(0), m.dte, 1e-18);
    EXPECT_NEAR(y(1), m.torsional_te, 1e-18);
    EXPECT_NEAR(y(2), m.deflection(0), 1e-18);
    // ε_η(θ) = 1e-6 + 4e-6 cos θ − 1e-6 sin θ (the coefficient's definition).
    EXPECT_NEAR(m.transmission_error(0), 1e-6 + 4e-6 * std::cos(theta) - 1e-6 * std::sin(theta),
                1e-18);
    EvalMeshDte(model, theta, q, dte);
    EXPECT_NEAR(dte(0), m.dte, 1e-18);
  }
}

TEST(ProbesTest, KernelsDoNotAllocate) {
  HandPairParams p;
  const SystemModel model = HandPairBuilder(p, SpurCoreWithError(p, 1e-6, 100.0)).Build();
  const ProbeMatrix probes = MakeProbeMatrix(model);
  ProbeWorkspace ws(model);
  const VectorX q = VectorX::Constant(12, 1e-6), v = VectorX::Constant(12, 1e-3);
  VectorX dte(1), offset(1), f(6);
  double sink = 0.0;
  const long allocations = test::CountAllocations([&] {
    for (int s = 0; s < 8; ++s) {
      const double theta = 0.4 * s;
      sink += EvalMeshProbe(model, ws, MeshIndex(0), theta, q, v).force(0);
      EvalMeshDte(model, theta, q, dte);
      EvalProbeOffset(model, probes, theta, offset);
      CalcElementForce(model, ElementIndex(1), q, v, f);
      sink += dte(0) + offset(0) + f(0);
    }
  });
  EXPECT_TRUE(std::isfinite(sink));
  if (GEARDYN_HAVE_ALLOCATION_COUNTER) {
    EXPECT_EQ(allocations, 0);
  }
}

TEST(ProbesTest, BadArgumentsThrowNamingThem) {
  HandPairParams p;
  const SystemModel model = HandPairBuilder(p, test::SpurCore(p)).Build();
  ProbeWorkspace ws(model);
  EXPECT_THROWS_MESSAGE(EvalMeshProbe(model, ws, MeshIndex(0), 0.0, VectorX::Zero(5), VectorX()),
                        InvalidInput, "EvalMeshProbe: q must have num_dofs = 12 entries, got 5");
  EXPECT_THROWS_MESSAGE(EvalMeshProbe(model, ws, MeshIndex(3), 0.0, VectorX::Zero(12), VectorX()),
                        InvalidInput, "mesh index 3 out of range");
  VectorX f(12);
  EXPECT_THROWS_MESSAGE(CalcElementForce(model, ElementIndex(0), VectorX::Zero(12), VectorX(), f),
                        InvalidInput,
                        "CalcElementForce: force: size 12 does not match the "
                        "expected 6");
  const SystemModel other = HandPairBuilder(p, test::SpurCore(p)).Build();
  EXPECT_THROWS_MESSAGE(EvalMeshProbe(other, ws, MeshIndex(0), 0.0, VectorX::Zero(12), VectorX()),
                        InvalidInput, "workspace was built for another model");
}

}  // namespace
}  // namespace geardyn
