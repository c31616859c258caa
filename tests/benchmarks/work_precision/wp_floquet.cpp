// Work-precision of the Floquet methods (issue 5): wall time against the largest multiplier error
// over each method's accuracy knob, on
//   sdof:   the Meissner equation (rectangular-wave stiffness), reference = closed form;
//   pair12: the hand-built 12-DOF pair with a smooth helical-like core, reference = GSL rk8pd at
//           tolerance 1e-13;
//   shaft:  two geared Timoshenko shafts (204 DOFs, stiffness-proportional shaft damping β = 2e-6
//   s)
//           with the spur rectangular wave, reference = exact steps on the full system; modal
//           projection (error of its retained multipliers) and ARPACK on the matrix-free
//           monodromy (error of its 6 dominant multipliers).
// Output CSV: case/method, knob, wall_time_s, error, evaluations (steps or A(t) evaluations).
// Run from a Release build: ./tests/benchmarks/wp_floquet
#include <algorithm>
#include <cstdio>
#include <string>

#include "../../analyses/floquet/floquet_test_support.hpp"
#include "wp_common.hpp"

using namespace geardyn;
using namespace geardyn::test;

namespace {

void Emit(const std::string& name, double knob, double time, double error, const FloquetResult& r) {
  const auto it = r.summary.counters.find("steps");
  wp::Row(name.c_str(), knob, time, error,
          it == r.summary.counters.end() ? 0.0 : static_cast<double>(it->second));
}

void Sdof() {
  const double duty = 0.6, T = 2.9;
  const VectorXc exact = MeissnerMultipliers(MeissnerTrace(1.3, 0.7, duty * T, (1 - duty) * T));
  const PeriodicSecondOrderSystem sys = MakeMeissnerSystem(1.3, 0.7, duty, T);
  auto run = [&](const std::string& name, double knob, const FloquetOptions& o) {
    FloquetResult r;
    const double time = wp::TimeIt([&] { r = ComputeFloquet(sys, o); });
    Emit("sdof/" + name, knob, time, MultiplierDistance(r.multipliers, exact), r);
  };
  run("exact_steps", 0, {});
  for (const double tol : {1e-4, 1e-6, 1e-8, 1e-10, 1e-12}) {
    FloquetOptions o;
    o.method = FloquetMethod::kOdeStepper;
    o.tolerance = tol;
    run("ode_stepper", tol, o);
  }
  for (const int steps : {16, 64, 256, 1024}) {
    FloquetOptions o;
    o.method = FloquetMethod::kMagnus;
    o.magnus_steps = steps;
    run("magnus6", steps, o);
  }
}

// Error of the reported multipliers: each against the nearest multiplier of the full system.
double NearestError(const VectorXc& reported, const VectorXc& full) {
  double err = 0.0;
  for (int i = 0; i < reported.size(); ++i) {
    err = std::max(err, (full.array() - reported[i]).abs().minCoeff());
  }
  return err;
}

void Pair12() {
  const SystemModel model = HandPair(HandSmoothCore(0.2, 0.05, 900.0));
  FloquetOptions base;
  base.mesh_frequency_hz = 5000.0;
  FloquetOptions ref_o = base;
  ref_o.method = FloquetMethod::kOdeStepper;
  ref_o.tolerance = 1e-13;
  const VectorXc ref = ComputeFloquet(model, ref_o).multipliers;
  auto run = [&](const std::string& name, double knob, const FloquetOptions& o) {
    FloquetResult r;
    const double time = wp::TimeIt([&] { r = ComputeFloquet(model, o); });
    Emit("pair12/" + name, knob, time, MultiplierDistance(r.multipliers, ref), r);
  };
  for (const int order : {4, 6}) {
    for (const int steps : {4, 8, 16, 32, 64, 128}) {
      FloquetOptions o = base;
      o.method = FloquetMethod::kMagnus;
      o.magnus_order = order;
      o.magnus_steps = steps;
      run("magnus" + std::to_string(order) + "_steps", steps, o);
    }
    for (const double tol : {1e-6, 1e-8, 1e-10}) {
      FloquetOptions o = base;
      o.method = FloquetMethod::kMagnus;
      o.magnus_order = order;
      o.tolerance = tol;
      run("magnus" + std::to_string(order) + "_tol", tol, o);
    }
  }
  for (const double tol : {1e-6, 1e-8, 1e-10}) {
    FloquetOptions o = base;
    o.method = FloquetMethod::kOdeStepper;
    o.tolerance = tol;
    run("ode_stepper", tol, o);
  }
  for (const int h : {3, 5, 8, 12}) {
    FloquetOptions o = base;
    o.method = FloquetMethod::kHill;
    o.hill_harmonics = h;
    run("hill", h, o);
  }
  for (const double tol : {1e-6, 1e-8, 1e-10}) {
    FloquetOptions o = base;
    o.method = FloquetMethod::kArpackMonodromy;
    o.arpack_nev = 6;
    o.tolerance = tol;
    FloquetResult r;
    const double time = wp::TimeIt([&] { r = ComputeFloquet(model, o); });
    Emit("pair12/arpack_monodromy", tol, time, NearestError(r.multipliers, ref), r);
  }
}

void Shaft() {
  const SystemModel model = GearedShafts(16, HandSpurWaveCore(600.0), 2e-6);
  FloquetOptions base;
  base.mesh_frequency_hz = 5000.0;
  base.split_blocks = false;
  FloquetOptions full = base;
  full.method = FloquetMethod::kExactSteps;
  FloquetResult ref;
  const double t_full = wp::TimeIt([&] { ref = ComputeFloquet(model, full); });
  Emit("shaft/exact_steps_full", model.num_dofs(), t_full, ref.summary.error_estimate, ref);
  for (const int m : {8, 16, 32, 64}) {
    FloquetOptions o = base;
    o.method = FloquetMethod::kModalProjection;
    o.num_modes = m;
    FloquetResult r;
    const double time = wp::TimeIt([&] { r = ComputeFloquet(model, o); });
    const double err = NearestError(r.multipliers, ref.multipliers);
    Emit("shaft/modal_projection", m, time, err, r);
    std::fprintf(stderr, "shaft modal m=%d: estimate %.3e, error %.3e, max|λ| %.15f (full %.15f)\n",
                 m, r.summary.error_estimate, err, r.max_abs_multiplier, ref.max_abs_multiplier);
  }
  for (const double tol : {1e-4, 1e-6, 1e-8, 1e-10}) {
    FloquetOptions o = base;
    o.method = FloquetMethod::kArpackMonodromy;
    o.arpack_nev = 6;
    o.tolerance = tol;
    FloquetResult r;
    const double time = wp::TimeIt([&] { r = ComputeFloquet(model, o); });
    // Each returned multiplier against the nearest full one, and max|λ| against the full one.
    const double err = std::max(NearestError(r.multipliers, ref.multipliers),
                                std::abs(r.max_abs_multiplier - ref.max_abs_multiplier));
    Emit("shaft/arpack_monodromy", tol, time, err, r);
    std::fprintf(stderr,
                 "shaft arpack tol=%g: estimate %.3e, error %.3e, applications %ld, status %s, "
                 "max|λ| %.15f (full %.15f)\n",
                 tol, r.summary.error_estimate, err, r.summary.counters.at("operator_applications"),
                 StatusName(r.summary.status), r.max_abs_multiplier, ref.max_abs_multiplier);
  }
}

}  // namespace

int main() {
  std::printf("method,knob,wall_time_s,error,evaluations\n");
  Sdof();
  Pair12();
  Shaft();
  return 0;
}
