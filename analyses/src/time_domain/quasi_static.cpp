/// @file
/// @brief SimulateQuasiStatic: the slow roll under load (time_response.hpp) — a static solve at
/// every θ sample (shared system phase, or each mesh's own cycle) and, per mesh, the loaded TE,
/// tangent mesh stiffness, mesh force pair and the LTV transmission error ε_η; with a regularised
/// continuation start where the flanks are apart (singular Newton tangent).
#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <Eigen/QR>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <numbers>
#include <sstream>

#include "geardyn/analyses/time_response.hpp"
#include "geardyn/common/check.hpp"
#include "geardyn/common/errors.hpp"
#include "geardyn/system/probes.hpp"
#include "static_continuation.hpp"
#include "td_symmetry.hpp"
#include "td_system.hpp"

namespace geardyn {
namespace {

using internal::SolveBordered;
using internal::TdMeshTerm;

// Regularised continuation (see SimulateQuasiStatic): λ bounds, its factors and the iteration
// limit. λ = 1 weighs the tangent and the stand-in stiffness equally; below kLambdaMin the step
// is plain Newton (λ = 0); above kLambdaMax no step reduces the residual: no contact found.
constexpr double kLambdaStart = 1.0;
constexpr double kLambdaMin = 1e-10;
constexpr double kLambdaMax = 1e12;
constexpr int kRegularisedIterations = 400;
// Accepted steps at λ ≤ kLambdaMin without a residual reduction before giving up.
constexpr int kStalledSteps = 20;
// Newton's step criterion of SolveStatic (td_system.cpp): ‖dx‖∞ ≤ 1e-12 ‖x‖∞.
constexpr double kStepTolerance = 1e-12;
// A residual this small relative to the load ‖f0‖∞ is an equilibrium even with a singular
// tangent (free play: zero mesh load inside the backlash).
constexpr double kFreePlayResidual = 1e-10;
// Displacement whose force on the stiffest spring sets the force scale without a load [m].
constexpr double kRestDisplacement = 1e-9;

/// The 2×2 tangent ∂F/∂δ of a NonlinearMeshCore: its internal coordinates condensed out of the
/// core's stiffness (K_pp − K_pi K_ii⁻¹ K_ip, 12×12 on the pair), then K2 = G⁺ᵀ K₁₂ G⁺ (exact when
/// the condensed stiffness acts through δ = G q_pair only, as a mesh's must).
Matrix2 CoreTangent(const TdMeshTerm& t, const MatrixX& k) {
  MatrixX k12 = k.topLeftCorner(12, 12);
  if (t.num_internal > 0) {
    const MatrixX kii = k.bottomRightCorner(t.num_internal, t.num_internal);
    const MatrixX kip = k.bottomLeftCorner(t.num_internal, 12);
    const Eigen::LDLT<MatrixX> ldlt(kii);
    if (ldlt.info() == Eigen::Success) k12 -= kip.transpose() * ldlt.solve(kip);
  }
  const Eigen::CompleteOrthogonalDecomposition<MatrixX> cod(MatrixX(t.G.transpose()));
  const MatrixX gp = cod.pseudoInverse();  // (2×12) G⁺ᵀ = (G Gᵀ)⁻¹ G
  return gp * k12 * gp.transpose();
}

/// F = −A f₁₂ (A = (G Gᵀ)⁻¹ G) of a NonlinearMeshCore: its force on the 12 body coordinates
/// projected on the mesh deflections (time_response.hpp QuasiStaticMesh::force_pair).
Vector2 CoreForcePair(const TdMeshTerm& t, const VectorX& core_force) {
  const Eigen::CompleteOrthogonalDecomposition<MatrixX> cod(MatrixX(t.G.transpose()));
  const MatrixX a = cod.pseudoInverse();
  return -(a * core_force.head(12));
}

/// One static solve with its outcome.
struct StaticSolve {
  VectorX x;
  bool ok = false;
  bool regularised = false;  ///< SolveStatic failed; the continuation found the equilibrium
  bool free_play = false;    ///< equilibrium at a singular tangent (no mesh load)
  int iterations = 0;        ///< Newton's, then the continuation's
  std::string message;
};

/// Levenberg–Marquardt continuation from x0: (K_t + λ R) dx = r, bordered on the rigid modes,
/// R the mean stiffness with the stand-in mesh springs (sys.guess_stiffness) and the cores'
/// internal tangents at rest. A step that does not increase ‖r‖ is taken and λ ← λ/10 (0 below
/// kLambdaMin: Newton), otherwise λ ← 10λ. With the flanks apart under load ‖r‖ stays flat and
/// the growing steps close the gap; once in contact it is Newton.
StaticSolve RegularisedStatic(const internal::TdSystem& sys, internal::TdWorkspace& ws,
                              double theta, const VectorX& x0) {
  StaticSolve out;
  const VectorX zero = VectorX::Zero(sys.n);
  const MatrixX mv = sys.mass * sys.rigid_modes;
  EvalForces(sys, ws, theta, 0.0, zero, zero, true);
  const MatrixX reg = internal::RestStiffness(sys, ws);
  // Force scale of "equilibrium already": the load, or without load the force of 1 nm on the
  // stiffest regularising spring (round-off of a state at rest).
  const double load_scale = std::max(sys.load0.lpNorm<Eigen::Infinity>(),
                                     kRestDisplacement * reg.diagonal().cwiseAbs().maxCoeff());
  VectorX x = x0.allFinite() ? x0 : zero;
  double lambda = kLambdaStart;
  EvalForces(sys, ws, theta, 0.0, x, zero, true);
  VectorX r = ws.force;
  MatrixX kt = ws.tangent_k;
  int stalled = 0;  // accepted near-Newton steps that did not reduce the residual
  for (int it = 0; it < kRegularisedIterations && stalled < kStalledSteps; ++it) {
    out.iterations = it + 1;
    const double r_norm = r.norm();
    if (r.lpNorm<Eigen::Infinity>() <= kFreePlayResidual * load_scale) {
      // Equilibrium already (zero load, or a free-play position): nothing to move.
      out.x = x;
      out.ok = out.regularised = true;
      return out;
    }
    VectorX dx;
    const bool solved = SolveBordered(kt + lambda * reg, mv, r, &dx);
    if (!solved) {
      if (lambda == 0.0) {
        lambda = kLambdaMin;
        continue;
      }
      out.message = "static equilibrium: the regularised system is singular (an unsupported body)";
      return out;
    }
    const VectorX trial = x + dx;
    EvalForces(sys, ws, theta, 0.0, trial, zero, true);
    if (ws.force.allFinite() && ws.force.norm() <= r_norm) {
      // Flat residual with (almost) no regularisation left: the flanks do not close.
      stalled = lambda <= kLambdaMin && ws.force.norm() >= (1.0 - 1e-9) * r_norm ? stalled + 1 : 0;
      x = trial;
      r = ws.force;
      kt = ws.tangent_k;
      const double scale = std::max(x.lpNorm<Eigen::Infinity>(), 1e-300);
      if (lambda <= 1e-6 && dx.lpNorm<Eigen::Infinity>() <= kStepTolerance * scale) {
        out.x = x;
        out.ok = out.regularised = true;
        return out;
      }
      lambda = lambda * 0.1 < kLambdaMin ? 0.0 : lambda * 0.1;
    } else {
      lambda = lambda == 0.0 ? kLambdaMin : 10.0 * lambda;
      if (lambda > kLambdaMax) break;
    }
  }
  std::ostringstream s;
  s << "static equilibrium: flanks apart — no tooth contact carries the load (Newton's tangent "
       "is singular and the regularised continuation stalled with the residual "
    << r.lpNorm<Eigen::Infinity>() << " against the force scale " << load_scale
    << "): the teeth cannot transmit the torque at this phase (contact ratio < 1, or the "
       "scene's backlash/geometry leaves no pair within reach)";
  out.message = s.str();
  return out;
}

/// The static equilibrium at θ: SolveStatic (Newton, warm start), and where it fails the
/// regularised continuation from the same start.
StaticSolve SolveQuasiStatic(const internal::TdSystem& sys, internal::TdWorkspace& ws, double theta,
                             const VectorX* start) {
  internal::TdStatic st = internal::SolveStatic(sys, ws, theta, start);
  if (!(st.ok && st.x.allFinite()) && start != nullptr) {
    // The warm start can stall where a cold one converges (tooth bodies: Newton with the
    // contact Jacobian that omits f ∂²δ/∂x² creeps from a neighbouring sample's state).
    const internal::TdStatic cold = internal::SolveStatic(sys, ws, theta, nullptr);
    if (cold.ok && cold.x.allFinite()) st = cold;
  }
  if (st.ok && st.x.allFinite()) {
    StaticSolve out;
    out.x = st.x;
    out.ok = true;
    out.iterations = st.iterations;
    return out;
  }
  const VectorX x0 = start != nullptr ? *start : VectorX::Zero(sys.n);
  StaticSolve out = RegularisedStatic(sys, ws, theta, x0);
  if (!out.ok && start != nullptr) {
    StaticSolve cold = RegularisedStatic(sys, ws, theta, VectorX::Zero(sys.n));
    if (cold.ok) out = std::move(cold);
  }
  if (!out.ok && out.message.empty()) out.message = st.message;
  out.iterations += st.iterations;
  return out;
}

/// Allocates mesh q's arrays for `samples` samples.
void Allocate(QuasiStaticMesh& q, Eigen::Index samples) {
  q.loaded_te = q.dte = q.force = q.theta = q.mesh_phase = q.transmission_error =
      VectorX::Zero(samples);
  q.stiffness = MatrixX::Zero(3, samples);
  q.force_pair = MatrixX::Zero(2, samples);
  q.contacts = Eigen::VectorXi::Constant(samples, -1);
}

/// Keeps the first `done` samples of mesh q.
void Truncate(QuasiStaticMesh& q, Eigen::Index done) {
  for (VectorX* v :
       {&q.loaded_te, &q.dte, &q.force, &q.theta, &q.mesh_phase, &q.transmission_error}) {
    v->conservativeResize(done);
  }
  q.stiffness.conservativeResize(3, done);
  q.force_pair.conservativeResize(2, done);
  q.contacts.conservativeResize(done);
}

/// Mesh k's quantities at the static state x (ws evaluated there with jacobians), column s.
void Record(const internal::TdSystem& sys, const internal::TdWorkspace& ws, ProbeWorkspace& probe,
            int k, double theta, const VectorX& x, Eigen::Index s, QuasiStaticMesh& q) {
  const SystemModel& model = sys.model;
  const auto kk = static_cast<std::size_t>(k);
  const TdMeshTerm& t = sys.terms[kk];
  const auto q_sys = x.head(sys.num_dofs);
  const Vector2 delta = CalcMeshDeflection(model, MeshIndex(k), q_sys);
  Vector2 f = Vector2::Zero();
  Matrix2 j;
  if (t.kind == TdMeshTerm::Kind::kNonlinear) {
    j = CoreTangent(t, ws.core_out[kk].stiffness);
    f = CoreForcePair(t, ws.core_out[kk].force);
    q.dte(s) = delta(0);  // no ε for a contact core: DTE = δ_η
  } else {
    j = ws.mesh_tangent[kk];
    const MeshProbeValues p = EvalMeshProbe(model, probe, MeshIndex(k), theta, q_sys, VectorX());
    f = p.force;
    q.dte(s) = p.dte;
  }
  // The symmetric tangent (K, K·h, K·μ·b²): K2 = [[K, −K·h], [−K·h, K·μ·b²]].
  Matrix2 k2;
  k2 << j(0, 0), 0.5 * (j(0, 1) + j(1, 0)), 0.5 * (j(0, 1) + j(1, 0)), j(1, 1);
  q.theta(s) = theta;
  q.mesh_phase(s) = t.phase_ratio * theta + t.phase_offset;
  q.loaded_te(s) = delta(0);
  q.force(s) = t.kind == TdMeshTerm::Kind::kNonlinear ? f(0) : ws.force_eta[kk];
  q.force_pair.col(s) = f;
  q.stiffness(0, s) = k2(0, 0);
  q.stiffness(1, s) = -k2(0, 1);
  q.stiffness(2, s) = k2(1, 1);
  // ε = δ − K2⁺ F: the LTV mesh's static deflection ε + K2⁻¹F is then δ (K2 = 0: ε = δ).
  const Vector2 eps = delta - k2.completeOrthogonalDecomposition().solve(f);
  q.transmission_error(s) = eps.allFinite() ? eps(0) : delta(0);
  q.contacts(s) = ws.contacts[kk];
}

/// Counts and warnings of the solves.
struct RollStats {
  long solves = 0;
  long regularised = 0;
  long free_play = 0;
};

/// True when some mesh carries no load at this equilibrium while its tangent is zero (free play).
bool MeshInFreePlay(const internal::TdSystem& sys, const internal::TdWorkspace& ws) {
  for (const TdMeshTerm& t : sys.terms) {
    const auto kk = static_cast<std::size_t>(t.mesh);
    if (ws.contacts[kk] == 0) return true;
  }
  return false;
}

}  // namespace

namespace internal {

TdStatic SolveStaticWithContinuation(const TdSystem& sys, TdWorkspace& ws, double theta0,
                                     const VectorX* start) {
  const StaticSolve st = SolveQuasiStatic(sys, ws, theta0, start);
  TdStatic out;
  out.x = st.ok ? st.x : VectorX::Zero(sys.n);
  out.ok = st.ok;
  out.iterations = st.iterations;
  out.message = st.message;
  return out;
}

}  // namespace internal

bool QuasiStaticOptions::IsValid(std::string* why) const {
  std::ostringstream s;
  if (samples_per_mesh < 1 || samples_per_mesh > 65536)
    s << "samples_per_mesh: must be in [1, 65536], got " << samples_per_mesh;
  else if (period_multiple < 1 || period_multiple > 1000)
    s << "period_multiple: must be in [1, 1000], got " << period_multiple;
  else if (sampling != QuasiStaticSampling::kSystemPhase &&
           sampling != QuasiStaticSampling::kMeshCycle)
    s << "sampling: not a QuasiStaticSampling value";
  else
    return true;
  if (why != nullptr) *why = s.str();
  return false;
}

QuasiStaticResult SimulateQuasiStatic(const SystemModel& model, const QuasiStaticOptions& options,
                                      const TimeProgress& progress,
                                      const std::atomic<bool>* cancel) {
  std::string why;
  if (!options.IsValid(&why)) throw InvalidInput("SimulateQuasiStatic: " + why);
  GEARDYN_THROW_UNLESS(model.num_meshes() > 0, "SimulateQuasiStatic: the model has no meshes");
  const auto start = std::chrono::steady_clock::now();
  const internal::TdSystem sys(model);
  internal::TdWorkspace ws(sys);
  ProbeWorkspace probe(sys.model);
  const bool per_mesh = options.sampling == QuasiStaticSampling::kMeshCycle;
  const std::int64_t P = per_mesh ? 1 : model.period_meshes() * options.period_multiple;
  const std::int64_t total = P * options.samples_per_mesh;
  GEARDYN_THROW_UNLESS(total <= 10000000, "SimulateQuasiStatic: " << total
                                                                  << " θ samples (samples_per_mesh"
                                                                     " × P × period_multiple) "
                                                                     "exceed 1e7");
  const int m = model.num_meshes();
  const auto samples = static_cast<Eigen::Index>(total);
  QuasiStaticResult out;
  out.theta = VectorX::Zero(samples);
  out.meshes.resize(static_cast<std::size_t>(m));
  for (int k = 0; k < m; ++k) {
    QuasiStaticMesh& q = out.meshes[static_cast<std::size_t>(k)];
    q.name = model.meshes()[static_cast<std::size_t>(k)].name;
    Allocate(q, samples);
  }
  RollStats stats;
  VectorX dte(m);
  const long total_solves = static_cast<long>(per_mesh ? samples * m : samples);
  // One roll: `samples` static solves at the system phases theta_of(s), each warm-started from
  // the previous one; records the meshes [k_lo, k_hi). Returns the samples done.
  auto roll = [&](const auto& theta_of, int k_lo, int k_hi, VectorX* last) -> Eigen::Index {
    VectorX previous;
    for (Eigen::Index s = 0; s < samples; ++s) {
      if (cancel != nullptr && cancel->load()) {
        out.summary.status = Status::kInterrupted;
        out.summary.message = "cancelled";
        return s;
      }
      const double theta = theta_of(s);
      const StaticSolve st =
          SolveQuasiStatic(sys, ws, theta, previous.size() > 0 ? &previous : nullptr);
      ++stats.solves;
      if (!st.ok) {
        out.summary.status = Status::kNotConverged;
        std::ostringstream msg;
        msg << st.message << " (θ = " << theta << " rad";
        if (per_mesh) msg << ", mesh " << out.meshes[static_cast<std::size_t>(k_lo)].name;
        msg << ", sample " << s << ")";
        out.summary.message = msg.str();
        return s;
      }
      if (st.regularised) ++stats.regularised;
      previous = st.x;
      internal::EvalForces(sys, ws, theta, 0.0, st.x, VectorX::Zero(sys.n), true);
      if (MeshInFreePlay(sys, ws)) ++stats.free_play;
      EvalMeshDte(model, theta, st.x.head(sys.num_dofs), dte);
      for (int k = k_lo; k < k_hi; ++k) {
        QuasiStaticMesh& q = out.meshes[static_cast<std::size_t>(k)];
        Record(sys, ws, probe, k, theta, st.x, s, q);
        if (sys.terms[static_cast<std::size_t>(k)].kind != TdMeshTerm::Kind::kNonlinear) {
          q.dte(s) = dte(k);
        }
      }
      if (progress && stats.solves % 64 == 0) {
        progress(static_cast<double>(stats.solves) / static_cast<double>(total_solves),
                 "static solve " + std::to_string(stats.solves));
      }
    }
    if (last != nullptr) *last = previous;
    return samples;
  };

  Eigen::Index done = 0;
  if (!per_mesh) {
    const auto theta_of = [&](Eigen::Index s) {
      return 2.0 * std::numbers::pi * static_cast<double>(P) * static_cast<double>(s) /
             static_cast<double>(samples);
    };
    done = roll(theta_of, 0, m, nullptr);
    for (Eigen::Index s = 0; s < done; ++s) out.theta(s) = theta_of(s);
    for (QuasiStaticMesh& q : out.meshes) {
      if (done < samples) Truncate(q, done);
    }
  } else {
    for (Eigen::Index s = 0; s < samples; ++s) {
      out.theta(s) = 2.0 * std::numbers::pi * static_cast<double>(s) / static_cast<double>(samples);
    }
    done = samples;
    for (int k = 0; k < m && out.summary.ok(); ++k) {
      const TdMeshTerm& t = sys.terms[static_cast<std::size_t>(k)];
      const auto theta_of = [&](Eigen::Index s) {
        return (out.theta(s) - t.phase_offset) / t.phase_ratio;
      };
      VectorX last;
      const Eigen::Index d = roll(theta_of, k, k + 1, &last);
      QuasiStaticMesh& q = out.meshes[static_cast<std::size_t>(k)];
      if (d < samples) {
        // This mesh keeps the samples it has; the meshes after it were not rolled.
        Truncate(q, d);
        for (int k2 = k + 1; k2 < m; ++k2) Truncate(out.meshes[static_cast<std::size_t>(k2)], 0);
        done = d;
        break;
      }
      const std::int64_t pk = PeriodMeshes(model.meshes()[static_cast<std::size_t>(k)].core);
      if (!options.check_next_cycle || pk <= 1) continue;
      // The same mesh phase one cycle later (θ_k = 2π), continued from the last sample.
      const double theta = (2.0 * std::numbers::pi - t.phase_offset) / t.phase_ratio;
      const StaticSolve st = SolveQuasiStatic(sys, ws, theta, last.size() > 0 ? &last : nullptr);
      ++stats.solves;
      if (!st.ok) continue;  // next_cycle_change stays NaN
      QuasiStaticMesh next;
      Allocate(next, 1);
      internal::EvalForces(sys, ws, theta, 0.0, st.x, VectorX::Zero(sys.n), true);
      Record(sys, ws, probe, k, theta, st.x, 0, next);
      const double k0 = q.stiffness(0, 0), ste0 = q.loaded_te(0);
      const double dk = std::abs(next.stiffness(0, 0) - k0) / std::max(std::abs(k0), 1e-300);
      const double ds = std::abs(next.loaded_te(0) - ste0) / std::max(std::abs(ste0), 1e-300);
      q.next_cycle_change = std::max(dk, ds);
    }
  }
  if (stats.free_play > 0) {
    out.summary.warnings.push_back(
        std::to_string(stats.free_play) +
        " static solve(s) ended with a mesh out of contact under no mesh load (free play in the "
        "backlash: the static position there is not unique, the starting one is kept; K = 0 and "
        "ε_η = δ_η at those samples)");
  }
  out.summary.counters["samples"] = static_cast<long>(done);
  out.summary.counters["static_solves"] = stats.solves;
  out.summary.counters["regularised_starts"] = stats.regularised;
  out.summary.counters["free_play_samples"] = stats.free_play;
  out.summary.wall_time_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

TimeRunEstimate EstimateTimeRun(const SystemModel& model, double mesh_frequency_hz,
                                const TimeResponseOptions& options) {
  GEARDYN_THROW_UNLESS(
      std::isfinite(mesh_frequency_hz) && mesh_frequency_hz > 0.0,
      "EstimateTimeRun: mesh_frequency_hz must be > 0 and finite, got " << mesh_frequency_hz);
  std::string why;
  if (!options.IsValid(&why)) throw InvalidInput("EstimateTimeRun: " + why);
  GEARDYN_THROW_UNLESS(model.num_meshes() > 0, "EstimateTimeRun: the model has no meshes");
  const internal::TdSystem sys(model);
  internal::TdWorkspace ws(sys);
  TimeRunEstimate out;
  const SteadyStateOptions& so = options.steady;
  out.min_periods = static_cast<long>(std::max(2, so.min_periods)) + so.consecutive_periods - 1 +
                    so.record_periods;
  out.min_periods = std::min<long>(out.min_periods, so.max_periods + so.record_periods);
  // The period the run's steady test uses (the symmetry period of identical tooth bodies unless
  // switched off: td_symmetry.hpp), not the model's hunting period.
  const double cycles = static_cast<double>(
      internal::MakeTdSymmetry(sys, so.use_symmetry).period_meshes * so.period_multiple);
  out.min_simulated_time_s = static_cast<double>(out.min_periods) * cycles / mesh_frequency_hz;
  out.static_deflection.assign(static_cast<std::size_t>(model.num_meshes()), 0.0);
  const double theta0 = options.initial_phase;
  const StaticSolve st = SolveQuasiStatic(sys, ws, theta0, nullptr);
  if (!st.ok) {
    out.summary.status = Status::kNotConverged;
    out.summary.message = st.message;
    return out;
  }
  for (int k = 0; k < model.num_meshes(); ++k) {
    out.static_deflection[static_cast<std::size_t>(k)] =
        CalcMeshDeflection(model, MeshIndex(k), st.x.head(sys.num_dofs))(0);
  }
  const double w_max = internal::EstimateHighestFrequency(sys, ws, theta0, st.x);
  out.highest_frequency_hz = w_max / (2.0 * std::numbers::pi);
  out.highest_mode_cycles = out.highest_frequency_hz * out.min_simulated_time_s;
  return out;
}

}  // namespace geardyn
