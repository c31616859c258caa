// A runout as sidebands (RunoutForm, MakeRunoutSidebands): the linear core's ε is the table of ε
// without the runout plus two lines over the hunting period. Truths: the exact pointwise ε of
// TransmissionErrorModel::CalcTransmissionError at the table's nodes over the whole 997/991
// hunting period; the linear HB of a built-in scene with the runout as a table (the dense path
// that existed before) against the same scene with the runout as sidebands (sparse harmonics),
// equal to round-off where both exist; and the refusals kept for what has no sparse form.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "geardyn/analyses/harmonic_balance.hpp"
#include "geardyn/models/scene/mesh_model.hpp"
#include "geardyn/models/scene/mesh_transmission_error.hpp"
#include "geardyn/models/scene/scene_reader.hpp"
#include "geardyn/models/system/scene_system.hpp"
#include "support/expect_throws.hpp"

namespace geardyn {
namespace {

const std::vector<std::string> kCoprime = {"gear.pinion.teeth=997", "gear.wheel.teeth=991"};

std::vector<std::string> With(std::vector<std::string> a, const std::vector<std::string>& b) {
  a.insert(a.end(), b.begin(), b.end());
  return a;
}

TEST(RunoutSidebandsTest, CoreErrorIsTheExactTransmissionErrorOverTheHuntingPeriod) {
  // Both runouts and a tip relief (a mesh-periodic ε): 997/991 teeth, P = 988 027.
  const Scene scene =
      LoadScene("builtin:helical-pair",
                With(kCoprime, {"mesh.pinion-wheel.errors.gear_runout=1e-5",
                                "mesh.pinion-wheel.errors.pinion_runout=4e-6",
                                "mesh.pinion-wheel.errors.pinion_runout_phase_deg=40",
                                "mesh.pinion-wheel.modifications.pinion_tip_relief=8e-6",
                                "mesh.pinion-wheel.modifications.pinion_tip_relief_length=2e-3"}));
  const MeshDef& mesh = scene.meshes.front();
  // The table form is refused (2.5·10⁸ samples); kAuto gives sidebands.
  EXPECT_THROWS_MESSAGE(BuildMeshCore(scene, mesh, true, RunoutForm::kTable), InvalidInput,
                        "hunting period of 988027 mesh cycles");
  const BuiltMeshCore built = BuildMeshCore(scene, mesh, true, RunoutForm::kAuto);
  const auto& core = std::get<LinearMeshCore>(built.core);
  ASSERT_TRUE(built.contact_lines.has_value());
  ASSERT_EQ(core.sidebands().size(), 2);
  EXPECT_EQ(core.sidebands().period_meshes, 988027);
  ASSERT_TRUE(core.transmission_error().has_value());
  EXPECT_EQ(PeriodMeshes(*core.transmission_error()), 1);
  const auto te = MakeMeshTransmissionErrorModel(scene, mesh, *built.contact_lines);
  ASSERT_TRUE(te.has_value());
  // At the table's nodes (linear interpolation exact there), spread over the hunting period.
  const int per_mesh = mesh.model.core_options.coefficient.num_samples;
  double worst = 0.0, scale = 0.0;
  for (std::int64_t cycle = 0; cycle < 988027; cycle += 9973) {
    for (int s = 0; s < per_mesh; s += 17) {
      const double theta =
          2.0 * std::numbers::pi * (static_cast<double>(cycle) + static_cast<double>(s) / per_mesh);
      const Vector2 exact = te->CalcTransmissionError(theta);
      worst = std::max(worst, (EvalTransmissionError(core, theta) - exact).norm());
      scale = std::max(scale, exact.norm());
    }
  }
  EXPECT_GT(scale, 5e-6);
  EXPECT_LE(worst, 1e-9 * scale);
}

TEST(RunoutSidebandsTest, ShortHuntingPeriodSidebandsEqualTheTable) {
  // The built-in helical pair with a runout (P = lcm of its teeth, small enough for the table):
  // the same HB through the table (dense harmonics) and through the sidebands (sparse).
  const Scene scene =
      LoadScene("builtin:helical-pair",
                {"mesh.pinion-wheel.errors.gear_runout=1e-5",
                 "mesh.pinion-wheel.errors.pinion_runout=3e-6", "damping.modal_ratio=0.02"});
  SceneSystemOptions table_options;
  table_options.runout_form = RunoutForm::kTable;
  SceneSystemOptions sideband_options;
  sideband_options.runout_form = RunoutForm::kSidebands;
  const SystemModel table = BuildSceneSystem(scene, table_options).model;
  const SystemModel sidebands = BuildSceneSystem(scene, sideband_options).model;
  ASSERT_EQ(table.period_meshes(), sidebands.period_meshes());
  ASSERT_GT(table.period_meshes(), 1);
  const std::int64_t q = table.period_meshes() / OperatorPeriodMeshes(table);
  HbOptions options;
  options.harmonics = 4;
  options.compute_forces = true;
  options.time_samples = static_cast<int>(q) * 256;
  const HbResult a = SolveHarmonicBalance(table, options, 2500.0);
  options.harmonic_storage = HbHarmonicStorage::kSparse;
  const HbResult b = SolveHarmonicBalance(sidebands, options, 2500.0);
  ASSERT_TRUE(a.summary.ok() && b.summary.ok()) << a.summary.message << b.summary.message;
  ASSERT_TRUE(b.sparse_harmonics);
  EXPECT_EQ(a.kept_harmonics, b.kept_harmonics);
  constexpr double kTol = 1e-8;  // round-off of two expansions of the same trigonometric ε
  for (size_t m = 0; m < a.meshes.size(); ++m) {
    EXPECT_NEAR(b.meshes[m].mean_dte, a.meshes[m].mean_dte, kTol * std::abs(a.meshes[m].mean_dte));
    EXPECT_NEAR(b.meshes[m].rms_dte, a.meshes[m].rms_dte, kTol * a.meshes[m].rms_dte);
    EXPECT_NEAR(b.meshes[m].rms_force, a.meshes[m].rms_force, kTol * a.meshes[m].rms_force);
    EXPECT_NEAR(b.meshes[m].peak_to_peak_dte, a.meshes[m].peak_to_peak_dte,
                kTol * a.meshes[m].peak_to_peak_dte);
    for (size_t i = 0; i < a.kept_harmonics.size(); ++i) {
      EXPECT_NEAR(b.meshes[m].dte_amplitudes(static_cast<Eigen::Index>(i)),
                  a.meshes[m].dte_amplitudes(a.kept_harmonics[i]), kTol * a.meshes[m].rms_dte)
          << a.kept_harmonics[i];
    }
  }
}

TEST(RunoutSidebandsTest, WhatHasNoSparseFormKeepsTheTableRefusal) {
  // Pitch deviations over a coprime hunting period, and the slice model: the table, refused.
  std::string pitch = "mesh.pinion-wheel.errors.gear_pitch_deviations=[1e-6, -1e-6";
  for (int i = 2; i < 991; ++i) pitch += ", 0";
  pitch += "]";
  for (const std::vector<std::string>& extra :
       {std::vector<std::string>{"mesh.pinion-wheel.errors.gear_runout=1e-5", pitch},
        std::vector<std::string>{"mesh.pinion-wheel.errors.gear_runout=1e-5",
                                 "mesh.pinion-wheel.model=slices"}}) {
    const Scene scene = LoadScene("builtin:helical-pair", With(kCoprime, extra));
    EXPECT_THROWS_MESSAGE(BuildMeshCore(scene, scene.meshes.front(), true, RunoutForm::kAuto),
                          InvalidInput, "hunting period of 988027 mesh cycles.*above the limit");
  }
}

}  // namespace
}  // namespace geardyn
