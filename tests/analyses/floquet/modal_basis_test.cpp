// kAuto on a large system (issue 12): ≥ 200 DOF switch to the modal projection, whose basis must
// see the mesh modes that drive the principal instabilities. Truth: the full exact step product
// (kExactSteps on all 204 DOFs: exact to round-off) on the same small chart of mesh frequencies
// around the principal resonance f_m = 2 f_p of the mode with the largest mesh strain energy.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "floquet_test_support.hpp"
#include "geardyn/analyses/modal.hpp"

namespace geardyn::test {
namespace {

FloquetResult RunFloquet(const SystemModel& model, FloquetMethod method, double mesh_hz) {
  FloquetOptions o;
  o.mesh_frequency_hz = mesh_hz;
  o.method = method;
  o.tolerance = 1e-6;
  // One 204-DOF system (its blocks would each fall below the 200-DOF switch).
  o.split_blocks = false;
  return ComputeFloquet(model, o);
}

// The natural frequency [Hz] of the mode with the largest mesh strain-energy fraction.
double MeshModeHz(const SystemModel& model) {
  ModalOptions mo;
  mo.method = ModalMethod::kDense;
  const ModalResult r = ComputeModes(model, mo);
  int mesh_column = -1;
  for (std::size_t c = 0; c < r.strain_names.size(); ++c) {
    if (r.strain_names[c] == "mesh:mesh") mesh_column = static_cast<int>(c);
  }
  EXPECT_GE(mesh_column, 0);
  Eigen::Index best = 0;
  r.strain_fractions.col(mesh_column).maxCoeff(&best);
  return r.frequencies_hz[best];
}

TEST(ModalBasisTest, AutoFindsTheMeshModeTongueOfTheFullExactPath) {
  // 204 DOFs, damped shafts (β = 2e-6 s) and mesh (c_m = 600 N·s/m), ±25 % rectangular wave.
  const SystemModel model = GearedShafts(16, HandSpurWaveCore(600.0), 2e-6);
  ASSERT_GE(model.num_dofs(), 200);
  const double f_mesh_mode = MeshModeHz(model);
  // A small chart across the principal tongue f_m = 2 f_p (its width ≈ ±Δk/(2k̄) = ±25 %·f_m/2).
  int unstable_exact = 0, agree = 0, points = 0, projected = 0;
  for (const double ratio : {1.5, 1.7, 1.85, 1.95, 2.0, 2.05, 2.15, 2.3, 2.5}) {
    const double hz = ratio * f_mesh_mode;
    SCOPED_TRACE("f_m = " + std::to_string(hz) + " Hz (" + std::to_string(ratio) + " f_p)");
    const FloquetResult full = RunFloquet(model, FloquetMethod::kExactSteps, hz);
    const FloquetResult automatic = RunFloquet(model, FloquetMethod::kAuto, hz);
    // kAuto projects, or solves the full system when the projection's estimate of max|λ| cannot
    // settle the verdict (inside the tongue, docs/design.md "Floquet kAuto by cost").
    ASSERT_TRUE(automatic.method_used == FloquetMethod::kModalProjection ||
                automatic.method_used == FloquetMethod::kExactSteps)
        << ToString(automatic.method_used);
    projected += automatic.method_used == FloquetMethod::kModalProjection;
    ASSERT_NE(full.verdict, FloquetVerdict::kUndetermined) << full.summary.message;
    EXPECT_NE(automatic.verdict, FloquetVerdict::kUndetermined) << automatic.summary.message;
    EXPECT_EQ(automatic.verdict, full.verdict)
        << "max|λ| auto " << automatic.max_abs_multiplier << " ± "
        << automatic.summary.error_estimate << ", full " << full.max_abs_multiplier;
    // The basis covered the mesh mode: the dominant multiplier is the full path's.
    EXPECT_NEAR(automatic.max_abs_multiplier, full.max_abs_multiplier,
                automatic.summary.error_estimate + full.summary.error_estimate + 1e-9);
    unstable_exact += full.verdict == FloquetVerdict::kUnstable;
    agree += automatic.verdict == full.verdict;
    ++points;
  }
  EXPECT_GE(unstable_exact, 2);  // the chart does cross the tongue
  EXPECT_GE(projected, 5);       // outside the tongue the projection answers
  EXPECT_EQ(agree, points);
}

}  // namespace
}  // namespace geardyn::test
