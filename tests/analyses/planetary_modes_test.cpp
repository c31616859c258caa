// Planetary mode structure (Lin & Parker 1999, J. Sound Vib. 228(1) 109–128): for N equally
// spaced identical planets with isotropic supports, the planar model (x, y, θz per body) has 6
// rotational modes (multiplicity 1), 6 translational pairs (multiplicity 2) and 3 planet-mode
// frequencies of multiplicity N − 3.
//
// 6-DOF spur model, derived here the same way (independent of the labelling code): a spur mesh
// with its load at mid face acts in the plane (δ_η on x, y, θz) and rocks only through δ_ζ (θx,
// θy), so the in-plane part is Lin & Parker's model and the out-of-plane part (z, θx, θy per body)
// splits by the harmonic k of the planet index (cyclic group C_N): central members carry only
// k = 0 (z) and k = ±1 (θx, θy). k = 0: sun z and ring z on their supports, carrier z with the
// in-phase planet z (4 modes, central members move: rotational-axial) and the two in-phase planet
// tilts, which meet central members only through their tilts (zero at k = 0), so they are planet
// modes with the frequencies of the k ≥ 2 tilts; k = ±1: 3 central tilt pairs + 3 planet pairs
// (6 translational-tilting pairs); k = 2 … N−2: planet z and two tilts (N − 3 copies). Total:
// 10 rotational, 12 translational pairs, 4 planet frequencies of multiplicity N − 3 (3 in-plane,
// planet z) and 2 of multiplicity N − 2 (planet tilts).
#include <gtest/gtest.h>

#include <map>
#include <string>
#include <vector>

#include "geardyn/analyses/modal.hpp"
#include "geardyn/models/scene/scene_reader.hpp"
#include "geardyn/models/system/scene_system.hpp"
#include "models/system/planetary_scene.hpp"

namespace geardyn {
namespace {

using testing::PlanetaryFixture;
using testing::PlanetarySceneText;

ModalResult Modes(const PlanetaryFixture& f) {
  const SystemModel model = MakeSystemModel(ParseScene(PlanetarySceneText(f), "t.toml"));
  ModalOptions options;
  options.method = ModalMethod::kDense;
  options.multiplicity_rel_tol = 1e-7;
  ModalResult r = ComputeModes(model, options);
  EXPECT_TRUE(r.summary.ok()) << r.summary.message;
  EXPECT_EQ(r.num_rigid_body_modes, 0);
  return r;
}

// (type, multiplicity) → number of multiplicity groups with that label and size.
std::map<std::pair<PlanetaryModeType, int>, int> GroupCounts(const ModalResult& r) {
  std::map<std::pair<PlanetaryModeType, int>, int> counts;
  for (const std::vector<int>& g : r.multiplicity_groups) {
    const PlanetaryModeType t = r.planetary_labels.at(static_cast<std::size_t>(g.front()));
    for (int k : g) EXPECT_EQ(r.planetary_labels[static_cast<std::size_t>(k)], t);
    ++counts[{t, static_cast<int>(g.size())}];
  }
  return counts;
}

// Expected number of multiplicity groups per (label, size).
using Structure = std::map<std::pair<PlanetaryModeType, int>, int>;

void ExpectStructure(const ModalResult& r, int n_planets, Structure want) {
  std::erase_if(want, [](const auto& e) { return e.first.second <= 0 || e.second == 0; });
  EXPECT_EQ(GroupCounts(r), want) << "N = " << n_planets;
}

Structure Planar(int n) {
  return {{{PlanetaryModeType::kRotational, 1}, 6},
          {{PlanetaryModeType::kTranslational, 2}, 6},
          {{PlanetaryModeType::kPlanet, n - 3}, 3}};
}

Structure SixDofSpur(int n) {
  Structure s = {{{PlanetaryModeType::kRotational, 1}, 10},
                 {{PlanetaryModeType::kTranslational, 2}, 12}};
  if (n > 3) s[{PlanetaryModeType::kPlanet, n - 3}] += 4;
  s[{PlanetaryModeType::kPlanet, n - 2}] += 2;
  return s;
}

TEST(PlanetaryModesTest, PlanarModelHasLinParkerStructure) {
  for (int n : {3, 4, 5}) {
    PlanetaryFixture f;
    f.planets = n;
    f.planar = true;
    const ModalResult r = Modes(f);
    ASSERT_EQ(r.frequencies_hz.size(), 3 * (n + 3));
    ExpectStructure(r, n, Planar(n));
  }
}

TEST(PlanetaryModesTest, SixDofSpurModelHasDerivedStructure) {
  for (int n : {3, 4, 5}) {
    PlanetaryFixture f;
    f.planets = n;
    const ModalResult r = Modes(f);
    ASSERT_EQ(r.frequencies_hz.size(), 6 * (n + 3));
    ExpectStructure(r, n, SixDofSpur(n));
  }
}

TEST(PlanetaryModesTest, BlankenshipSinghMeshesKeepTheStructure) {
  PlanetaryFixture f;
  f.planets = 4;
  f.model = "blankenship_singh";
  ExpectStructure(Modes(f), 4, SixDofSpur(4));
}

TEST(PlanetaryModesTest, RotatingThePlanetSetChangesNoFrequency) {
  // The supports are isotropic: turning every planet by the same angle is a rigid rotation of the
  // whole set (the assembly condition only constrains differences of angles).
  for (int n : {3, 4, 5}) {
    PlanetaryFixture f;
    f.planets = n;
    const ModalResult ref = Modes(f);
    f.angles_deg.clear();
    for (int k = 0; k < n; ++k) f.angles_deg.push_back(23.0 + 360.0 * k / n);
    const ModalResult turned = Modes(f);
    ASSERT_EQ(turned.frequencies_hz.size(), ref.frequencies_hz.size());
    for (Eigen::Index k = 0; k < ref.frequencies_hz.size(); ++k) {
      EXPECT_NEAR(turned.frequencies_hz(k), ref.frequencies_hz(k), 1e-9 * ref.frequencies_hz(k))
          << "N = " << n << ", mode " << k;
    }
    EXPECT_EQ(GroupCounts(turned), GroupCounts(ref));
  }
}

TEST(PlanetaryModesTest, UnequalSpacingBreaksTheStructure) {
  // 0°, 120°, 237° (assemblable: 120 · 237/360 = 79): no longer cyclically symmetric, so the
  // translational pairs split and modes mix central rotation and translation.
  PlanetaryFixture f;
  f.angles_deg = {0.0, 120.0, 237.0};
  f.planar = true;
  const ModalResult r = Modes(f);
  int mixed = 0;
  for (PlanetaryModeType t : r.planetary_labels) mixed += t == PlanetaryModeType::kMixed;
  EXPECT_GT(mixed, 0);
  for (const std::vector<int>& g : r.multiplicity_groups) EXPECT_EQ(g.size(), 1u);
}

TEST(PlanetaryModesTest, NoPlanetsNoPlanetaryLabels) {
  const SystemModel model = MakeSystemModel(LoadScene("builtin:kahraman-blankenship-rig"));
  const ModalResult r = ComputeModes(model);
  EXPECT_TRUE(r.planetary_labels.empty());
  EXPECT_EQ(ToString(PlanetaryModeType::kPlanet), std::string("planet"));
}

}  // namespace
}  // namespace geardyn
