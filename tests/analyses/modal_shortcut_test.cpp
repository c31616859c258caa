// ComputeModes computes mode vectors only for the outputs that use them: a damped model asked
// for frequencies only (no shapes, no energy fractions, no damping ratios) is solved for
// eigenvalues only, and gives the same frequencies as the full path with vectors.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

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

// The dense path with vectors and 0 < num_modes < n computes only those (few-modes solver,
// symmetric_eigen_subset.hpp): the same frequencies and, up to sign, the same M-orthonormal
// shapes as the full dense solve (num_modes = 0, all n), the lowest and nearest a shift.
TEST(ModalShortcutTest, DenseFewModesEqualTheFullSolveOnTheGearedShafts) {
  const SystemModel model = MakeSystemModel(LoadScene("builtin:geared-shafts"));
  const int n = model.num_dofs();
  ModalOptions all;
  all.method = ModalMethod::kDense;
  all.compute_shapes = true;
  const ModalResult full = ComputeModes(model, all);
  ASSERT_TRUE(full.summary.ok()) << full.summary.message;
  ASSERT_EQ(full.frequencies_hz.size(), n);
  const MatrixX M(model.mass());
  const double top = full.frequencies_hz.maxCoeff();
  // Shifted window: σ = ω² of mode 40 (0-based) a little above it; the 10 nearest start at 35
  // or 36 depending on the spectrum, found by the definition (nearest |λ − σ|) on the full one.
  const double sigma = 1.0001 * full.eigenvalues(40);
  for (const bool shifted : {false, true}) {
    ModalOptions few = all;
    few.num_modes = shifted ? 10 : 20;
    if (shifted) few.shift = sigma;
    const ModalResult r = ComputeModes(model, few);
    ASSERT_TRUE(r.summary.ok()) << r.summary.message;
    EXPECT_EQ(r.summary.counters.at("subset_solver"), 1);  // the few-modes solver ran
    ASSERT_EQ(r.frequencies_hz.size(), few.num_modes);
    ASSERT_EQ(r.shapes.cols(), few.num_modes);
    // First index of the window in the full spectrum: the definition, evaluated on `full`.
    Eigen::Index first = 0;
    if (shifted) {
      while (first + few.num_modes < n &&
             std::abs(full.eigenvalues(first + few.num_modes) - sigma) <
                 std::abs(full.eigenvalues(first) - sigma)) {
        ++first;
      }
      EXPECT_GT(first, 0);
    }
    const MatrixX gram = r.shapes.transpose() * M * r.shapes;
    EXPECT_LE((gram - MatrixX::Identity(few.num_modes, few.num_modes)).cwiseAbs().maxCoeff(),
              1e-10);
    for (int k = 0; k < few.num_modes; ++k) {
      EXPECT_NEAR(r.frequencies_hz(k), full.frequencies_hz(first + k), kTol * top) << "mode " << k;
      // ‖projection onto the full solve's eigenspace‖²_M = 1: the same shape up to sign, or a
      // shape inside the same repeated eigenspace (the shafts' bending pairs).
      double in_space = 0.0;
      for (const std::vector<int>& group : full.multiplicity_groups) {
        if (std::find(group.begin(), group.end(), first + k) == group.end()) continue;
        for (const int j : group) {
          const double overlap = r.shapes.col(k).dot(M * full.shapes.col(j));
          in_space += overlap * overlap;
        }
      }
      EXPECT_NEAR(in_space, 1.0, 1e-8) << "mode " << k;
    }
    EXPECT_EQ(r.num_rigid_body_modes, shifted ? 0 : full.num_rigid_body_modes);
  }
}

// The geared shafts with 50 elements per shaft (612 DOFs) have repeated bending frequencies (the
// two bending planes of an axisymmetric shaft). Lanczos can return such a pair once (found at
// 3208 Hz) and the next mode in its place with info = 0. Truth: the full dense solve. Forced
// ARPACK either returns the dense spectrum or reports the miss (Sylvester inertia count); kAuto
// always returns the dense spectrum (it re-solves densely after a miss).
TEST(ModalShortcutTest, ArpackNeverReturnsAMissedRepeatedModeAsSuccess) {
  const SystemModel model =
      MakeSystemModel(LoadScene("builtin:geared-shafts", {"shaft.input.sections.0.elements=50",
                                                          "shaft.output.sections.0.elements=50"}));
  ModalOptions all;
  all.method = ModalMethod::kDense;
  all.compute_energy_fractions = false;
  const ModalResult dense = ComputeModes(model, all);
  ASSERT_TRUE(dense.summary.ok()) << dense.summary.message;
  const int wanted = 20;
  const double top = dense.frequencies_hz(wanted - 1);
  for (const ModalMethod method : {ModalMethod::kArpack, ModalMethod::kAuto}) {
    ModalOptions few = all;
    few.method = method;
    few.num_modes = wanted;
    const ModalResult r = ComputeModes(model, few);
    const bool forced = method == ModalMethod::kArpack;
    if (!r.summary.ok()) {
      EXPECT_TRUE(forced) << "kAuto must fall back to the dense solver: " << r.summary.message;
      EXPECT_NE(r.summary.message.find("Lanczos missed"), std::string::npos) << r.summary.message;
      continue;
    }
    ASSERT_EQ(r.frequencies_hz.size(), wanted);
    for (int k = 0; k < wanted; ++k) {
      EXPECT_NEAR(r.frequencies_hz(k), dense.frequencies_hz(k), 1e-8 * top)
          << "mode " << k << (forced ? " (arpack)" : " (auto)");
    }
  }
}

}  // namespace
}  // namespace geardyn
