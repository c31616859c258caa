// [[shaft]] scenes through MakeSystemModel: closed-form shaft frequencies (free–free torsion of a
// shaft with an end disc, pinned–pinned Timoshenko bending) and the scene path against the same
// system assembled directly with SystemBuilder (the geared-shaft benchmark's construction).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "geardyn/models/elements/shaft_beam.hpp"
#include "geardyn/models/scene/builtin_scenes.hpp"
#include "geardyn/models/scene/scene_reader.hpp"
#include "geardyn/models/system/scene_system.hpp"
#include "geardyn/numerics/symmetric_eigen.hpp"
#include "geardyn/system/system_builder.hpp"
#include "geardyn/system/workspace.hpp"

namespace geardyn {
namespace {

constexpr double kE = 2.1e11, kNu = 0.3, kRho = 7850.0;  // steel [Pa, -, kg/m³]

std::string Num(double v) {
  char b[40];
  std::snprintf(b, sizeof(b), "%.17g", v);
  return b;
}

// All eigenvalues λ = ω² of (K̄, M), ascending [rad²/s²].
VectorX Eigenvalues(const SystemModel& model) {
  SystemWorkspace ws(model, StorageKind::kDense);
  GeneralizedEigenOptions o;
  o.compute_vectors = false;
  const GeneralizedEigenResult r =
      SolveGeneralizedEigenDense(AssembleMeanStiffness(model, ws), model.DenseMass(), o);
  EXPECT_TRUE(r.summary.ok()) << r.summary.message;
  return r.eigenvalues;
}

// Relative distance from ω² to the nearest computed eigenvalue.
double NearestRelative(const VectorX& eigenvalues, double omega2) {
  double best = 1e300;
  for (const double l : eigenvalues) best = std::min(best, std::abs(l - omega2) / omega2);
  return best;
}

// The helical pair plus a free shaft "torsion" (L = 1 m, Ø 40 mm, 100 elements) carrying a disc
// of polar inertia I_d = μ ρ J_p L at its end, and a shaft "beam" (L = 1 m, Ø 40 mm, 40
// elements) pinned at both ends by stiff radial bearings: two blocks decoupled from the pair.
std::string ShaftScene(double disc_inertia, int beam_refinement = 1) {
  const std::string material = "youngs_modulus = " + Num(kE) + "\npoisson_ratio = " + Num(kNu) +
                               "\ndensity = " + Num(kRho) + "\n";
  return std::string(*BuiltinSceneText("helical-pair")) +
         "\n[[gear]]\nname = \"disc\"\nteeth = 20\nnormal_module = 0.003\nface_width = 0.02\n"
         "mass = 1.0\ninertia = " +
         Num(disc_inertia) + "\ntransverse_inertia = " + Num(disc_inertia) +
         "\n\n[[shaft]]\nname = \"torsion\"\n" + material +
         "sections = [{ length = 1.0, outer_diameter = 0.04, elements = 100 }]\n"
         "gears = [{ gear = \"disc\", station = 1.0 }]\n"
         "\n[[shaft]]\nname = \"beam\"\n" +
         material + "sections = [{ length = 0.4, outer_diameter = 0.04, elements = " +
         std::to_string(16 * beam_refinement) +
         " },\n"
         "            { length = 0.6, outer_diameter = 0.04, elements = " +
         std::to_string(24 * beam_refinement) +
         " }]\n"
         "\n[[bearing]]\nname = \"pin-a\"\nbody = \"beam\"\nstation = 0.0\n"
         "stiffness = [1e13, 1e13, 0.0, 0.0, 0.0, 0.0]\n"
         "\n[[bearing]]\nname = \"pin-b\"\nbody = \"beam\"\nstation = 1.0\n"
         "stiffness = [1e13, 1e13, 0.0, 0.0, 0.0, 0.0]\n";
}

TEST(SceneShaftsTest, TorsionOfAFreeShaftWithAnEndDiscMatchesTheExactRoot) {
  // Free–free rod θ = A cos(kx) with a disc I_d at x = L: GJ θ'(L) = I_d ω² θ(L) gives
  // tan β = −μ β, β = ωL/c, c = √(G/ρ), μ = I_d/(ρ J_p L) (Timoshenko, Vibration Problems in
  // Engineering, §"torsional vibration of a shaft with a disc").
  const double d = 0.04, length = 1.0, mu = 1.0;
  const double jp = M_PI * std::pow(d, 4) / 32.0, g = kE / (2.0 * (1.0 + kNu));
  const Scene scene = ParseScene(ShaftScene(mu * kRho * jp * length), "shafts.toml");
  const VectorX lambda = Eigenvalues(MakeSystemModel(scene));
  // First root of sin β + μ β cos β = 0 in (π/2, π) by bisection.
  double lo = M_PI / 2.0, hi = M_PI;
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    (std::sin(mid) + mu * mid * std::cos(mid) > 0.0 ? lo : hi) = mid;
  }
  const double omega = lo * std::sqrt(g / kRho) / length;
  // Linear torsion elements with consistent mass: ω_h/ω − 1 ≈ (β/n)²/24 = 1.7e-5 at n = 100.
  EXPECT_LT(NearestRelative(lambda, omega * omega), 5e-5);
}

// Simply supported Timoshenko beam: w = W sin kx, ψ = Ψ cos kx, k = nπ/L in the Timoshenko
// equations give (ρAω² − κGAk²)(ρIω² − EIk² − κGA) = (κGAk)², a quadratic in ω² whose lower
// root is the bending mode n (Han, Benaroya & Wei, J. Sound Vib. 225 (1999) 935–988, the simply
// supported Timoshenko beam).
double PinnedTimoshenkoOmega2(int n, double length, double d) {
  const double g = kE / (2.0 * (1.0 + kNu));
  const double kappa = CalcShearCoefficient(CircularSection{d, 0.0}, kNu);
  const double area = M_PI * d * d / 4.0, inertia = M_PI * std::pow(d, 4) / 64.0;
  const double k = n * M_PI / length;
  const double a = kRho * area * kRho * inertia;
  const double b = kRho * area * (kE * inertia * k * k + kappa * g * area) +
                   kRho * inertia * kappa * g * area * k * k;
  const double c = kappa * g * area * kE * inertia * std::pow(k, 4);
  return (b - std::sqrt(b * b - 4.0 * a * c)) / (2.0 * a);
}

TEST(SceneShaftsTest, BendingOfAPinnedShaftConvergesToTheTimoshenkoClosedForm) {
  // 40 and 80 elements over L = 1 m (two sections), pinned by radial bearings of 1e13 N/m.
  const VectorX coarse = Eigenvalues(MakeSystemModel(ParseScene(ShaftScene(1e-3), "s.toml")));
  const VectorX fine = Eigenvalues(MakeSystemModel(ParseScene(ShaftScene(1e-3, 2), "s.toml")));
  const double h = 1.0 / 40.0;
  for (int n = 1; n <= 3; ++n) {
    const double omega2 = PinnedTimoshenkoOmega2(n, 1.0, 0.04);
    const double e_coarse = NearestRelative(coarse, omega2);
    const double e_fine = NearestRelative(fine, omega2);
    // Measured coefficient ≈ 0.04 of (kh)⁴ at 40 elements; refining must approach the closed
    // form (the error then falls at second order: measured log₂ ratio 2.07 for mode 3).
    EXPECT_LT(e_coarse, 0.05 * std::pow(n * M_PI * h, 4)) << "mode " << n;
    EXPECT_LT(e_fine, e_coarse) << "mode " << n;
    if (n == 3) {  // clear of the bearings' compliance (≈ 1e-8): the order shows
      EXPECT_GT(std::log2(e_coarse / e_fine), 1.9);
    }
  }
}

// The geared-shaft system built directly (as tests/benchmarks/micro/geared_shafts_benchmark.cpp):
// nodes along Z through the gear centre, the gear's 6×6 mass on the middle node.
BodyIndex AddShaft(SystemBuilder& b, const std::string& name, int nodes, const Vector3& centre,
                   const Matrix6& gear_mass) {
  const int gear = nodes / 2;
  const double h = 0.5 / (nodes - 1);
  std::vector<BodyIndex> ids;
  for (int i = 0; i < nodes; ++i) {
    ids.push_back(b.AddBody(name + std::to_string(i), i == gear ? gear_mass : Matrix6::Zero(),
                            centre + Vector3(0.0, 0.0, (i - gear) * h)));
  }
  ShaftBeam beam;
  beam.section.outer_diameter = 0.06;
  beam.material = ShaftMaterial::FromPoissonRatio(kE, kNu, kRho);
  beam.node_b = Vector3(0.0, 0.0, h);
  const MatrixX K = CalcShaftBeamStiffness(beam), M = CalcShaftBeamMass(beam);
  for (int i = 0; i + 1 < nodes; ++i) {
    b.AddElement(name + "-shaft" + std::to_string(i), ElementKind::kShaft, {ids[i], ids[i + 1]}, K,
                 MatrixX(), M);
  }
  Vector6 k_locating, k_floating;
  k_locating << 5e8, 5e8, 3e8, 1e5, 1e5, 0.0;
  k_floating << 5e8, 5e8, 0.0, 1e5, 1e5, 0.0;
  b.AddElement(name + "-a", ElementKind::kBearing, {ids.front()}, MatrixX(k_locating.asDiagonal()));
  b.AddElement(name + "-b", ElementKind::kBearing, {ids.back()}, MatrixX(k_floating.asDiagonal()));
  return ids[gear];
}

TEST(SceneShaftsTest, GearedShaftsSceneEqualsTheLibraryPath) {
  Scene scene = LoadScene("builtin:geared-shafts");
  scene.damping = {};  // compare the undamped M and K̄
  const SceneSystem built = BuildSceneSystem(scene);
  const SceneSystem pair = BuildSceneSystem(LoadScene("builtin:helical-pair"));
  const MatrixX Mp = pair.model.DenseMass();
  SystemBuilder b;
  const BodyIndex p = AddShaft(b, "p", 9, pair.centres[0], Matrix6(Mp.block<6, 6>(0, 0)));
  const BodyIndex w = AddShaft(b, "w", 9, pair.centres[1], Matrix6(Mp.block<6, 6>(6, 6)));
  b.AddMesh("mesh", p, w, pair.model.meshes()[0].G, pair.model.meshes()[0].core);
  const SystemModel library = b.Build();

  ASSERT_EQ(built.model.num_dofs(), library.num_dofs());
  EXPECT_EQ(built.model.num_dofs(), 108);
  // Same gear centres (pinion at the origin, wheel at a_w along +x).
  EXPECT_TRUE(built.centres[0].isApprox(pair.centres[0], 1e-15) || built.centres[0].isZero());
  EXPECT_TRUE(built.centres[1].isApprox(pair.centres[1], 1e-15));
  // Permutation invariants of M and K̄ and the full spectrum (the body order differs).
  SystemWorkspace ws_a(built.model, StorageKind::kDense), ws_b(library, StorageKind::kDense);
  const MatrixX Ka = AssembleMeanStiffness(built.model, ws_a);
  const MatrixX Kb = AssembleMeanStiffness(library, ws_b);
  EXPECT_NEAR(Ka.norm(), Kb.norm(), 1e-13 * Kb.norm());
  EXPECT_NEAR(built.model.DenseMass().norm(), library.DenseMass().norm(),
              1e-13 * library.DenseMass().norm());
  const VectorX la = Eigenvalues(built.model), lb = Eigenvalues(library);
  // 108 eigenvalues of the same pencil up to a permutation: round-off of the dense solver,
  // ε·‖K‖/min(M) relative to the largest.
  EXPECT_LT((la - lb).cwiseAbs().maxCoeff(), 1e-9 * lb.maxCoeff());
  for (int k = 0; k < la.size(); ++k) {
    if (lb(k) > 1e-6 * lb.maxCoeff()) {
      EXPECT_NEAR(la(k), lb(k), 1e-8 * lb(k)) << "eigenvalue " << k;
    }
  }
}

}  // namespace
}  // namespace geardyn
