// ComputeModes computes mode vectors only for the outputs that use them: a damped model asked
// for frequencies only (no shapes, no energy fractions, no damping ratios) is solved for
// eigenvalues only, and gives the same frequencies as the full path with vectors.
#include <gtest/gtest.h>

#include "geardyn/analyses/modal.hpp"
#include "geardyn/models/scene/scene_reader.hpp"
#include "geardyn/models/system/scene_system.hpp"

namespace geardyn {
namespace {

// Same pencil, two LAPACK-style paths (tridiagonal QR with and without accumulated vectors):
// the eigenvalues agree to round-off relative to the largest.
constexpr double kTol = 1e-11;

void ExpectShortcutEqualsFullPath(const SystemModel& model, ModalMethod method, int num_modes) {
  ModalOptions full;
  full.method = method;
  full.num_modes = num_modes;
  ModalOptions shortcut = full;
  shortcut.compute_energy_fractions = false;
  shortcut.compute_damping_ratios = false;
  const ModalResult a = ComputeModes(model, full);
  const ModalResult b = ComputeModes(model, shortcut);
  ASSERT_TRUE(a.summary.ok()) << a.summary.message;
  ASSERT_TRUE(b.summary.ok()) << b.summary.message;
  // The full path computed vectors (residual estimate, damping ratios); the shortcut did not.
  EXPECT_GT(a.summary.error_estimate, 0.0);
  EXPECT_GT(a.modal_damping_ratios.size(), 0);
  EXPECT_EQ(b.summary.error_estimate, 0.0);
  EXPECT_EQ(b.modal_damping_ratios.size(), 0);
  ASSERT_EQ(a.frequencies_hz.size(), b.frequencies_hz.size());
  const double top = a.frequencies_hz.maxCoeff();
  for (int k = 0; k < a.frequencies_hz.size(); ++k) {
    EXPECT_NEAR(a.frequencies_hz(k), b.frequencies_hz(k), kTol * top) << "mode " << k;
  }
  EXPECT_EQ(a.num_rigid_body_modes, b.num_rigid_body_modes);
  // The damping classification does not need the vectors below 2000 DOFs.
  EXPECT_EQ(a.damping_kind, b.damping_kind);
}

TEST(ModalShortcutTest, DampedModelFrequenciesOnlySkipTheVectorsDense) {
  const SystemModel model = MakeSystemModel(LoadScene("builtin:geared-shafts"));
  ASSERT_GT(model.constant_damping().nonZeros(), 0);  // the scene's modal damping
  ExpectShortcutEqualsFullPath(model, ModalMethod::kDense, 0);
  ExpectShortcutEqualsFullPath(model, ModalMethod::kDense, 10);
}

TEST(ModalShortcutTest, DampedModelFrequenciesOnlySkipTheVectorsArpack) {
  const SystemModel model = MakeSystemModel(LoadScene("builtin:geared-shafts"));
  ExpectShortcutEqualsFullPath(model, ModalMethod::kArpack, 12);
}

}  // namespace
}  // namespace geardyn
