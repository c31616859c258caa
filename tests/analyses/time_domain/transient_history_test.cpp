/// @file
/// @brief A run that ends before steady state (cancelled or failed) keeps the last complete
/// integrated period as its DTE history (TimeResponse::history_from_transient). Truth: the same
/// integration not cancelled but stopped by max_periods records the NEXT period through the
/// ordinary recording path — so a run cancelled after period n must hold exactly what a run with
/// max_periods = n − 1 records (the same deterministic steps from the same static start).
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <string>

#include "analyses/harmonic_balance/hb_fixtures.hpp"
#include "geardyn/analyses/time_response.hpp"
#include "lib/system/hand_pair.hpp"
#include "lib/system/periodic_fixture.hpp"

namespace geardyn {
namespace {

SystemModel LightlyDampedPair() {
  const test::HandPairParams p;
  const double m_e = 1.0 / (p.r1 * p.r1 / p.I1 + p.r2 * p.r2 / p.I2);
  const LinearMeshCore core(MeshCoreLevel::kBlankenshipSingh,
                            ConstantCoefficient(Vector3(p.k, 0.0, p.k * p.b * p.b / 3.0)), p.b,
                            Coefficient(test::SmoothTransmissionError(2e-6, 0.0, 0.0)),
                            MeshDamping::FromCoefficient(2.0 * 0.002 * std::sqrt(p.k * m_e)));
  return test::TorsionalPair(core, 150.0);
}

TimeResponseOptions Options() {
  TimeResponseOptions o;
  o.integration.integrator = TimeIntegrator::kRungeKutta;
  o.integration.samples_per_period = 32;
  o.steady.tolerance = 1e-14;  // never steady within these few periods
  return o;
}

TEST(TransientHistory, CancelledRunKeepsItsLastCompletePeriod) {
  constexpr double kFm = 1500.0;
  const SystemModel model = LightlyDampedPair();
  std::atomic<bool> cancel{false};
  // Cancel once period 4 is done: the run stops before period 5.
  const TimeProgress progress = [&](double, const std::string& note) {
    if (note.rfind("period 4,", 0) == 0) cancel.store(true);
  };
  const TimeResponse cancelled = SimulateSteadyState(model, kFm, Options(), progress, &cancel);
  EXPECT_EQ(cancelled.summary.status, Status::kInterrupted);
  EXPECT_EQ(cancelled.summary.message, "cancelled");
  EXPECT_EQ(cancelled.steady, SteadyVerdict::kUndetermined);
  ASSERT_TRUE(cancelled.history_from_transient);
  EXPECT_EQ(cancelled.periods, 4);

  TimeResponseOptions o = Options();
  o.steady.max_periods = 3;  // not steady: records period 4
  const TimeResponse reference = SimulateSteadyState(model, kFm, o);
  ASSERT_FALSE(reference.history_from_transient);
  ASSERT_EQ(reference.time.size(), 32);
  ASSERT_EQ(cancelled.time.size(), 32);
  ASSERT_EQ(cancelled.meshes.size(), 1u);
  const VectorX& a = cancelled.meshes[0].dte;
  const VectorX& b = reference.meshes[0].dte;
  const double scale = b.cwiseAbs().maxCoeff();
  for (Eigen::Index s = 0; s < 32; ++s) {
    EXPECT_NEAR(cancelled.time(s), reference.time(s), 1e-12 * reference.time(31)) << s;
    EXPECT_NEAR(a(s), b(s), 1e-9 * scale) << s;
  }
  EXPECT_NEAR(cancelled.meshes[0].rms_dte, reference.meshes[0].rms_dte,
              1e-9 * reference.meshes[0].rms_dte);
}

// Cancelled before any period is complete: no history (nothing invented).
TEST(TransientHistory, CancelledBeforeTheFirstPeriodHasNoHistory) {
  std::atomic<bool> cancel{true};
  const TimeResponse r = SimulateSteadyState(LightlyDampedPair(), 1500.0, Options(), {}, &cancel);
  EXPECT_EQ(r.summary.message, "cancelled");
  EXPECT_FALSE(r.history_from_transient);
  EXPECT_EQ(r.time.size(), 0);
}

}  // namespace
}  // namespace geardyn
