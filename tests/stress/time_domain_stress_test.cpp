// Stress suite part B, the time-domain simulator (issue 16): huge and tiny speeds against the
// SDOF closed form of the torsional pair (hb_stress_cases.hpp), zero damping (energy conserved
// per the energy bookkeeping, and a status instead of a verdict), a bounded step count that ends
// with a status, and the same system in mm–t–s units. No NaN/Inf may reach a TimeResponse.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "geardyn/analyses/time_response.hpp"
#include "stress/hb_stress_cases.hpp"

namespace geardyn {
namespace {

using stress::AllFinite;
using stress::SdofPair;

struct SpeedCase {
  std::string name;
  double f_m_hz;
  double tol;  // relative, against the closed form
};

void PrintTo(const SpeedCase& c, std::ostream* os) { *os << c.name; }

class TimeDomainSpeedStress : public ::testing::TestWithParam<SpeedCase> {};

// The pair with a harmonic torque at order 1: RMS DTE = |X|/√2 (closed-form FRF), mean DTE the
// static deflection T/(r1 k).
TEST_P(TimeDomainSpeedStress, SteadyStateEqualsTheClosedForm) {
  const SpeedCase& c = GetParam();
  SdofPair pair;
  pair.harmonic_torque = 20.0;
  TimeResponseOptions o;
  o.integration.relative_tolerance = 1e-10;
  o.integration.absolute_tolerance = 1e-10;
  o.integration.max_steps = 2000000;  // bounded: a status, never an endless run
  o.steady.tolerance = 1e-8;
  // The pair is LTI and damped (Floquet-stable): the linear HB's orbit is the attracting one.
  o.start_from_linear_steady_state = true;
  const TimeResponse r = SimulateSteadyState(pair.Model(), c.f_m_hz, o);
  EXPECT_TRUE(AllFinite(r)) << c.name;
  ASSERT_TRUE(r.summary.ok()) << c.name << ": " << r.summary.BriefReport();
  EXPECT_EQ(r.steady, SteadyVerdict::kSteady);
  const double rms = pair.FrfAmplitude(c.f_m_hz) / std::sqrt(2.0);
  EXPECT_NEAR(r.meshes[0].rms_dte, rms, c.tol * rms) << c.name;
  EXPECT_NEAR(r.meshes[0].mean_dte, pair.StaticDeflection(), 1e-6 * pair.StaticDeflection());
  EXPECT_LT(r.max_energy_error, 1e-4) << c.name;
}

// f_m/f_n = 2e-7: quasi-static, |X| = F/k. Fixed in issue 16 (docs/stress/part-b.md): the
// energy balance read 6.9e-2 although the response was right. W ≈ D ≈ 3.4e-8 of the gross flow G
// per period there, and the quadrature's error of ≈ 2e-9·G was measured against D alone; the
// scale now has a floor of 1e-3·G (time_response.hpp, "Energy balance"): 2.3e-6.
INSTANTIATE_TEST_SUITE_P(QuasiStatic, TimeDomainSpeedStress,
                         ::testing::Values(SpeedCase{"quasi_static_1e_3_Hz", 1e-3, 1e-4}),
                         [](const ::testing::TestParamInfo<SpeedCase>& param_info) {
                           return param_info.param.name;
                         });

// Fixed in issue 16 (docs/stress/part-b.md): at 1e-3 Hz generalized-α (picked by kAuto)
// rejected ~1e6 steps (velocity tolerance below round-off; the spurious root of ρ∞ = 0.9 in the
// error estimate); at 1e6 Hz the start from static excited a free vibration that needed ~1.3e4
// periods to decay (a run may now start from the linear HB's periodic state; off by default, see
// TimeResponseOptions::start_from_linear_steady_state).
INSTANTIATE_TEST_SUITE_P(Cases, TimeDomainSpeedStress,
                         ::testing::Values(
                             // f_m/f_n ≈ 216: mass dominated, |X| ≈ F/(m_e ω²).
                             SpeedCase{"mass_dominated_1e6_Hz", 1e6, 1e-4}),
                         [](const ::testing::TestParamInfo<SpeedCase>& param_info) {
                           return param_info.param.name;
                         });

// The static start at 1e6 Hz (the linear HB start switched off): the free vibration of the mesh
// mode decays by exp(−ζ ω_n T) = exp(−1.45e-3) per mesh period, ~1.3e4 periods to the steady
// tolerance. At max_periods = 3000 the run ends kNotConverged and says so: the decay factor it
// measured from the period-to-period changes is the closed form's, and the message says how far
// to raise max_periods.
TEST(TimeDomainStress, SlowlyDecayingTransientIsReportedWithTheNeededPeriods) {
  SdofPair pair;
  pair.harmonic_torque = 20.0;
  TimeResponseOptions o;
  o.integration.relative_tolerance = 1e-10;
  o.integration.absolute_tolerance = 1e-10;
  o.steady.tolerance = 1e-8;
  o.start_from_linear_steady_state = false;
  const double f_m = 1e6;
  const TimeResponse r = SimulateSteadyState(pair.Model(), f_m, o);
  EXPECT_TRUE(AllFinite(r));
  ASSERT_EQ(r.summary.status, Status::kNotConverged) << r.summary.BriefReport();
  EXPECT_EQ(r.steady, SteadyVerdict::kUndetermined);
  const double decay = std::exp(-pair.zeta * pair.NaturalRadPerS() / f_m);
  EXPECT_NEAR(std::log(r.transient_decay_per_period), std::log(decay), 0.05 * -std::log(decay))
      << r.summary.message;
  EXPECT_NE(r.summary.message.find("raise max_periods"), std::string::npos) << r.summary.message;
}

// ζ = 0 and a harmonic torque: the free vibration never decays, so no steady verdict; the run
// ends at max_periods with a status and a message, and the energy bookkeeping closes per period
// with nothing dissipated.
TEST(TimeDomainStress, ZeroDampingConservesEnergyAndEndsWithAStatus) {
  SdofPair pair;
  pair.zeta = 0.0;
  pair.harmonic_torque = 20.0;
  TimeResponseOptions o;
  o.integration.integrator = TimeIntegrator::kRungeKutta;
  o.integration.relative_tolerance = 1e-11;
  o.integration.absolute_tolerance = 1e-11;
  o.steady.max_periods = 12;
  const TimeResponse r = SimulateSteadyState(pair.Model(), 0.37 * pair.NaturalHz(), o);
  EXPECT_TRUE(AllFinite(r));
  EXPECT_EQ(r.summary.status, Status::kNotConverged) << r.summary.BriefReport();
  EXPECT_FALSE(r.summary.message.empty());
  EXPECT_EQ(r.steady, SteadyVerdict::kUndetermined);
  ASSERT_FALSE(r.energy.empty());
  for (const EnergyBalancePeriod& e : r.energy) {
    EXPECT_EQ(e.dissipated, 0.0);
    // W = ΔS to the integration error (rk8pd at 1e-11).
    EXPECT_LT(e.relative_error, 1e-7);
  }
}

// The energy error's floor of 1e-3 of the gross flow (issue 16: the quasi-static case above)
// leaves the check's sense in a dynamic run: generalized-α at loose tolerances with numerical
// damping (ρ∞ = 0.5: energy the integrator removes and D does not book) on the pair with a 20 %
// mesh-stiffness variation under load, below resonance. G ≈ 47 D there, so the floor is inactive
// and the error is the numerical loss against D (3.3e-3; the RMS DTE is 0.55 % off rk8pd's).
// Truth: rk8pd at 1e-11, whose balance closes to ≲ 1e-9.
TEST(TimeDomainStress, EnergyCheckStillSeesALooseIntegrationUnderLoad) {
  SdofPair pair;
  pair.shape = stress::StiffnessShape::kCosine;
  pair.a = 0.2;
  pair.harmonic_torque = 20.0;
  const double f_m = 0.8 * pair.NaturalHz();
  TimeResponseOptions tight;
  tight.integration.integrator = TimeIntegrator::kRungeKutta;
  tight.integration.relative_tolerance = 1e-11;
  tight.integration.absolute_tolerance = 1e-11;
  const TimeResponse ref = SimulateSteadyState(pair.Model(), f_m, tight);
  ASSERT_TRUE(ref.summary.ok()) << ref.summary.BriefReport();
  EXPECT_LT(ref.max_energy_error, 1e-8);
  TimeResponseOptions loose;
  loose.integration.integrator = TimeIntegrator::kGeneralizedAlpha;
  loose.integration.spectral_radius = 0.5;
  loose.integration.relative_tolerance = 1e-2;
  loose.integration.absolute_tolerance = 1e-2;
  const TimeResponse r = SimulateSteadyState(pair.Model(), f_m, loose);
  ASSERT_TRUE(r.summary.ok()) << r.summary.BriefReport();
  ASSERT_FALSE(r.energy.empty());
  for (const EnergyBalancePeriod& e : r.energy) {
    EXPECT_GT(e.dissipated, 1e-3 * e.gross_flow);  // the floor is inactive
    EXPECT_GT(e.gross_flow, e.dissipated);         // G counts the parametric exchange too
  }
  EXPECT_GT(r.max_energy_error, 1e-4);
  const double rms_error =
      std::abs(r.meshes[0].rms_dte - ref.meshes[0].rms_dte) / ref.meshes[0].rms_dte;
  EXPECT_GT(rms_error, 1e-3);  // the warning is about a real error
  bool warned = false;
  for (const std::string& w : r.summary.warnings) {
    warned = warned || w.find("tighten the tolerances") != std::string::npos;
  }
  EXPECT_TRUE(warned) << r.summary.BriefReport();
}

// A step budget far too small for the request: the run ends with kNotConverged and a message
// after at most max_steps steps, keeping what it computed (finite).
// (Issue 16: it ended with kNumericalIssue where time_response.hpp documents "exceeded →
// kNotConverged"; fixed in td_stepper.cpp / time_response.cpp.)
TEST(TimeDomainStress, StepBudgetEndsTheRunWithAStatus) {
  SdofPair pair;
  pair.harmonic_torque = 20.0;
  for (const TimeIntegrator method :
       {TimeIntegrator::kRungeKutta, TimeIntegrator::kGeneralizedAlpha}) {
    TimeResponseOptions o;
    o.integration.integrator = method;
    o.integration.max_steps = 50;
    const TimeResponse r = SimulateSteadyState(pair.Model(), 0.5 * pair.NaturalHz(), o);
    EXPECT_TRUE(AllFinite(r)) << ToString(method);
    EXPECT_EQ(r.summary.status, Status::kNotConverged) << r.summary.BriefReport();
    EXPECT_FALSE(r.summary.message.empty()) << ToString(method);
    EXPECT_LE(r.steps, 50) << ToString(method);
    EXPECT_EQ(r.steady, SteadyVerdict::kUndetermined);
  }
}

// The LTV pair (spur wave, ε, harmonic torque) in SI and in mm–t–s: DTE over the static
// deflection is the same number to the integration tolerance.
TEST(TimeDomainStress, MillimetreTonneSecondUnitsGiveTheSameDimensionlessAnswer) {
  SdofPair si;
  si.shape = stress::StiffnessShape::kSpurWave;
  si.e1 = 2e-6;
  si.harmonic_torque = 15.0;
  SdofPair mm = si;
  mm.units = stress::kMmTonneSecond;
  TimeResponseOptions o;
  o.integration.integrator = TimeIntegrator::kRungeKutta;
  o.integration.relative_tolerance = 1e-10;
  o.integration.absolute_tolerance = 1e-10;
  o.steady.tolerance = 1e-9;
  const double f_m = 0.6 * si.NaturalHz();
  const TimeResponse a = SimulateSteadyState(si.Model(), f_m, o);
  const TimeResponse b = SimulateSteadyState(mm.Model(), f_m, o);
  ASSERT_TRUE(a.summary.ok() && b.summary.ok()) << b.summary.BriefReport();
  const double sa = si.StaticDeflection(), sb = 1e3 * si.StaticDeflection();
  EXPECT_NEAR(b.meshes[0].mean_dte / sb, a.meshes[0].mean_dte / sa, 1e-6);
  EXPECT_NEAR(b.meshes[0].rms_dte / sb, a.meshes[0].rms_dte / sa, 1e-6 * a.meshes[0].rms_dte / sa);
  EXPECT_NEAR(b.meshes[0].peak_to_peak_dte / sb, a.meshes[0].peak_to_peak_dte / sa,
              1e-6 * a.meshes[0].peak_to_peak_dte / sa);
}

}  // namespace
}  // namespace geardyn
