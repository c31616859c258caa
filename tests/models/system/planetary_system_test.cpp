// A planetary set as a SystemModel: placement, mesh lines of centres, body roles, Parker & Lin
// mesh phasing, static load sharing and torque ratios, and the torsional fixed-carrier modes in
// closed form.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "geardyn/analyses/modal.hpp"
#include "geardyn/models/scene/scene_reader.hpp"
#include "geardyn/models/system/scene_system.hpp"
#include "geardyn/system/static_deflection.hpp"
#include "models/system/planetary_scene.hpp"

namespace geardyn {
namespace {

using testing::PlanetaryFixture;
using testing::PlanetarySceneText;

constexpr double kPi = std::numbers::pi;
constexpr double kGeomTol = 1e-12;   // m, rad: closed-form placement of exact data
constexpr double kStaticTol = 1e-8;  // relative: dense static solve of a ~60-DOF system

// Fixture data (planetary_scene.hpp): m = 2 mm, α = 20°, z = 40 / 20 / 80.
const double kBaseSun = 0.002 * 40 / 2 * std::cos(20.0 * kPi / 180.0);
const double kBasePlanet = 0.002 * 20 / 2 * std::cos(20.0 * kPi / 180.0);

double Wrap(double x) {
  x = std::fmod(x, 2.0 * kPi);
  return x < 0.0 ? x + 2.0 * kPi : x;
}
// Distance of two angles on the circle.
double AngleGap(double a, double b) { return std::abs(std::remainder(a - b, 2.0 * kPi)); }

const SystemMesh& MeshNamed(const SystemModel& model, const std::string& name) {
  for (const SystemMesh& m : model.meshes()) {
    if (m.name == name) return m;
  }
  ADD_FAILURE() << "no mesh " << name;
  return model.meshes().front();
}

TEST(PlanetarySystemTest, PlacesPlanetsAndMeshesAtTheirAngles) {
  PlanetaryFixture f;
  f.angles_deg = {10.0, 130.0, 250.0};
  const Scene scene = ParseScene(PlanetarySceneText(f), "t.toml");
  const SceneSystem sys = BuildSceneSystem(scene);
  const PlanetaryDef& p = scene.planetaries[0];
  const DofMap& dofs = sys.model.dof_map();
  for (std::size_t g = 0; g < scene.gears.size(); ++g) {
    const std::string& name = scene.gears[g].name;
    const BodyRole role = dofs.body_role(dofs.GetBody(name));
    if (name == "sun" || name == "ring" || name == "carrier") {
      EXPECT_LE(sys.centres[g].norm(), kGeomTol) << name;  // coaxial with the sun (the origin)
      EXPECT_EQ(role, name == "sun" ? BodyRole::kSun
                                    : (name == "ring" ? BodyRole::kRing : BodyRole::kCarrier));
    }
  }
  for (std::size_t n = 0; n < 3; ++n) {
    const double psi = (10.0 + 120.0 * static_cast<double>(n)) * kPi / 180.0;
    const BodyIndex b = dofs.GetBody(p.planets[n]);
    EXPECT_EQ(dofs.body_role(b), BodyRole::kPlanet);
    EXPECT_NEAR(sys.centres[b].x(), 0.060 * std::cos(psi), kGeomTol);
    EXPECT_NEAR(sys.centres[b].y(), 0.060 * std::sin(psi), kGeomTol);
    for (std::size_t k = 0; k < scene.meshes.size(); ++k) {
      if (scene.meshes[k].name == p.sun_meshes[n]) {
        EXPECT_LE(AngleGap(sys.mesh_angles[k], psi), 1e-12);  // sun → planet
      }
      if (scene.meshes[k].name == p.ring_meshes[n]) {
        EXPECT_LE(AngleGap(sys.mesh_angles[k], psi + kPi), 1e-12);  // planet → ring centre
      }
    }
  }
  EXPECT_EQ(dofs.num_planets(), 3);
}

TEST(PlanetarySystemTest, MeshPhasesFollowParkerAndLin) {
  // Parker & Lin (2004): sun–planet n lags z_s ψ_n/2π cycles, ring–planet n −z_r ψ_n/2π cycles
  // (relative to planet 0's meshes); geardyn stores φ = −2π·lag, and every planetary mesh has the
  // same mesh frequency (phase ratio 1). The ring formula is not the one the code uses (it adds
  // the sun–ring phase Δ to the sun phase): they agree through the assembly condition.
  for (int sign : {1, -1}) {
    PlanetaryFixture f;
    f.planets = 5;
    f.torque = sign * 100.0;
    const Scene scene = ParseScene(PlanetarySceneText(f), "t.toml");
    const SystemModel model = MakeSystemModel(scene);
    const PlanetaryDef& p = scene.planetaries[0];
    const double ring0 = MeshNamed(model, p.ring_meshes[0]).phase_offset;
    for (int n = 0; n < 5; ++n) {
      const double psi = 2.0 * kPi * n / 5.0;
      const SystemMesh& sun = MeshNamed(model, p.sun_meshes[n]);
      const SystemMesh& ring = MeshNamed(model, p.ring_meshes[n]);
      EXPECT_LE(AngleGap(sun.phase_offset, Wrap(-sign * 40.0 * psi)), 1e-9) << n;
      EXPECT_LE(AngleGap(ring.phase_offset, Wrap(ring0 + sign * 80.0 * psi)), 1e-9) << n;
      // Standard gears, even z_p = 20: the ring mesh is half a mesh cycle from the sun mesh.
      EXPECT_LE(AngleGap(ring.phase_offset - sun.phase_offset, kPi), 1e-9) << n;
      EXPECT_DOUBLE_EQ(sun.phase_ratio, ring.phase_ratio);
    }
  }
}

TEST(PlanetarySystemTest, StaticLoadSharingAndTorqueRatios) {
  // Sun free in rotation (torque T), ring and carrier held by torsional supports: by symmetry the
  // N planets share equally, F = T/(N a_s) on every sun mesh (sun moment balance), F on every
  // ring mesh (planet moment balance), no net radial force on the sun, ring reaction torque
  // T z_r/z_s and carrier reaction T (1 + z_r/z_s), all three summing to zero with T (moment
  // balance of the whole set, a check of every mesh frame).
  for (bool planar : {true, false}) {
    for (int n_planets : {3, 4, 5}) {
      PlanetaryFixture f;
      f.planets = n_planets;
      f.planar = planar;
      f.sun_torsion = 0.0;
      f.torque = 200.0;
      const Scene scene = ParseScene(PlanetarySceneText(f), "t.toml");
      const SystemModel model = MakeSystemModel(scene);
      const StaticDeflectionResult r = SolveStaticDeflection(model);
      ASSERT_EQ(r.num_rigid_modes, 0);
      const double force = 200.0 / (n_planets * kBaseSun);
      for (const MeshStaticState& m : r.meshes) {
        EXPECT_NEAR(m.force_eta, force, kStaticTol * force) << m.name;
      }
      double ring_torque = 0.0, carrier_torque = 0.0;
      for (std::size_t e = 0; e < model.elements().size(); ++e) {
        const SystemElement& el = model.elements()[e];
        const VectorX& fe = r.element_forces[e];  // K_e q̄_e: the body pushes the support
        if (el.name == "sun-support") {
          EXPECT_LE(std::hypot(fe(0), fe(1)), kStaticTol * force) << "net radial force on sun";
        }
        if (el.name == "ring-support") ring_torque = fe(5);
        if (el.name == "carrier-support") carrier_torque = fe(5);
      }
      EXPECT_NEAR(std::abs(ring_torque), 200.0 * 80.0 / 40.0, kStaticTol * 200.0);
      EXPECT_NEAR(std::abs(carrier_torque), 200.0 * (1.0 + 80.0 / 40.0), kStaticTol * 200.0);
      EXPECT_NEAR(200.0 - ring_torque - carrier_torque, 0.0, kStaticTol * 200.0)
          << "supports react the applied torque";
    }
  }
}

TEST(PlanetarySystemTest, TorsionalFixedCarrierModesInClosedForm) {
  // Torsional meshes (θz only), ring and carrier fixed: restrict to the sun's and planets' θz.
  // In-phase planets φ: M = diag(J_s, N J_p), K = N [[k_s a_s², k_s a_s a_p],
  // [k_s a_s a_p, (k_s + k_r) a_p²]] (two rotational modes); planets against each other with the
  // sun at rest: ω² = (k_s + k_r) a_p² / J_p, multiplicity N − 1.
  const double ks = 4e8, kr = 6e8, Js = 8e-4, Jp = 6e-5;
  for (int n_planets : {3, 4, 5}) {
    PlanetaryFixture f;
    f.planets = n_planets;
    f.model = "torsional";
    f.sun_torsion = 0.0;  // the sun's θz is held only by the meshes
    std::vector<std::string> overrides;
    overrides.push_back("mesh.sun-planet.parameters={form=\"table\", stiffness=[" +
                        std::to_string(ks) + "]}");
    overrides.push_back("mesh.planet-ring.parameters={form=\"table\", stiffness=[" +
                        std::to_string(kr) + "]}");
    const Scene scene = ParseScene(PlanetarySceneText(f), "t.toml", overrides);
    const SystemModel full = MakeSystemModel(scene);
    std::vector<int> keep;
    const DofMap& dofs = full.dof_map();
    keep.push_back(dofs.dof(dofs.GetBody("sun"), BodyDof::kThetaZ));
    for (const std::string& planet : scene.planetaries[0].planets) {
      keep.push_back(dofs.dof(dofs.GetBody(planet), BodyDof::kThetaZ));
    }
    std::sort(keep.begin(), keep.end());
    const SystemModel model = full.Restrict(keep);
    ModalOptions options;
    options.method = ModalMethod::kDense;
    const ModalResult modes = ComputeModes(model, options);
    ASSERT_TRUE(modes.summary.ok()) << modes.summary.message;

    const double N = n_planets;
    const double as = kBaseSun, ap = kBasePlanet;
    const double K11 = N * ks * as * as, K12 = N * ks * as * ap, K22 = N * (ks + kr) * ap * ap;
    const double M11 = Js, M22 = N * Jp;
    const double b = K11 * M22 + K22 * M11, c = K11 * K22 - K12 * K12, a = M11 * M22;
    const double disc = std::sqrt(b * b - 4.0 * a * c);
    std::vector<double> want = {(b - disc) / (2.0 * a), (b + disc) / (2.0 * a)};
    for (int k = 0; k < n_planets - 1; ++k) want.push_back((ks + kr) * ap * ap / Jp);
    std::sort(want.begin(), want.end());
    ASSERT_EQ(modes.eigenvalues.size(), static_cast<Eigen::Index>(want.size()));
    for (std::size_t k = 0; k < want.size(); ++k) {
      EXPECT_NEAR(modes.eigenvalues(static_cast<Eigen::Index>(k)), want[k], 1e-10 * want[k])
          << "N = " << n_planets << ", mode " << k;
    }
    // Labels: the two in-phase modes move the sun (rotational), the others leave it at rest.
    int rotational = 0, planet = 0;
    for (PlanetaryModeType t : modes.planetary_labels) {
      rotational += t == PlanetaryModeType::kRotational;
      planet += t == PlanetaryModeType::kPlanet;
    }
    EXPECT_EQ(rotational, 2);
    EXPECT_EQ(planet, n_planets - 1);
  }
}

}  // namespace
}  // namespace geardyn
