// The bad-input catalogue of the library API (issue 16, with tests/apps/
// bad_input_catalogue_test.cpp for the command): every row passes one bad argument to a public
// entry point — SystemBuilder, a mesh core, ComputeModes, ComputeFloquet, SolveHarmonicBalance,
// SweepHarmonicBalance, SimulateSteadyState, ComputeStabilityChart — and expects
// geardyn::InvalidInput (never another exception, a crash or a NaN result) whose message names
// the argument and the reason (architecture §3.7: "names the argument, its value and the bound").
// Set GEARDYN_BAD_INPUT_TABLE=FILE to write the rows as docs/bad-input.md's table.
//
// Independent truth: the bounds documented in the public headers (system_builder.hpp,
// mesh_core.hpp, modal.hpp, floquet.hpp, harmonic_balance.hpp, time_response.hpp,
// stability_chart.hpp), not the messages printed today.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <limits>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "geardyn/analyses/floquet.hpp"
#include "geardyn/analyses/harmonic_balance.hpp"
#include "geardyn/analyses/modal.hpp"
#include "geardyn/analyses/stability_chart.hpp"
#include "geardyn/analyses/time_response.hpp"
#include "geardyn/common/errors.hpp"
#include "lib/system/hand_pair.hpp"

namespace geardyn {
namespace {

using test::DiagMass;
using test::HandPairBuilder;
using test::HandPairJacobian;
using test::HandPairParams;
using test::SpurCore;

constexpr double kNan = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

struct ApiCase {
  std::string name;      // unique test name
  std::string category;  // docs/bad-input.md groups the rows by it
  std::string call;      // the call, as the table shows it
  std::string argument;  // the message names it
  std::string reason;    // ... and gives this reason
  std::function<void()> run;
};

void PrintTo(const ApiCase& c, std::ostream* os) { *os << c.name; }

// The hand-built spur pair with bearings (tests/lib/system/hand_pair.hpp): a valid model.
SystemModel Pair() {
  const HandPairParams p;
  return HandPairBuilder(p, SpurCore(p)).Build();
}

// A builder holding bodies "a" and "b".
struct TwoBodies {
  SystemBuilder builder;
  BodyIndex a, b;
  TwoBodies() {
    a = builder.AddBody("a", DiagMass(1.0, 1e-3, 2e-3));
    b = builder.AddBody("b", DiagMass(2.0, 2e-3, 4e-3), Vector3(0.13, 0, 0));
  }
};

MatrixX Diag6(double first) {
  Vector6 d;
  d << first, 1e8, 1e8, 1e6, 1e6, 1e6;
  return d.asDiagonal();
}

Matrix6 MassWith(int i, int j, double value) {
  Matrix6 m = DiagMass(1.0, 1e-3, 2e-3);
  m(i, j) = value;
  return m;
}

// --- SystemBuilder -------------------------------------------------------------------------
std::vector<ApiCase> BuilderCases() {
  std::vector<ApiCase> c;
  auto body = [](const std::string& name, const Matrix6& m) {
    return [=] {
      SystemBuilder b;
      b.AddBody(name, m);
    };
  };
  c.push_back({"BodyNegativeMass", "builder", "AddBody(\"g\", diag(-1, …))", "body 'g' mass",
               "positive semi-definite", body("g", DiagMass(-1.0, 1e-3, 2e-3))});
  c.push_back({"BodyNanMass", "builder", "AddBody(\"g\", M with NaN)", "body 'g' mass",
               "non-finite", body("g", MassWith(0, 0, kNan))});
  c.push_back({"BodyInfInertia", "builder", "AddBody(\"g\", M with I_z = inf)", "body 'g' mass",
               "non-finite", body("g", MassWith(5, 5, kInf))});
  c.push_back({"BodyAsymmetricMass", "builder", "AddBody(\"g\", M₀₁ ≠ M₁₀)", "body 'g' mass",
               "symmetric", body("g", MassWith(0, 1, 0.3))});
  c.push_back({"BodyNegativeInertia", "builder", "AddBody(\"g\", I_z = -2e-3)", "body 'g' mass",
               "positive semi-definite", body("g", DiagMass(1.0, 1e-3, -2e-3))});
  c.push_back({"BodyEmptyName", "builder", "AddBody(\"\", M)", "body", "empty",
               body("", DiagMass(1.0, 1e-3, 2e-3))});
  c.push_back({"BodyDuplicateName", "builder", "AddBody(\"a\") twice", "body 'a'", "duplicate", [] {
                 TwoBodies t;
                 t.builder.AddBody("a", DiagMass(1.0, 1e-3, 2e-3));
               }});
  c.push_back({"BodyPositionNan", "builder", "AddBody(\"g\", M, (NaN, 0, 0))", "body 'g' position",
               "non-finite", [] {
                 SystemBuilder b;
                 b.AddBody("g", DiagMass(1.0, 1e-3, 2e-3), Vector3(kNan, 0, 0));
               }});
  auto element = [](const std::string& name, std::vector<int> bodies, const MatrixX& k,
                    const MatrixX& damping = MatrixX(), const MatrixX& mass = MatrixX()) {
    return [=] {
      TwoBodies t;
      std::vector<BodyIndex> idx;
      for (int i : bodies) idx.push_back(BodyIndex(i));
      t.builder.AddElement(name, ElementKind::kBearing, idx, k, damping, mass);
    };
  };
  c.push_back({"ElementNanStiffness", "builder", "AddElement(\"k\", {a}, K with NaN)",
               "bearing 'k' stiffness", "non-finite", element("k", {0}, Diag6(kNan))});
  c.push_back({"ElementNegativeStiffness", "builder", "AddElement(\"k\", {a}, diag(-1e8, …))",
               "bearing 'k' stiffness", "positive semi-definite", element("k", {0}, Diag6(-1e8))});
  c.push_back({"ElementAsymmetricStiffness", "builder", "AddElement(\"k\", {a}, K₀₁ ≠ K₁₀)",
               "bearing 'k' stiffness", "symmetric", [] {
                 TwoBodies t;
                 MatrixX k = Diag6(1e8);
                 k(0, 1) = 1e6;
                 t.builder.AddElement("k", ElementKind::kBearing, {t.a}, k);
               }});
  c.push_back({"ElementWrongSize", "builder", "AddElement(\"k\", {a}, 7×7)",
               "bearing 'k' stiffness", "expected 6×6",
               element("k", {0}, MatrixX::Identity(7, 7))});
  c.push_back({"ElementUnknownBody", "builder", "AddElement(\"k\", {body 7}, K)", "bearing 'k'",
               "unknown body index 7", element("k", {7}, Diag6(1e8))});
  c.push_back({"ElementSameBodyTwice", "builder", "AddElement(\"k\", {a, a}, 12×12)", "bearing 'k'",
               "connects body 'a' to itself", element("k", {0, 0}, MatrixX::Identity(12, 12))});
  c.push_back({"ElementNoBody", "builder", "AddElement(\"k\", {}, K)", "bearing 'k'",
               "1 (grounded) or 2 bodies", element("k", {}, Diag6(1e8))});
  c.push_back({"ElementInfDamping", "builder", "AddElement(\"k\", {a}, K, C with inf)",
               "bearing 'k' damping", "non-finite", element("k", {0}, Diag6(1e8), Diag6(kInf))});
  c.push_back({"ElementNegativeDamping", "builder", "AddElement(\"k\", {a}, K, diag(-1, …))",
               "bearing 'k' damping", "positive semi-definite",
               element("k", {0}, Diag6(1e8), Diag6(-1.0))});
  c.push_back({"ElementNanMass", "builder", "AddElement(\"k\", {a}, K, 0, M with NaN)",
               "bearing 'k' mass", "non-finite",
               element("k", {0}, Diag6(1e8), MatrixX(), Diag6(kNan))});
  c.push_back({"ElementEmptyName", "builder", "AddElement(\"\", {a}, K)", "bearing 0", "empty name",
               element("", {0}, Diag6(1e8))});
  const HandPairParams p;
  auto mesh = [p](const std::string& name, int i, int j, Matrix2x12 G, std::optional<double> me,
                  double ratio, double offset) {
    return [=] {
      TwoBodies t;
      t.builder.AddMesh(name, BodyIndex(i), BodyIndex(j), G, SpurCore(p), me, ratio, offset);
    };
  };
  Matrix2x12 nan_g = HandPairJacobian(p);
  nan_g(0, 5) = kNan;
  c.push_back({"MeshNanJacobian", "builder", "AddMesh(\"m\", a, b, G with NaN, core)", "mesh 'm'",
               "non-finite", mesh("m", 0, 1, nan_g, std::nullopt, 1.0, 0.0)});
  c.push_back({"MeshEqualBodies", "builder", "AddMesh(\"m\", a, a, G, core)", "mesh 'm'",
               "with itself", mesh("m", 0, 0, HandPairJacobian(p), std::nullopt, 1.0, 0.0)});
  c.push_back({"MeshUnknownBody", "builder", "AddMesh(\"m\", a, body 5, G, core)", "mesh 'm'",
               "body", mesh("m", 0, 5, HandPairJacobian(p), std::nullopt, 1.0, 0.0)});
  c.push_back({"MeshZeroEquivalentMass", "builder", "AddMesh(…, equivalent_mass = 0)",
               "mesh 'm' equivalent_mass", "> 0",
               mesh("m", 0, 1, HandPairJacobian(p), 0.0, 1.0, 0.0)});
  c.push_back({"MeshNanPhaseRatio", "builder", "AddMesh(…, phase_ratio = NaN)",
               "mesh 'm' phase_ratio", "finite",
               mesh("m", 0, 1, HandPairJacobian(p), std::nullopt, kNan, 0.0)});
  c.push_back({"MeshInfPhaseOffset", "builder", "AddMesh(…, phase_offset = inf)",
               "mesh 'm' phase_offset", "finite",
               mesh("m", 0, 1, HandPairJacobian(p), std::nullopt, 1.0, kInf)});
  c.push_back({"MeshEmptyName", "builder", "AddMesh(\"\", a, b, G, core)", "mesh", "empty",
               mesh("", 0, 1, HandPairJacobian(p), std::nullopt, 1.0, 0.0)});
  c.push_back(
      {"TorqueNan", "builder", "AddTorque(a, (0, …, NaN), \"t\")", "load 't'", "non-finite", [] {
         TwoBodies t;
         Vector6 f = Vector6::Zero();
         f(5) = kNan;
         t.builder.AddTorque(t.a, f, "t");
       }});
  c.push_back(
      {"TorqueUnknownBody", "builder", "AddTorque(body 9, f, \"t\")", "load 't'", "body", [] {
         TwoBodies t;
         t.builder.AddTorque(BodyIndex(9), Vector6::Zero(), "t");
       }});
  c.push_back({"HarmonicLoadOrderZero", "builder", "AddHarmonicLoad(a, F, order = 0, \"h\")",
               "load 'h' order", ">= 1", [] {
                 TwoBodies t;
                 t.builder.AddHarmonicLoad(t.a, Vector6c::Ones(), 0, "h");
               }});
  c.push_back({"HarmonicLoadNanAmplitude", "builder", "AddHarmonicLoad(a, F with NaN, 1, \"h\")",
               "load 'h' amplitude", "non-finite", [] {
                 TwoBodies t;
                 Vector6c f = Vector6c::Ones();
                 f(2) = {0.0, kNan};
                 t.builder.AddHarmonicLoad(t.a, f, 1, "h");
               }});
  c.push_back({"RayleighNegativeAlpha", "builder", "SetRayleighDamping(-1, 0)", "rayleigh alpha",
               "≥ 0", [] { SystemBuilder().SetRayleighDamping(-1.0, 0.0); }});
  c.push_back({"RayleighNanBeta", "builder", "SetRayleighDamping(0, NaN)", "rayleigh beta",
               "finite", [] { SystemBuilder().SetRayleighDamping(0.0, kNan); }});
  c.push_back({"ModalRatioOne", "builder", "SetModalDampingRatio(1)", "modal damping ratio",
               "[0, 1)", [] { SystemBuilder().SetModalDampingRatio(1.0); }});
  c.push_back({"ModalRatioNan", "builder", "SetModalDampingRatio(NaN)", "modal damping ratio",
               "[0, 1)", [] { SystemBuilder().SetModalDampingRatio(kNan); }});
  c.push_back({"BuildNoBodies", "builder", "SystemBuilder().Build()", "system", "no bodies",
               [] { (void)SystemBuilder().Build(); }});
  c.push_back({"BuildMasslessDof", "builder", "Build() with a body of zero I_z and no element",
               "DOF", "zero mass", [] {
                 SystemBuilder b;
                 b.AddBody("hub", DiagMass(1.0, 1e-3, 0.0));
                 (void)b.Build();
               }});
  return c;
}

// --- mesh cores ------------------------------------------------------------------------------
std::vector<ApiCase> CoreCases() {
  std::vector<ApiCase> c;
  auto core = [](Vector3 k, double half_width) {
    return [=] {
      const HandPairParams p;
      const LinearMeshCore mesh_core(MeshCoreLevel::kBlankenshipSingh, ConstantCoefficient(k),
                                     half_width);
      (void)HandPairBuilder(p, mesh_core).Build();
    };
  };
  c.push_back({"CoreNanStiffness", "mesh core", "LinearMeshCore(K = NaN)",
               "ConstantCoefficient values", "not finite", core(Vector3(kNan, 0.0, 1e4), 0.0125)});
  c.push_back({"CoreNegativeStiffness", "mesh core", "LinearMeshCore(K = -4e8)", "stiffness",
               ">= 0", core(Vector3(-4e8, 0.0, 1e4), 0.0125)});
  c.push_back({"CoreZeroHalfWidth", "mesh core", "LinearMeshCore(…, half_face_width = 0)",
               "half_face_width", "must be positive", core(Vector3(4e8, 0.0, 1e4), 0.0)});
  return c;
}

// --- analyses --------------------------------------------------------------------------------
std::vector<ApiCase> AnalysisCases() {
  std::vector<ApiCase> c;
  // ComputeModes
  auto modes = [](std::function<void(ModalOptions&)> set) {
    return [=] {
      ModalOptions o;
      set(o);
      (void)ComputeModes(Pair(), o);
    };
  };
  c.push_back({"ModesNegativeCount", "ComputeModes", "num_modes = -1", "num_modes", "got -1",
               modes([](ModalOptions& o) { o.num_modes = -1; })});
  c.push_back({"ModesNanZeroTol", "ComputeModes", "zero_tol = NaN", "zero_tol", "nan",
               modes([](ModalOptions& o) { o.zero_tol = kNan; })});
  c.push_back({"ModesArpackTolOne", "ComputeModes", "arpack_tol = 1", "arpack_tol", "[0, 1)",
               modes([](ModalOptions& o) { o.arpack_tol = 1.0; })});
  c.push_back({"ModesNegativeMultiplicityTol", "ComputeModes", "multiplicity_rel_tol = -1",
               "multiplicity_rel_tol", "got -1",
               modes([](ModalOptions& o) { o.multiplicity_rel_tol = -1.0; })});
  // ComputeFloquet
  auto floquet = [](std::function<void(FloquetOptions&)> set) {
    return [=] {
      FloquetOptions o;
      o.mesh_frequency_hz = 1000.0;
      set(o);
      (void)ComputeFloquet(Pair(), o);
    };
  };
  c.push_back({"FloquetNanFrequency", "ComputeFloquet", "mesh_frequency_hz = NaN",
               "mesh_frequency_hz", "finite and > 0",
               floquet([](FloquetOptions& o) { o.mesh_frequency_hz = kNan; })});
  c.push_back({"FloquetInfFrequency", "ComputeFloquet", "mesh_frequency_hz = inf",
               "mesh_frequency_hz", "finite and > 0",
               floquet([](FloquetOptions& o) { o.mesh_frequency_hz = kInf; })});
  c.push_back({"FloquetNegativeFrequency", "ComputeFloquet", "mesh_frequency_hz = -100",
               "mesh_frequency_hz", "got -100",
               floquet([](FloquetOptions& o) { o.mesh_frequency_hz = -100.0; })});
  c.push_back({"FloquetZeroTolerance", "ComputeFloquet", "tolerance = 0", "tolerance", "(0, 1)",
               floquet([](FloquetOptions& o) { o.tolerance = 0.0; })});
  c.push_back({"FloquetHillHarmonics", "ComputeFloquet", "hill_harmonics = 500", "hill_harmonics",
               "[0, 199]", floquet([](FloquetOptions& o) { o.hill_harmonics = 500; })});
  c.push_back({"FloquetMagnusOrder", "ComputeFloquet", "magnus_order = 5", "magnus_order", "4 or 6",
               floquet([](FloquetOptions& o) { o.magnus_order = 5; })});
  c.push_back({"FloquetMagnusSteps", "ComputeFloquet", "magnus_steps = -1", "magnus_steps",
               "got -1", floquet([](FloquetOptions& o) { o.magnus_steps = -1; })});
  c.push_back({"FloquetNumModes", "ComputeFloquet", "num_modes = -2", "num_modes", "got -2",
               floquet([](FloquetOptions& o) { o.num_modes = -2; })});
  c.push_back({"FloquetArpackNev", "ComputeFloquet", "arpack_nev = 0", "arpack_nev", ">= 1",
               floquet([](FloquetOptions& o) { o.arpack_nev = 0; })});
  c.push_back({"FloquetArpackNcv", "ComputeFloquet", "arpack_ncv = 3 (nev 6)", "arpack_ncv",
               "arpack_nev + 2", floquet([](FloquetOptions& o) { o.arpack_ncv = 3; })});
  c.push_back({"FloquetArpackIterations", "ComputeFloquet", "arpack_max_iterations = 0",
               "arpack_max_iterations", "got 0",
               floquet([](FloquetOptions& o) { o.arpack_max_iterations = 0; })});
  c.push_back({"FloquetNevAboveTwiceDofs", "ComputeFloquet",
               "method = kArpackMonodromy, arpack_nev = 1000", "arpack_nev", "<= 2n",
               floquet([](FloquetOptions& o) {
                 o.method = FloquetMethod::kArpackMonodromy;
                 o.arpack_nev = 1000;
               })});
  // SolveHarmonicBalance, SweepHarmonicBalance
  auto hb = [](double f, std::function<void(HbOptions&)> set) {
    return [=] {
      HbOptions o;
      set(o);
      (void)SolveHarmonicBalance(Pair(), o, f);
    };
  };
  auto none = [](HbOptions&) {};
  c.push_back({"HbNanFrequency", "SolveHarmonicBalance", "mesh_frequency_hz = NaN",
               "mesh_frequency_hz", "nan", hb(kNan, none)});
  c.push_back({"HbZeroFrequency", "SolveHarmonicBalance", "mesh_frequency_hz = 0",
               "mesh_frequency_hz", "got 0", hb(0.0, none)});
  c.push_back({"HbInfFrequency", "SolveHarmonicBalance", "mesh_frequency_hz = inf",
               "mesh_frequency_hz", "inf", hb(kInf, none)});
  c.push_back({"HbNegativeHarmonics", "SolveHarmonicBalance", "harmonics = -1", "harmonics",
               "got -1", hb(1000.0, [](HbOptions& o) { o.harmonics = -1; })});
  c.push_back({"HbHugeHarmonics", "SolveHarmonicBalance", "harmonics = 10⁹", "harmonics", "<= 2048",
               hb(1000.0, [](HbOptions& o) { o.harmonics = 1000000000; })});
  c.push_back({"HbNanTolerance", "SolveHarmonicBalance", "tolerance = NaN", "tolerance", "nan",
               hb(1000.0, [](HbOptions& o) { o.tolerance = kNan; })});
  c.push_back({"HbNegativeTimeSamples", "SolveHarmonicBalance", "time_samples = -4", "time_samples",
               "got -4", hb(1000.0, [](HbOptions& o) { o.time_samples = -4; })});
  c.push_back({"HbMinAboveMaxHarmonics", "SolveHarmonicBalance",
               "min_harmonics = 64, max_harmonics = 16", "max_harmonics", "min_harmonics",
               hb(1000.0, [](HbOptions& o) {
                 o.min_harmonics = 64;
                 o.max_harmonics = 16;
               })});
  c.push_back({"HbSweepNanPoint", "SweepHarmonicBalance", "frequencies {1000, NaN}",
               "mesh_frequencies_hz[1]", "must be finite and > 0", [] {
                 (void)SweepHarmonicBalance(Pair(), {1000.0, kNan}, HbOptions{});
               }});
  // SimulateSteadyState
  auto sim = [](double f, std::function<void(TimeResponseOptions&)> set) {
    return [=] {
      TimeResponseOptions o;
      o.steady.max_periods = 2;
      set(o);
      (void)SimulateSteadyState(Pair(), f, o);
    };
  };
  auto keep = [](TimeResponseOptions&) {};
  c.push_back({"SimNanFrequency", "SimulateSteadyState", "mesh_frequency_hz = NaN",
               "SimulateSteadyState: mesh frequency", "finite and > 0 Hz, got nan",
               sim(kNan, keep)});
  c.push_back({"SimNegativeFrequency", "SimulateSteadyState", "mesh_frequency_hz = -1",
               "SimulateSteadyState: mesh frequency", "got -1", sim(-1.0, keep)});
  c.push_back({"SimZeroRelativeTolerance", "SimulateSteadyState", "relative_tolerance = 0",
               "relative_tolerance", "got 0",
               sim(1000.0, [](TimeResponseOptions& o) { o.integration.relative_tolerance = 0; })});
  c.push_back({"SimSpectralRadius", "SimulateSteadyState", "spectral_radius = 2", "spectral_radius",
               "[0, 1]",
               sim(1000.0, [](TimeResponseOptions& o) { o.integration.spectral_radius = 2; })});
  c.push_back({"SimNewtonIterations", "SimulateSteadyState", "max_newton_iterations = 0",
               "max_newton_iterations", "[1, 100]", sim(1000.0, [](TimeResponseOptions& o) {
                 o.integration.max_newton_iterations = 0;
               })});
  c.push_back({"SimSamplesPerPeriod", "SimulateSteadyState", "samples_per_period = 0",
               "samples_per_period", "got 0",
               sim(1000.0, [](TimeResponseOptions& o) { o.integration.samples_per_period = 0; })});
  c.push_back(
      {"SimMaxStepFraction", "SimulateSteadyState", "max_step_fraction = NaN", "max_step_fraction",
       "nan", sim(1000.0, [](TimeResponseOptions& o) { o.integration.max_step_fraction = kNan; })});
  c.push_back({"SimSteadyTolerance", "SimulateSteadyState", "steady.tolerance = 2", "tolerance",
               "[1e-14, 1]",
               sim(1000.0, [](TimeResponseOptions& o) { o.steady.tolerance = 2.0; })});
  c.push_back({"SimMaxPeriodsZero", "SimulateSteadyState", "steady.max_periods = 0", "max_periods",
               "got 0", sim(1000.0, [](TimeResponseOptions& o) { o.steady.max_periods = 0; })});
  c.push_back({"SimRecordPeriods", "SimulateSteadyState", "steady.record_periods = 5000",
               "record_periods", "[1, 1000]",
               sim(1000.0, [](TimeResponseOptions& o) { o.steady.record_periods = 5000; })});
  c.push_back({"SimInitialStateSize", "SimulateSteadyState",
               "start_from_static = false, initial_state of size 3", "initial_state",
               "must have 2·(num_dofs + internal) = 24", sim(1000.0, [](TimeResponseOptions& o) {
                 o.start_from_static = false;
                 o.initial_state = VectorX::Zero(3);
               })});
  c.push_back({"SimNanInitialPhase", "SimulateSteadyState", "initial_phase = NaN", "initial_phase",
               "nan", sim(1000.0, [](TimeResponseOptions& o) { o.initial_phase = kNan; })});
  // ComputeStabilityChart
  auto chart = [](ChartAxis x, ChartAxis y, std::function<void(StabilityChartOptions&)> set) {
    return [=] {
      StabilityChartOptions o;
      set(o);
      const ChartEvaluatorFactory factory = [] {
        return [](const ChartPoint&) { return ChartPointResult{0.5, 0.0, 1.0, true}; };
      };
      (void)ComputeStabilityChart(x, y, factory, o);
    };
  };
  const ChartAxis good_x{"x", 0.0, 1.0, 3};
  const ChartAxis good_y{"y", 0.0, 1.0, 3};
  auto defaults = [](StabilityChartOptions&) {};
  c.push_back({"ChartAxisNanBound", "ComputeStabilityChart", "x = {lo = NaN}", "x", "nan",
               chart({"x", kNan, 1.0, 3}, good_y, defaults)});
  c.push_back({"ChartAxisReversed", "ComputeStabilityChart", "y = {lo = 1, hi = 0}", "y axis",
               "lower bound must be below the upper bound",
               chart(good_x, {"y", 1.0, 0.0, 3}, defaults)});
  c.push_back({"ChartAxisOnePoint", "ComputeStabilityChart", "x = {num_points = 1}", "x", "got 1",
               chart({"x", 0.0, 1.0, 1}, good_y, defaults)});
  c.push_back({"ChartNegativeThreads", "ComputeStabilityChart", "num_threads = -1", "num_threads",
               "got -1",
               chart(good_x, good_y, [](StabilityChartOptions& o) { o.num_threads = -1; })});
  c.push_back({"ChartBoundaryTolerance", "ComputeStabilityChart", "boundary_tolerance = 0",
               "boundary_tolerance", "got 0", chart(good_x, good_y, [](StabilityChartOptions& o) {
                 o.boundary_tolerance = 0.0;
               })});
  c.push_back({"ChartResonanceOrder", "ComputeStabilityChart", "max_resonance_order = 0",
               "max_resonance_order", "got 0",
               chart(good_x, good_y, [](StabilityChartOptions& o) { o.max_resonance_order = 0; })});
  c.push_back({"ChartInstabilityThreshold", "ComputeStabilityChart", "instability_threshold = NaN",
               "instability_threshold", "nan", chart(good_x, good_y, [](StabilityChartOptions& o) {
                 o.instability_threshold = kNan;
               })});
  c.push_back({"ChartFrequencyListSize", "ComputeStabilityChart",
               "natural_frequencies_hz with 2 lists for 3 rows", "natural_frequencies_hz",
               "must have 0, 1 or 3 (y.num_points) lists",
               chart(good_x, good_y, [](StabilityChartOptions& o) {
                 o.natural_frequencies_hz = {{100.0}, {200.0}};
               })});
  return c;
}

std::vector<ApiCase> AllCases() {
  std::vector<ApiCase> rows = BuilderCases();
  for (ApiCase& r : CoreCases()) rows.push_back(std::move(r));
  for (ApiCase& r : AnalysisCases()) rows.push_back(std::move(r));
  return rows;
}

class BadInputApiTest : public ::testing::TestWithParam<ApiCase> {};

TEST_P(BadInputApiTest, ThrowsInvalidInputNamingTheArgumentAndTheReason) {
  const ApiCase& c = GetParam();
  try {
    c.run();
    ADD_FAILURE() << "no exception; expected InvalidInput naming '" << c.argument << "'";
  } catch (const InvalidInput& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(c.argument), std::string::npos)
        << "argument '" << c.argument << "' not in: " << what;
    EXPECT_NE(what.find(c.reason), std::string::npos)
        << "reason '" << c.reason << "' not in: " << what;
  } catch (const std::exception& e) {
    ADD_FAILURE() << "not InvalidInput: " << e.what();
  }
}

INSTANTIATE_TEST_SUITE_P(Rows, BadInputApiTest, ::testing::ValuesIn(AllCases()),
                         [](const ::testing::TestParamInfo<ApiCase>& p) { return p.param.name; });

TEST(BadInputApiTest, HasUniqueRows) {
  const std::vector<ApiCase> rows = AllCases();
  std::set<std::string> names, inputs;
  for (const ApiCase& r : rows) {
    EXPECT_TRUE(names.insert(r.name).second) << r.name;
    EXPECT_TRUE(inputs.insert(r.category + "\x1f" + r.call).second) << "duplicate: " << r.name;
  }
  EXPECT_GE(rows.size(), 50u);
  // GEARDYN_BAD_INPUT_TABLE=FILE writes the rows for docs/bad-input.md.
  if (const char* file = std::getenv("GEARDYN_BAD_INPUT_TABLE")) {
    std::ofstream md(file);
    std::map<std::string, int> per_category;
    for (const ApiCase& r : rows) {
      md << "| " << r.name << " | " << r.category << " | `" << r.call << "` | " << r.argument
         << " … " << r.reason << " | InvalidInput |\n";
      ++per_category[r.category];
    }
    md << "\n";
    for (const auto& [category, n] : per_category) md << "| " << category << " | " << n << " |\n";
    md << "| total | " << rows.size() << " |\n";
  }
}

}  // namespace
}  // namespace geardyn
