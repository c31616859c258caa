// Mode matching by the mass-weighted MAC (mode_matching.hpp) against invariants that fix the
// answer: a model matched with itself (MAC = 1, Δf = 0), with its own modes permuted, with a
// mode removed (absent, best MAC 0 by M-orthogonality), and with the basis of a repeated-frequency
// eigenspace rotated (the subspace MAC does not depend on the basis).
#include "geardyn/analyses/mode_matching.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "geardyn/models/scene/scene_reader.hpp"
#include "geardyn/models/system/scene_system.hpp"

namespace geardyn {
namespace {

// M-orthonormal dense eigenvectors: products of O(n) terms, n ≤ 60.
constexpr double kTol = 1e-10;

struct Modes {
  SystemModel model;
  ModalResult result;
};

Modes ComputeSceneModes(const std::string& scene, int count) {
  SceneSystemOptions so;
  so.transmission_error = false;
  Modes m{MakeSystemModel(LoadScene(scene), so), {}};
  ModalOptions options;
  options.method = ModalMethod::kDense;
  options.num_modes = count;
  options.compute_shapes = true;
  m.result = ComputeModes(m.model, options);
  return m;
}

TEST(ModeMatchingTest, AModelMatchedWithItselfHasMacOneAndNoDifference) {
  const Modes m = ComputeSceneModes("builtin:helical-pair", 12);
  const ModeMatching match = MatchModesByMac(m.result, m.result, m.model.mass());
  ASSERT_EQ(match.matches.size(), 12u);
  EXPECT_EQ(match.num_matched, 12);
  EXPECT_TRUE(match.extra.empty());
  for (const ModeMatch& x : match.matches) {
    EXPECT_EQ(x.other, x.reference);
    EXPECT_NEAR(x.mac, 1.0, kTol);
    EXPECT_EQ(x.relative_difference, 0.0);
  }
  EXPECT_EQ(match.max_abs_relative_difference, 0.0);
}

TEST(ModeMatchingTest, PermutedModesAreFoundByShape) {
  const Modes m = ComputeSceneModes("builtin:helical-pair", 12);
  ModalResult reversed = m.result;
  const int n = static_cast<int>(m.result.frequencies_hz.size());
  for (int k = 0; k < n; ++k) {
    reversed.frequencies_hz(k) = m.result.frequencies_hz(n - 1 - k);
    reversed.shapes.col(k) = -m.result.shapes.col(n - 1 - k);  // the sign does not matter
  }
  const ModeMatching match = MatchModesByMac(m.result, reversed, m.model.mass());
  for (const ModeMatch& x : match.matches) {
    EXPECT_EQ(x.other, n - 1 - x.reference);
    EXPECT_NEAR(x.mac, 1.0, kTol);
    EXPECT_EQ(x.relative_difference, 0.0);
  }
}

TEST(ModeMatchingTest, AMissingModeIsAbsentWithBestMacZero) {
  const Modes m = ComputeSceneModes("builtin:helical-pair", 12);
  ModalResult fewer = m.result;
  const int removed = 5;
  const int n = static_cast<int>(m.result.frequencies_hz.size());
  fewer.frequencies_hz.resize(n - 1);
  fewer.shapes.resize(m.result.shapes.rows(), n - 1);
  for (int k = 0, j = 0; k < n; ++k) {
    if (k == removed) continue;
    fewer.frequencies_hz(j) = m.result.frequencies_hz(k);
    fewer.shapes.col(j++) = m.result.shapes.col(k);
  }
  const ModeMatching match = MatchModesByMac(m.result, fewer, m.model.mass());
  EXPECT_EQ(match.num_matched, n - 1);
  EXPECT_EQ(match.matches[removed].other, -1);
  EXPECT_TRUE(std::isnan(match.matches[removed].other_hz));
  EXPECT_NEAR(match.matches[removed].mac, 0.0, kTol);  // M-orthogonal to every kept mode
}

TEST(ModeMatchingTest, RepeatedFrequenciesAreComparedAsSubspaces) {
  // The planetary set's planet modes come in degenerate pairs; rotating the basis of each pair
  // changes the individual MACs but not the subspace's.
  const Modes m = ComputeSceneModes("builtin:planetary-lin-parker", 30);
  ModalResult rotated = m.result;
  int pairs = 0;
  for (const std::vector<int>& group : m.result.multiplicity_groups) {
    if (group.size() != 2) continue;
    ++pairs;
    const double c = std::cos(0.7), s = std::sin(0.7);
    const VectorX a = m.result.shapes.col(group[0]), b = m.result.shapes.col(group[1]);
    rotated.shapes.col(group[0]) = c * a + s * b;
    rotated.shapes.col(group[1]) = -s * a + c * b;
  }
  ASSERT_GT(pairs, 0) << "the planetary scene should have degenerate mode pairs";
  const ModeMatching match = MatchModesByMac(m.result, rotated, m.model.mass());
  EXPECT_EQ(match.num_matched, static_cast<int>(m.result.frequencies_hz.size()));
  for (const ModeMatch& x : match.matches) {
    EXPECT_NEAR(x.mac, 1.0, kTol) << "mode " << x.reference;
    EXPECT_NEAR(x.relative_difference, 0.0, 1e-6) << "mode " << x.reference;
  }
}

TEST(ModeMatchingTest, InvalidInputThrows) {
  const Modes m = ComputeSceneModes("builtin:helical-pair", 4);
  ModeMatchingOptions bad;
  bad.mac_threshold = 0.0;
  EXPECT_THROW(MatchModesByMac(m.result, m.result, m.model.mass(), bad), InvalidInput);
  ModalResult no_shapes = m.result;
  no_shapes.shapes.resize(0, 0);
  EXPECT_THROW(MatchModesByMac(m.result, no_shapes, m.model.mass()), InvalidInput);
}

}  // namespace
}  // namespace geardyn
