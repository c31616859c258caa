/// @file
/// @brief SimulateSteadyState, SimulateSweep, SimulateSpeeds and SolveTimeDomainStatic: the
/// period loop with steady-state detection, the energy balance per period and the recording.
#include "geardyn/analyses/time_response.hpp"

#include <omp.h>

#include <Eigen/LU>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <complex>
#include <exception>
#include <iomanip>
#include <limits>
#include <numbers>
#include <sstream>

#include "../floquet/floquet_internal.hpp"
#include "geardyn/analyses/harmonic_balance.hpp"
#include "geardyn/common/check.hpp"
#include "geardyn/common/errors.hpp"
#include "geardyn/system/probes.hpp"
#include "static_continuation.hpp"
#include "td_steppers.hpp"
#include "td_symmetry.hpp"
#include "td_system.hpp"

namespace geardyn {
namespace {

using internal::TdScales;
using internal::TdSystem;
using internal::TdWorkspace;

/// Fraction of a period's gross energy flow G below which the energy balance does not resolve
/// the net flows (time_response.hpp, "Energy balance") [-].
constexpr double kGrossFlowFloor = 1e-3;

/// Growth of a mesh's max |DTE| over its first period beyond which a run is unbounded [-].
constexpr double kGrowthLimit = 1e4;

/// True when no period dissipated energy: D ≤ 1e-12 × the period's largest energy term (|W|,
/// |ΔS|) in every period, and some period moved energy at all. Such a model (no damping
/// anywhere) never settles: its free vibration from the starting state persists.
bool Undamped(const std::vector<EnergyBalancePeriod>& energy) {
  bool moved = false;
  for (const EnergyBalancePeriod& e : energy) {
    const double scale = std::max(std::abs(e.input_work), std::abs(e.stored_change));
    if (!(e.dissipated <= 1e-12 * scale)) return false;
    moved = moved || scale > 0.0;
  }
  return moved;
}

/// ": undamped modes …" naming the modes of the mean system without damping (ζ < 1e-9, as
/// Floquet's marginal verdict lists them), or "" when there are none or the modal analysis does
/// not apply (a tooth-contact core, whose stiffness and damping the mean system lacks): a transient
/// in such a mode never decays, which is why a run does not settle although the model dissipates
/// energy elsewhere.
std::string UndampedModesNote(const SystemModel& model) {
  // The modal model of a tooth-contact core lacks its stiffness and damping: no diagnosis.
  for (const SystemMesh& m : model.meshes()) {
    if (std::holds_alternative<std::shared_ptr<const NonlinearMeshCore>>(m.core)) return "";
  }
  std::vector<UndampedMode> modes;
  try {
    modes = internal::UndampedModes(model);
  } catch (const std::exception&) {
    return "";  // a diagnostic only
  }
  if (modes.empty()) return "";
  std::ostringstream note;
  note << ": the mean system has undamped modes (";
  constexpr std::size_t kListed = 4;
  for (std::size_t i = 0; i < std::min(modes.size(), kListed); ++i) {
    note << (i > 0 ? ", " : "") << std::setprecision(6) << modes[i].frequency_hz << " Hz ("
         << modes[i].dominant_dof << ")";
  }
  if (modes.size() > kListed) note << ", … " << modes.size() - kListed << " more";
  note << "): if the run excites them, their transient never decays; add damping there (e.g. "
          "bearing damping)";
  return note.str();
}

/// Worse of two statuses (kSuccess < kToleranceNotMet < kNotConverged < kNumericalIssue <
/// kInterrupted: an interrupted sweep says so whatever its points did).
Status Worse(Status a, Status b) {
  auto rank = [](Status s) {
    switch (s) {
      case Status::kSuccess:
        return 0;
      case Status::kToleranceNotMet:
        return 1;
      case Status::kNotConverged:
        return 2;
      case Status::kNumericalIssue:
        return 3;
      case Status::kInterrupted:
        return 4;
    }
    return 4;
  };
  return rank(a) >= rank(b) ? a : b;
}

/// Error scales from a reference state: c_i = max(|x_i|, 1e-3·max|x|) (1e-6 without any
/// deflection), velocities ω_v·c_i with ω_v = max(ω_m, ω_floor).
///
/// ω_floor (issue 16): double precision cannot resolve a velocity finer than about
/// ε·ω_max·c (round-off of an acceleration ~ ω_max² c over a step ~ 1/ω_max, ω_max the highest
/// natural frequency). At a very low speed (1e-3 Hz on a 4.6 kHz pair: ω_m/ω_max = 2e-7) the
/// velocity tolerance atol·ω_m·c fell below that round-off, generalized-α's Newton never met
/// it, and ~1e6 steps were rejected. The velocity scale is floored so that the Newton test
/// (update ≤ newton_tolerance × atol·scale) stays 10× above round-off:
/// ω_floor = min(ω_max, 10 ε ω_max / (atol·newton_tolerance)). It is below ω_m (no change) at
/// every ordinary speed: ω_m/ω_max > 2e-3 at atol = 1e-10, > 2e-5 at the default 1e-8.
TdScales MakeScales(const VectorX& x, double omega, double w_max,
                    const TimeIntegrationOptions& io) {
  TdScales s;
  double top = x.lpNorm<Eigen::Infinity>();
  if (!(top > 0.0)) top = 1e-6;
  s.x = x.cwiseAbs().cwiseMax(1e-3 * top);
  const double eps = std::numeric_limits<double>::epsilon();
  const double floor =
      std::isfinite(w_max)
          ? std::min(w_max, 10.0 * eps * w_max / (io.absolute_tolerance * io.newton_tolerance))
          : 0.0;
  s.v = std::max(omega, floor) * s.x;
  return s;
}

/// The periodic solution of the linear HB at θ₀ (TimeResponseOptions::
/// start_from_linear_steady_state): q = Q_0 + 2 Re Σ_k Q_k e^{ikθ/P}, q̇ = 2 Re Σ_k ikΩ Q_k
/// e^{ikθ/P}, Ω = ω_m/P (harmonic_balance.hpp). False (the caller keeps the static start) when
/// the mean system has an undamped mode (no attracting periodic orbit: the run from the static
/// start reports the transient that never decays), or the HB throws, fails or gives non-finite
/// harmonics.
bool LinearSteadyStart(const SystemModel& model, double f_m, double theta0, double tolerance,
                       VectorX* x, VectorX* v) {
  try {
    if (!internal::UndampedModes(model).empty()) return false;
  } catch (const std::exception&) {
    return false;
  }
  HbOptions ho;
  ho.tolerance = std::max(tolerance, 1e-10);
  ho.max_harmonics = 128;
  ho.compute_forces = false;
  ho.keep_harmonics = true;
  HbResult hb;
  try {
    hb = SolveHarmonicBalance(model, ho, f_m);
  } catch (const std::exception&) {
    return false;  // a model the linear HB does not take: the static start
  }
  const bool usable =
      hb.summary.status == Status::kSuccess || hb.summary.status == Status::kToleranceNotMet;
  const MatrixXc& q = hb.response_harmonics;
  if (!usable || q.size() == 0 || !q.allFinite() || q.rows() != model.num_dofs()) return false;
  const double P = static_cast<double>(hb.period_meshes);
  const double big_omega = 2.0 * std::numbers::pi * f_m / P;
  *x = VectorX::Zero(q.rows());
  *v = VectorX::Zero(q.rows());
  for (Eigen::Index j = 0; j < q.cols(); ++j) {
    const int k =
        hb.sparse_harmonics ? hb.kept_harmonics[static_cast<std::size_t>(j)] : static_cast<int>(j);
    const std::complex<double> z = std::polar(1.0, k * theta0 / P);
    if (k == 0) {
      *x += q.col(j).real();
      continue;
    }
    const VectorXc qz = q.col(j) * z;
    *x += 2.0 * qz.real();
    *v += -2.0 * k * big_omega * qz.imag();  // 2 Re(ikΩ Q_k z)
  }
  return x->allFinite() && v->allFinite();
}

/// Running statistics of a sampled signal.
struct Stats {
  double sum = 0.0, sum2 = 0.0, lo = std::numeric_limits<double>::infinity(),
         hi = -std::numeric_limits<double>::infinity();
  long count = 0;
  void Add(double v) {
    sum += v;
    sum2 += v * v;
    lo = std::min(lo, v);
    hi = std::max(hi, v);
    ++count;
  }
  double Mean() const { return count > 0 ? sum / static_cast<double>(count) : 0.0; }
  /// RMS of v − mean.
  double Rms() const {
    if (count == 0) return 0.0;
    const double m = Mean();
    return std::sqrt(std::max(sum2 / static_cast<double>(count) - m * m, 0.0));
  }
};

/// One run at one speed on an existing TdSystem (see SimulateSteadyState).
TimeResponse Run(const TdSystem& sys, double f_m, const TimeResponseOptions& options,
                 const TimeProgress& progress, const std::atomic<bool>* cancel) {
  const auto start = std::chrono::steady_clock::now();
  TimeResponse out;
  out.mesh_frequency_hz = f_m;
  Summary& summary = out.summary;
  const SystemModel& model = sys.model;
  const int n = sys.n;
  const int num_meshes = model.num_meshes();
  const double omega = 2.0 * std::numbers::pi * f_m;
  const double theta0 = options.initial_phase;
  const TimeIntegrationOptions& io = options.integration;
  const SteadyStateOptions& so = options.steady;
  if (sys.unbalanced_fraction > 1e-8) {
    summary.warnings.push_back(
        "the constant load has a part along the rigid-body modes (relative size " +
        std::to_string(sys.unbalanced_fraction) +
        ") that the supports cannot react; it was removed (the train would accelerate)");
  }
  auto finish = [&]() {
    summary.wall_time_s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return out;
  };

  // Initial state.
  TdWorkspace ws(sys);
  VectorX x0(n), v0 = VectorX::Zero(n);
  VectorX reference;
  if (options.start_from_static) {
    const internal::TdStatic st = internal::SolveStaticWithContinuation(sys, ws, theta0);
    if (!st.ok) {
      summary.status = Status::kNumericalIssue;
      summary.message = st.message;
      return finish();
    }
    x0 = st.x;
    reference = st.x;
    if (options.start_from_linear_steady_state && !sys.has_nonlinear() && sys.n == sys.num_dofs) {
      VectorX xh, vh;
      if (LinearSteadyStart(model, f_m, theta0, so.tolerance, &xh, &vh)) {
        x0 = xh;
        v0 = vh;
        summary.counters["linear_hb_start"] = 1;
      }
    }
  } else {
    GEARDYN_THROW_UNLESS(options.initial_state.size() == 2 * n,
                         "initial_state: must have 2·(num_dofs + internal) = "
                             << 2 * n << " entries, got " << options.initial_state.size());
    x0 = options.initial_state.head(n);
    v0 = options.initial_state.tail(n);
    reference = x0;
  }

  // kAuto: explicit unless the highest frequency times the accuracy step is large (stiff).
  const double mesh_period = 2.0 * std::numbers::pi / omega;
  TimeIntegrationOptions run_io = io;  // kAuto may change ρ∞ (below)
  TimeIntegrator method = io.integrator;
  const double w_max = internal::EstimateHighestFrequency(sys, ws, theta0, x0);
  if (method == TimeIntegrator::kAuto) {
    const double ratio = w_max * mesh_period / io.samples_per_period;
    method = ratio < io.auto_stiffness_limit ? TimeIntegrator::kRungeKutta
                                             : TimeIntegrator::kGeneralizedAlpha;
    if (method == TimeIntegrator::kGeneralizedAlpha && ratio > kAutoQuasiStaticStiffness &&
        run_io.spectral_radius > 0.0) {
      // Issue 16 (time_response.hpp, TimeIntegrationOptions::integrator): annihilate the
      // unresolved modes in one step instead of ρ∞ per step.
      run_io.spectral_radius = 0.0;
      summary.counters["auto_rho_zero"] = 1;
    }
    summary.counters["auto_stiffness_ratio_x1000"] = static_cast<long>(1000.0 * ratio);
  }
  out.integrator_used = method;
  auto stepper = internal::MakeStepper(method, sys, run_io, MakeScales(reference, omega, w_max, io),
                                       omega, theta0);
  stepper->Reset(0.0, x0, v0);

  // The period of the steady test: P_S mesh cycles, over which the steady state repeats up to
  // the cores' relabelling S of their internal coordinates (td_symmetry.hpp).
  const internal::TdSymmetry symmetry = internal::MakeTdSymmetry(sys, so.use_symmetry);
  const std::int64_t P = symmetry.period_meshes * so.period_multiple;
  out.period_meshes = P;
  if (symmetry.any_shift()) summary.counters["symmetry_shift"] = 1;
  if (symmetry.quasi_periodic) {
    summary.warnings.push_back(
        "meshes at incommensurate frequencies (no common period of at most " +
        std::to_string(internal::kMaxCommonPeriodMeshes) +
        " mesh cycles): the steady response is quasi-periodic and the steady test over " +
        std::to_string(P) +
        " mesh cycles cannot pass; the quasi-periodic harmonic balance (geardyn hb) solves it");
  }
  // S x: the state a steady response has one period after x (rigid projection commutes with S:
  // S keeps M and the rigid modes, which do not move the tooth coordinates).
  const auto shifted = [&](VectorX y) -> VectorX {
    internal::ApplyTdSymmetry(sys, symmetry, so.period_multiple, y);
    return y;
  };
  const double period = mesh_period * static_cast<double>(P);
  const long samples = static_cast<long>(io.samples_per_period) * P;
  // Every size has a bound (architecture §3.7): the recorded histories.
  GEARDYN_THROW_UNLESS(
      static_cast<double>(samples) * so.record_periods <= 5e7,
      "samples_per_period × P × period_multiple × record_periods = "
          << static_cast<double>(samples) * so.record_periods
          << " recorded samples (8 bytes each per mesh and element component) exceed 5e7");
  VectorX dte(num_meshes);
  std::vector<double> prev_rms(static_cast<std::size_t>(num_meshes), -1.0);
  // y − V (VᵀMV)⁻¹ VᵀM y: removes the rigid-body part of a state vector.
  const MatrixX mv = sys.mass * sys.rigid_modes;
  const MatrixX vmv_inv = (sys.rigid_modes.transpose() * mv).inverse();
  const auto rigid_projector = [&](const VectorX& y) -> VectorX {
    if (sys.rigid_modes.cols() == 0) return y;
    return y - sys.rigid_modes * (vmv_inv * (mv.transpose() * y));
  };
  // A tooth-contact core is not invariant under the train's free rotation V: a rigid rotation
  // shifts the actual mesh phase against θ. The mesh losses D then act as a mean torque along V
  // that the constant loads (balanced at build time) do not supply, and the train slips behind
  // the nominal rotation (rig, type A: ≈ 0.03 rad/s after 120 cycles); the response sampled at
  // the period starts drifts in phase and never repeats (the 64–120 kHz tooth ringing turns the
  // slip into a 1e-2 change per cycle). The drive of a test rig holds the speed: between
  // transient periods the rigid-mode parts of x and v are reset to those of the start state (a
  // speed-and-phase governor acting once per period; inside a period, and in the recorded ones,
  // the train is free as before). Cores that act on G q only (linear, slice) are invariant under
  // V: nothing is reset for them.
  const bool hold_rigid = sys.has_nonlinear() && sys.rigid_modes.cols() > 0;
  const VectorX rigid_start = hold_rigid ? VectorX(vmv_inv * (mv.transpose() * x0)) : VectorX();
  long rigid_resets = 0;
  // The expected state at the next period start if the response were steady: S × this one.
  VectorX prev_x = shifted(rigid_projector(x0)), prev_v = shifted(rigid_projector(v0));
  int consecutive = 0;
  // Largest period-to-period change in the third and in the last quarter of max_periods: their
  // ratio is the decay of a slowly settling transient (the message of a run that ends unsteady).
  const int quarter = so.max_periods / 4;
  double third_quarter_change = 0.0, last_quarter_change = 0.0, final_change = 0.0;
  std::vector<double> first_level(static_cast<std::size_t>(num_meshes), 0.0);
  int grown = -1;
  bool steady = false;
  bool failed = false;
  long period_index = 0;

  Eigen::Index recorded = 0;  // samples written to the histories
  // The DTE of the period being integrated and of the last complete one (kept as the history of
  // a failed or cancelled run, which records nothing after the transient).
  VectorX current_time = VectorX::Zero(samples), last_time;
  MatrixX current_dte = MatrixX::Zero(num_meshes, samples), last_dte;
  auto record_meta = [&]() {
    out.steps = stepper->steps();
    out.events = stepper->events();
    summary.counters["steps"] = stepper->steps();
    summary.counters["rejected_steps"] = stepper->rejected();
    summary.counters["events"] = stepper->events();
    summary.counters["coefficient_jumps"] = stepper->breaks();
    summary.counters["force_evaluations"] = stepper->evaluations();
    out.final_state.resize(2 * n);
    out.final_state << stepper->x(), stepper->v();
    out.final_phase = stepper->Phase(stepper->t());
    for (const EnergyBalancePeriod& e : out.energy) {
      if (!(e.relative_error <= out.max_energy_error)) out.max_energy_error = e.relative_error;
    }
    summary.error_estimate = out.max_energy_error;
  };

  // Integrates one period; when `histories` is set, appends the samples to the output.
  auto integrate_period = [&](bool histories, std::vector<Stats>* stats,
                              std::vector<long>* loss) -> bool {
    const double t_begin = static_cast<double>(period_index) * period;
    ws.force.setZero();
    internal::EvalForces(sys, ws, stepper->Phase(stepper->t()), omega, stepper->x(), stepper->v(),
                         false);
    const double s_begin = internal::StoredEnergy(sys, ws, stepper->x(), stepper->v());
    const VectorX x_begin = stepper->x();
    stepper->ResetQuadrature();
    for (long s = 1; s <= samples; ++s) {
      if (!stepper->AdvanceTo(t_begin +
                              period * static_cast<double>(s) / static_cast<double>(samples))) {
        // A step budget exhausted is "did not finish" (kNotConverged, as time_response.hpp
        // documents for max_steps; issue 16), anything else a numerical failure.
        summary.status =
            stepper->budget_exhausted() ? Status::kNotConverged : Status::kNumericalIssue;
        summary.message = stepper->message();
        return false;
      }
      const double t = stepper->t();
      const double theta = stepper->Phase(t);
      EvalMeshDte(model, theta, stepper->x().head(sys.num_dofs), dte);
      current_time(s - 1) = t;
      current_dte.col(s - 1) = dte;
      for (int k = 0; k < num_meshes; ++k) {
        (*stats)[static_cast<std::size_t>(k)].Add(dte(k));
      }
      if (!dte.allFinite()) {
        summary.status = Status::kNumericalIssue;
        summary.message = "time integration: non-finite DTE at t = " + std::to_string(t) + " s";
        return false;
      }
      if (!histories && loss == nullptr) continue;
      internal::EvalForces(sys, ws, theta, omega, stepper->x(), stepper->v(), false);
      for (int k = 0; k < num_meshes; ++k) {
        const auto kk = static_cast<std::size_t>(k);
        if (ws.contacts[kk] == 0) ++(*loss)[kk];
      }
      if (!histories) continue;
      // Buffers preallocated for all recorded periods (no per-sample reallocation).
      const Eigen::Index at = recorded++;
      out.time(at) = t;
      for (int k = 0; k < num_meshes; ++k) {
        MeshTimeHistory& h = out.meshes[static_cast<std::size_t>(k)];
        h.dte(at) = dte(k);
        const internal::TdMeshTerm& term = sys.terms[static_cast<std::size_t>(k)];
        if (term.kind != internal::TdMeshTerm::Kind::kNonlinear) {
          h.force(at) = ws.force_eta[static_cast<std::size_t>(k)];
        } else if (at % io.channel_decimation == 0) {
          h.channels.col(at / io.channel_decimation) =
              ws.core_out[static_cast<std::size_t>(k)].channels;
        }
      }
      if (io.record_element_forces) {
        for (std::size_t e = 0; e < model.elements().size(); ++e) {
          MatrixX& f = out.element_forces[e];
          CalcElementForce(model, ElementIndex(static_cast<int>(e)),
                           stepper->x().head(sys.num_dofs), stepper->v().head(sys.num_dofs),
                           f.col(at));
        }
      }
    }
    // Energy balance of the period: W = f0ᵀΔx + ∫ΣP, ΔS, D.
    internal::EvalForces(sys, ws, stepper->Phase(stepper->t()), omega, stepper->x(), stepper->v(),
                         false);
    EnergyBalancePeriod e;
    e.stored_change = internal::StoredEnergy(sys, ws, stepper->x(), stepper->v()) - s_begin;
    e.input_work = sys.load0.dot(stepper->x() - x_begin) + stepper->phase_work();
    e.dissipated = stepper->dissipated();
    e.gross_flow = stepper->gross_flow();
    // Against the net flows, with a floor of 1e-3 of the energy moved (time_response.hpp,
    // "Energy balance"): the quadrature's resolution, reached only at quasi-static speeds.
    const double scale =
        std::max({std::abs(e.input_work), std::abs(e.stored_change), std::abs(e.dissipated),
                  kGrossFlowFloor * e.gross_flow, 1e-9 * std::abs(s_begin)});
    e.relative_error =
        scale > 0.0 ? std::abs(e.input_work - e.stored_change - e.dissipated) / scale : 0.0;
    out.energy.push_back(e);
    ++period_index;
    if (!histories) {
      last_time = current_time;
      last_dte = current_dte;
    }
    return true;
  };

  // Transient: period by period until steady.
  for (int p = 0; p < so.max_periods; ++p) {
    if (cancel != nullptr && cancel->load()) {
      summary.status = Status::kInterrupted;
      summary.message = "cancelled";
      failed = true;
      break;
    }
    std::vector<Stats> stats(static_cast<std::size_t>(num_meshes));
    if (!integrate_period(false, &stats, nullptr)) {
      failed = true;
      break;
    }
    out.periods = p + 1;
    if (hold_rigid) {
      const VectorX cx = vmv_inv * (mv.transpose() * stepper->x()) - rigid_start;
      const VectorX cv = vmv_inv * (mv.transpose() * stepper->v());
      const VectorX x_held = stepper->x() - sys.rigid_modes * cx;
      const VectorX v_held = stepper->v() - sys.rigid_modes * cv;
      stepper->Reset(stepper->t(), x_held, v_held);
      ++rigid_resets;
      summary.counters["rigid_resets"] = rigid_resets;
    }
    // Period-to-period change of the state at the period start and of each mesh's DTE RMS.
    // Rigid-body motion (a free rotation of the train) is not vibration: the change is measured
    // in the M-orthogonal complement of the rigid modes.
    const VectorX x = rigid_projector(stepper->x());
    const VectorX v = rigid_projector(stepper->v());
    const double xn = x.lpNorm<Eigen::Infinity>(), vn = v.lpNorm<Eigen::Infinity>();
    // Velocities against max(‖v‖, ω_m‖x‖): at rest ‖v‖ is round-off and its relative change
    // meaningless.
    double change = xn > 0.0 ? (x - prev_x).lpNorm<Eigen::Infinity>() / xn : 0.0;
    const double v_scale = std::max(vn, omega * xn);
    if (v_scale > 0.0) {
      change = std::max(change, (v - prev_v).lpNorm<Eigen::Infinity>() / v_scale);
    }
    // Unbounded growth (parametric instability, an undamped resonance): max |DTE| of a mesh
    // beyond kGrowthLimit × its first period's ends the run without a steady state.
    for (int k = 0; k < num_meshes; ++k) {
      const auto kk = static_cast<std::size_t>(k);
      const double level = std::max(std::abs(stats[kk].lo), std::abs(stats[kk].hi));
      if (p == 0) first_level[kk] = level;
      if (first_level[kk] > 0.0 && level > kGrowthLimit * first_level[kk]) grown = k;
    }
    if (grown >= 0) {
      const auto kk = static_cast<std::size_t>(grown);
      summary.status = Status::kNotConverged;
      summary.message =
          "the response grows without bound: max |DTE| of mesh '" + model.meshes()[kk].name +
          "' went from " + std::to_string(first_level[kk]) + " m to " +
          std::to_string(std::max(std::abs(stats[kk].lo), std::abs(stats[kk].hi))) + " m in " +
          std::to_string(p + 1) +
          " periods (parametric instability or an undamped resonance: no steady state)";
      failed = true;
      break;
    }
    for (int k = 0; k < num_meshes; ++k) {
      const auto kk = static_cast<std::size_t>(k);
      const double rms = stats[kk].Rms();
      // RMS changes relative to max(RMS, 1e-6·|mean|): a response at rest has an RMS of
      // round-off.
      const double denom = std::max(rms, 1e-6 * std::abs(stats[kk].Mean()));
      if (prev_rms[kk] < 0.0) {
        change = std::max(change, 1.0);
      } else if (denom > 0.0) {
        change = std::max(change, std::abs(rms - prev_rms[kk]) / denom);
      }
      prev_rms[kk] = rms;
    }
    if (!std::isfinite(change)) {
      summary.status = Status::kNumericalIssue;
      summary.message =
          "time integration: non-finite state at the end of period " + std::to_string(p + 1);
      failed = true;
      break;
    }
    prev_x = shifted(x);
    prev_v = shifted(v);
    consecutive = (p + 1 >= so.min_periods && change < so.tolerance) ? consecutive + 1 : 0;
    if (quarter > 0 && p >= 2 * quarter && p < 3 * quarter) {
      third_quarter_change = std::max(third_quarter_change, change);
    } else if (quarter > 0 && p >= 3 * quarter) {
      last_quarter_change = std::max(last_quarter_change, change);
    }
    final_change = change;
    if (progress) {
      progress(static_cast<double>(p + 1) / so.max_periods,
               "period " + std::to_string(p + 1) + ", change " + std::to_string(change));
    }
    if (consecutive >= so.consecutive_periods) {
      steady = true;
      break;
    }
  }
  if (!failed && !steady) {
    summary.status = Status::kNotConverged;
    summary.message = "not steady after max_periods = " + std::to_string(so.max_periods) +
                      " periods (tolerance " + std::to_string(so.tolerance) + ")";
    // An undamped model keeps its starting transient forever: say so instead of leaving the
    // user to raise max_periods (the energy balance gives D per period for free).
    if (Undamped(out.energy)) {
      summary.message +=
          ": the model dissipates no energy (D = 0 in every period: no damping in the meshes, "
          "bearings, shafts or teeth), so the free vibration started from the static "
          "equilibrium never decays and no steady state exists; add damping (a mesh's "
          "damping_ratio, the [mesh.contact] damping of a tooth-contact mesh, bearing damping)";
    } else {
      summary.message += UndampedModesNote(model);
      // Issue 16: a transient that decays, only too slowly (a lightly damped mode far below the
      // mesh frequency: ~1.3e4 periods at 1e6 Hz on a 4.6 kHz pair with ζ = 0.05), gets an
      // estimate of the periods it needs. The maxima over a quarter of the run each span many
      // cycles of the free vibration sampled once per period, so their ratio is the envelope's.
      const double rate = quarter >= 8 && third_quarter_change > 0.0 && last_quarter_change > 0.0
                              ? std::pow(last_quarter_change / third_quarter_change, 1.0 / quarter)
                              : std::numeric_limits<double>::quiet_NaN();
      if (rate > 0.0 && rate < 1.0 - 1e-9 && std::isfinite(rate)) {
        out.transient_decay_per_period = rate;
        const double more =
            std::log(so.tolerance / std::max(final_change, so.tolerance)) / std::log(rate);
        const double needed = static_cast<double>(so.max_periods) + std::max(more, 0.0);
        std::ostringstream note;
        note << std::setprecision(3) << "; the transient decays by a factor " << rate
             << " per period (the free vibration of a lightly damped mode): about " << needed
             << " periods would reach the tolerance — raise max_periods (--max-periods) to "
             << static_cast<long>(std::ceil(1.2 * needed)) << ", or start closer to the steady "
             << "state (a linear model starts from the linear HB solution)";
        summary.message += note.str();
      }
    }
  }

  // Recording (also after a non-steady end, so that the last periods can be inspected; never
  // after a numerical failure).
  if (!failed) {
    const Eigen::Index total = static_cast<Eigen::Index>(samples) * so.record_periods;
    const Eigen::Index decimated = (total + io.channel_decimation - 1) / io.channel_decimation;
    out.time = VectorX::Zero(total);
    out.meshes.resize(static_cast<std::size_t>(num_meshes));
    for (int k = 0; k < num_meshes; ++k) {
      MeshTimeHistory& h = out.meshes[static_cast<std::size_t>(k)];
      h.name = model.meshes()[static_cast<std::size_t>(k)].name;
      h.dte = VectorX::Zero(total);
      const internal::TdMeshTerm& term = sys.terms[static_cast<std::size_t>(k)];
      if (term.kind == internal::TdMeshTerm::Kind::kNonlinear) {
        h.channel_names = term.nonlinear->channel_names();
        h.channels = MatrixX::Zero(static_cast<Eigen::Index>(h.channel_names.size()), decimated);
      } else {
        h.force = VectorX::Zero(total);
      }
    }
    if (io.record_element_forces) {
      for (const SystemElement& e : model.elements()) {
        out.element_forces.push_back(
            MatrixX::Zero(static_cast<Eigen::Index>(e.dofs.size()), total));
      }
    }
    std::vector<Stats> stats(static_cast<std::size_t>(num_meshes));
    std::vector<long> loss(static_cast<std::size_t>(num_meshes), 0);
    for (int p = 0; p < so.record_periods; ++p) {
      if (!integrate_period(true, &stats, &loss)) break;
    }
    if (recorded < total) {  // a failed recording keeps the samples written so far
      out.time.conservativeResize(recorded);
      for (MeshTimeHistory& h : out.meshes) {
        h.dte.conservativeResize(recorded);
        if (h.force.size() > 0) h.force.conservativeResize(recorded);
        h.channels.conservativeResize(
            h.channels.rows(), (recorded + io.channel_decimation - 1) / io.channel_decimation);
      }
      for (MatrixX& f : out.element_forces) f.conservativeResize(f.rows(), recorded);
    }
    for (int k = 0; k < num_meshes; ++k) {
      const auto kk = static_cast<std::size_t>(k);
      MeshTimeHistory& h = out.meshes[kk];
      h.mean_dte = stats[kk].Mean();
      h.rms_dte = stats[kk].Rms();
      h.peak_to_peak_dte = stats[kk].count > 0 ? stats[kk].hi - stats[kk].lo : 0.0;
      h.contact_loss_fraction =
          stats[kk].count > 0 ? static_cast<double>(loss[kk]) / static_cast<double>(stats[kk].count)
                              : 0.0;
    }
  }
  if (failed && last_time.size() > 0 && last_dte.allFinite()) {
    // A failed or cancelled run: the last complete transient period as the DTE history (no
    // forces, channels or element forces), flagged history_from_transient.
    out.history_from_transient = true;
    out.time = last_time;
    out.meshes.resize(static_cast<std::size_t>(num_meshes));
    for (int k = 0; k < num_meshes; ++k) {
      MeshTimeHistory& h = out.meshes[static_cast<std::size_t>(k)];
      h.name = model.meshes()[static_cast<std::size_t>(k)].name;
      h.dte = last_dte.row(k).transpose();
      h.mean_dte = h.dte.mean();
      h.rms_dte = std::sqrt((h.dte.array() - h.mean_dte).square().mean());
      h.peak_to_peak_dte = h.dte.maxCoeff() - h.dte.minCoeff();
    }
  }
  record_meta();
  out.steady = summary.ok() && steady ? SteadyVerdict::kSteady : SteadyVerdict::kUndetermined;
  if (summary.ok() && !(out.max_energy_error <= 1e-4)) {
    summary.warnings.push_back("energy balance error " + std::to_string(out.max_energy_error) +
                               " of a period's work exceeds 1e-4: tighten the tolerances");
  }
  return finish();
}

void CheckFrequency(double f, const char* what) {
  GEARDYN_THROW_UNLESS(std::isfinite(f) && f > 0.0,
                       what << ": mesh frequency must be finite and > 0 Hz, got " << f);
}

void CheckModel(const SystemModel& model, const char* what) {
  GEARDYN_THROW_UNLESS(model.num_meshes() > 0, what << ": the model has no meshes");
}

}  // namespace

TimeResponse SimulateSteadyState(const SystemModel& model, double mesh_frequency_hz,
                                 const TimeResponseOptions& options, const TimeProgress& progress,
                                 const std::atomic<bool>* cancel) {
  std::string why;
  if (!options.IsValid(&why)) throw InvalidInput("SimulateSteadyState: " + why);
  CheckFrequency(mesh_frequency_hz, "SimulateSteadyState");
  CheckModel(model, "SimulateSteadyState");
  const TdSystem sys(model);
  return Run(sys, mesh_frequency_hz, options, progress, cancel);
}

TimeSweep SimulateSweep(const SystemModel& model, const std::vector<double>& frequencies_hz,
                        const TimeSweepOptions& options, const TimeProgress& progress,
                        const std::atomic<bool>* cancel) {
  std::string why;
  if (!options.IsValid(&why)) throw InvalidInput("SimulateSweep: " + why);
  CheckModel(model, "SimulateSweep");
  GEARDYN_THROW_UNLESS(!frequencies_hz.empty(), "SimulateSweep: frequencies_hz is empty");
  for (std::size_t i = 0; i < frequencies_hz.size(); ++i) {
    CheckFrequency(frequencies_hz[i], "SimulateSweep");
    GEARDYN_THROW_UNLESS(i == 0 || frequencies_hz[i] > frequencies_hz[i - 1],
                         "SimulateSweep: frequencies_hz must be strictly increasing (entry "
                             << i << " = " << frequencies_hz[i] << ")");
  }
  const auto start = std::chrono::steady_clock::now();
  const TdSystem sys(model);
  TimeSweep sweep;
  const int count = static_cast<int>(frequencies_hz.size());
  const int total = count * ((options.up ? 1 : 0) + (options.down ? 1 : 0));
  int done = 0;
  VectorX carried;  // final state of the last point (the up branch hands it to the down one)
  double carried_phase = options.response.initial_phase;
  long steps = 0, events = 0;
  for (SweepBranch branch : {SweepBranch::kUp, SweepBranch::kDown}) {
    if ((branch == SweepBranch::kUp && !options.up) ||
        (branch == SweepBranch::kDown && !options.down))
      continue;
    for (int i = 0; i < count; ++i) {
      if (cancel != nullptr && cancel->load()) {
        sweep.summary.status = Worse(sweep.summary.status, Status::kInterrupted);
        sweep.summary.message = "cancelled";
        sweep.summary.counters["points"] = static_cast<long>(sweep.points.size());
        return sweep;
      }
      const int idx = branch == SweepBranch::kUp ? i : count - 1 - i;
      const double f = frequencies_hz[static_cast<std::size_t>(idx)];
      TimeResponseOptions o = options.response;
      o.integration.record_element_forces = false;
      if (carried.size() > 0) {
        o.start_from_static = false;
        o.initial_state = carried;
        o.initial_phase = carried_phase;
      }
      const TimeResponse r = Run(sys, f, o, {}, cancel);
      TimeSweepPoint pt;
      pt.mesh_frequency_hz = f;
      pt.branch = branch;
      for (const MeshTimeHistory& h : r.meshes) {
        pt.rms_dte.push_back(h.rms_dte);
        pt.mean_dte.push_back(h.mean_dte);
        pt.peak_to_peak_dte.push_back(h.peak_to_peak_dte);
        pt.contact_loss_fraction.push_back(h.contact_loss_fraction);
      }
      pt.periods = r.periods;
      pt.steady = r.steady;
      pt.max_energy_error = r.max_energy_error;
      pt.status = r.summary.status;
      pt.message = r.summary.message;
      sweep.points.push_back(pt);
      steps += r.steps;
      events += r.events;
      ++done;
      if (progress) {
        progress(static_cast<double>(done) / total,
                 std::string(ToString(branch)) + " " + std::to_string(f) + " Hz");
      }
      if (!r.summary.ok()) {
        sweep.summary.status = Worse(sweep.summary.status, r.summary.status);
        if (sweep.summary.message.empty()) sweep.summary.message = r.summary.message;
        if (r.summary.status == Status::kInterrupted) return sweep;
        // Not steady within max_periods: the point is kept without a verdict and the sweep goes
        // on from its last state (a quasi-periodic or slowly settling response is still the
        // branch). A numerical failure ends the branch.
        const bool fatal = r.summary.status == Status::kNumericalIssue || r.final_state.size() == 0;
        sweep.summary.warnings.push_back(std::string(ToString(branch)) + " branch " +
                                         (fatal ? "stopped" : "not steady") + " at " +
                                         std::to_string(f) + " Hz: " + r.summary.message);
        if (fatal) {
          carried.resize(0);  // the next branch starts afresh
          carried_phase = options.response.initial_phase;
          break;
        }
        if (r.summary.message.rfind("the response grows", 0) == 0) {
          // Unbounded here (an instability region): the next point starts afresh, the branch
          // goes on.
          carried.resize(0);
          carried_phase = options.response.initial_phase;
          continue;
        }
      }
      carried = r.final_state;
      carried_phase = r.final_phase;
    }
  }
  sweep.summary.counters["steps"] = steps;
  sweep.summary.counters["events"] = events;
  sweep.summary.counters["points"] = static_cast<long>(sweep.points.size());
  sweep.summary.wall_time_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return sweep;
}

std::vector<TimeResponse> SimulateSpeeds(const SystemModel& model,
                                         const std::vector<double>& frequencies_hz,
                                         const TimeResponseOptions& options, int threads,
                                         const TimeProgress& progress,
                                         const std::atomic<bool>* cancel) {
  std::string why;
  if (!options.IsValid(&why)) throw InvalidInput("SimulateSpeeds: " + why);
  CheckModel(model, "SimulateSpeeds");
  GEARDYN_THROW_UNLESS(threads >= 0, "SimulateSpeeds: threads must be ≥ 0, got " << threads);
  for (double f : frequencies_hz) CheckFrequency(f, "SimulateSpeeds");
  const TdSystem sys(model);  // immutable, shared; every run has its own workspaces
  const int count = static_cast<int>(frequencies_hz.size());
  std::vector<TimeResponse> out(static_cast<std::size_t>(count));
  std::exception_ptr error;
  std::atomic<int> done{0};
  const int num_threads = threads > 0 ? threads : std::max(1, omp_get_max_threads());
#pragma omp parallel for schedule(dynamic, 1) num_threads(num_threads)
  for (int i = 0; i < count; ++i) {
    try {
      out[static_cast<std::size_t>(i)] =
          Run(sys, frequencies_hz[static_cast<std::size_t>(i)], options, {}, cancel);
    } catch (...) {
#pragma omp critical(geardyn_time_speeds_error)
      if (!error) error = std::current_exception();
    }
    const int d = ++done;
    if (progress && omp_get_thread_num() == 0) {
      progress(static_cast<double>(d) / count,
               std::to_string(d) + " of " + std::to_string(count) + " speeds");
    }
  }
  if (error) std::rethrow_exception(error);
  return out;
}

TimeDomainStatic SolveTimeDomainStatic(const SystemModel& model, double theta0) {
  GEARDYN_THROW_UNLESS(std::isfinite(theta0),
                       "SolveTimeDomainStatic: theta0 must be finite, got " << theta0);
  CheckModel(model, "SolveTimeDomainStatic");
  const TdSystem sys(model);
  TdWorkspace ws(sys);
  const internal::TdStatic st = internal::SolveStaticWithContinuation(sys, ws, theta0);
  TimeDomainStatic out;
  out.state = st.x;
  out.iterations = st.iterations;
  if (!st.ok) {
    out.summary.status = Status::kNotConverged;
    out.summary.message = st.message;
  }
  out.summary.counters["iterations"] = st.iterations;
  return out;
}

}  // namespace geardyn
