/// @file
/// @brief TdSystem: the time-domain equation of a SystemModel and the force kernel EvalForces.
#include "td_system.hpp"

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <variant>

#include "geardyn/common/check.hpp"
#include "geardyn/common/overloaded.hpp"
#include "geardyn/numerics/rigid_modes.hpp"
#include "geardyn/system/static_deflection.hpp"
#include "geardyn/system/system_harmonics.hpp"
#include "geardyn/system/workspace.hpp"

namespace geardyn::internal {
namespace {

/// Step of the central difference that gives the phase power ∂E/∂θ_k·θ̇_k of linear and slice
/// cores [rad]: the truncation error O(h²·E''') is ~1e-10 of E for θ-coefficients with mesh
/// harmonics up to ~30, far below the 1e-4 target of the energy balance.
constexpr double kPhaseStep = 1e-5;

/// Stand-in mesh stiffness of a NonlinearMeshCore for the rigid-mode detection and the static
/// starting guess only [N/m] (the order of a gear mesh's; Newton then uses the core's tangent).
constexpr double kStandInMeshStiffness = 1e9;

/// θ-mean of a slice core's all-loaded damping C2 = (c_m/Σk_s) K2 from samples (used when the
/// harmonic expansion is not available: a phase ratio ≠ 1).
Matrix2 SampledSliceDamping(const SliceMeshCore& core, double c_m) {
  SliceMeshWorkspace ws(core);
  const std::int64_t P = PeriodMeshes(core);
  const int samples = 256 * static_cast<int>(P);
  Matrix2 sum = Matrix2::Zero();
  for (int s = 0; s < samples; ++s) {
    const double th = 2.0 * std::numbers::pi * static_cast<double>(P) * s / samples;
    const Vector3 c = EvalSliceChannels(core, ws, th);
    if (c(0) > 0.0) {
      Matrix2 k2;
      k2 << c(0), -c(1), -c(1), c(2);
      sum += (c_m / c(0)) * k2;
    }
  }
  return sum / samples;
}

/// Appends the jumps of a piecewise-constant coefficient and the nodes of a table (kinks of its
/// linear interpolation); returns the coefficient's shape.
CoefficientShape AddBreaks(const Coefficient& coef,
                           std::vector<std::pair<VectorX, double>>* breaks) {
  if (const auto* pc = std::get_if<PiecewiseConstantCoefficient>(&coef)) {
    if (pc->num_intervals() >= 2) breaks->emplace_back(pc->breakpoints(), Period(coef));
    return CoefficientShape::kStepwise;
  }
  if (const auto* tc = std::get_if<TableCoefficient>(&coef)) {
    VectorX nodes(tc->num_samples());
    for (int s = 0; s < tc->num_samples(); ++s) nodes(s) = tc->sample_theta(s);
    breaks->emplace_back(nodes, Period(coef));
    return CoefficientShape::kKinked;
  }
  return CoefficientShape::kSmooth;
}

/// Half-width of the phase gap stepped across at a break of mesh phase θ_k [rad]: well above
/// the rounding of θ_k, far below any physical scale (≈ 1.6e-10 mesh periods).
double BreakGap(double theta_k) { return 1e-9 + 1e-13 * std::abs(theta_k); }

/// Step of the central difference of the phase power for a coefficient of the given shape:
/// smooth kPhaseStep; a table a quarter of the break gap, so that both points lie in the
/// interval of the evaluation point (the steps end at the nodes, the difference of a linear
/// piece is then exact); 0 for stepwise (held: its jumps are phase events).
double PhaseStep(CoefficientShape shape, double theta_k) {
  switch (shape) {
    case CoefficientShape::kSmooth:
      return kPhaseStep;
    case CoefficientShape::kKinked:
      return 0.25 * BreakGap(theta_k);
    case CoefficientShape::kStepwise:
      return 0.0;
  }
  return 0.0;
}

}  // namespace

void AppendTriplets(const SparseMatrixRowMajor& a, double scale,
                    std::vector<Eigen::Triplet<double>>* out) {
  for (int i = 0; i < a.outerSize(); ++i)
    for (SparseMatrixRowMajor::InnerIterator it(a, i); it; ++it)
      out->emplace_back(static_cast<int>(it.row()), static_cast<int>(it.col()), scale * it.value());
}

TdSystem::TdSystem(const SystemModel& m) : model(m) {
  num_dofs = model.num_dofs();
  // Internal coordinates of the nonlinear cores, appended mesh by mesh.
  int internal = 0;
  int switching = 0;
  bool all_unit_ratio = true;
  bool any_slice = false;
  for (int k = 0; k < model.num_meshes(); ++k) {
    const SystemMesh& mesh = model.meshes()[k];
    TdMeshTerm t;
    t.mesh = k;
    t.dofs = mesh.dofs;
    t.G = mesh.G;
    t.phase_ratio = mesh.phase_ratio;
    t.phase_offset = mesh.phase_offset;
    t.damping_coefficient = mesh.damping_coefficient;
    all_unit_ratio = all_unit_ratio && mesh.phase_ratio == 1.0;
    std::visit(Overloaded{
                   [&](const LinearMeshCore& core) {
                     t.kind = TdMeshTerm::Kind::kLinear;
                     t.linear = &core;
                     if (!core.is_mean_lti()) {
                       t.stiffness_shape = AddBreaks(core.stiffness(), &t.breaks);
                     }
                     if (core.transmission_error()) {
                       t.offset_shape = AddBreaks(*core.transmission_error(), &t.breaks);
                     }
                   },
                   [&](const SliceMeshCore& core) {
                     t.kind = TdMeshTerm::Kind::kSlice;
                     t.slice = &core;
                     t.stiffness_shape = AddBreaks(core.stiffness(), &t.breaks);
                     if (core.separation()) {
                       t.offset_shape = AddBreaks(*core.separation(), &t.breaks);
                     }
                     t.num_switching = core.num_slices() * (core.has_back_flank() ? 2 : 1);
                     any_slice = true;
                   },
                   [&](const std::shared_ptr<const NonlinearMeshCore>& core) {
                     GEARDYN_THROW_UNLESS(core != nullptr, "time integration: mesh '"
                                                               << mesh.name
                                                               << "' has a null NonlinearMeshCore");
                     t.kind = TdMeshTerm::Kind::kNonlinear;
                     t.nonlinear = core.get();
                     t.num_internal = core->num_internal_coordinates();
                     t.num_switching = core->num_switching_functions();
                   },
               },
               mesh.core);
    has_breaks = has_breaks || !t.breaks.empty();
    t.internal_offset = num_dofs + internal;
    internal += t.num_internal;
    t.switching_offset = switching;
    switching += t.num_switching;
    terms.push_back(t);
  }
  n = num_dofs + internal;
  num_switching = switching;

  // Slice cores: the nonlinear HB's C̄ (θ-mean of the all-loaded mesh damping, exact harmonic
  // m = 0 of system_harmonics.hpp), so that simulate integrates the equation the HB solves.
  if (any_slice) {
    std::vector<MeshHarmonics> h;
    if (all_unit_ratio) h = ExpandMeshHarmonics(model, 0);
    for (TdMeshTerm& t : terms) {
      if (t.kind != TdMeshTerm::Kind::kSlice) continue;
      t.mean_damping = all_unit_ratio
                           ? Matrix2(h[static_cast<std::size_t>(t.mesh)].damping[0].real())
                           : SampledSliceDamping(*t.slice, t.damping_coefficient);
    }
  }

  mass = MatrixX::Zero(n, n);
  stiffness0 = MatrixX::Zero(n, n);
  damping0 = MatrixX::Zero(n, n);
  load0 = VectorX::Zero(n);
  mass.topLeftCorner(num_dofs, num_dofs) = model.DenseMass();
  stiffness0.topLeftCorner(num_dofs, num_dofs) = model.DenseConstantStiffness();
  damping0.topLeftCorner(num_dofs, num_dofs) = model.DenseConstantDamping();
  for (const TdMeshTerm& t : terms) {
    if (t.kind != TdMeshTerm::Kind::kNonlinear) continue;
    const MatrixX mi = t.nonlinear->InternalMass();
    GEARDYN_THROW_UNLESS(mi.rows() == t.nonlinear->num_coordinates() && mi.cols() == mi.rows(),
                         "time integration: InternalMass of mesh '"
                             << model.meshes()[t.mesh].name << "' must be "
                             << t.nonlinear->num_coordinates() << "×"
                             << t.nonlinear->num_coordinates());
    auto index = [&](int a) { return a < 12 ? t.dofs[a] : t.internal_offset + a - 12; };
    for (int a = 0; a < mi.rows(); ++a) {
      const int ia = index(a);
      if (ia < 0) continue;
      for (int b = 0; b < mi.cols(); ++b) {
        const int ib = index(b);
        if (ib >= 0) mass(ia, ib) += mi(a, b);
      }
    }
  }
  auto ldlt = std::make_shared<Eigen::LDLT<MatrixX>>(mass);
  GEARDYN_THROW_UNLESS(
      ldlt->info() == Eigen::Success && ldlt->isPositive() && ldlt->vectorD().minCoeff() > 0.0,
      "time integration: the mass matrix (system mass plus the cores' "
      "InternalMass) is not positive definite");
  mass_ldlt = ldlt;
  mass_solver = std::make_shared<const MassSolver>(mass, num_dofs);
  GEARDYN_THROW_UNLESS(mass_solver->ok(),
                       "time integration: the mass matrix (system mass plus the cores' "
                       "InternalMass) is not positive definite (block factorization)");
  mass_sparse = mass.sparseView(0.0, 0.0);

  // Rigid-body modes of the mean system stiffness: K0 + the mean linear/slice mesh terms +, for
  // every NonlinearMeshCore, a stand-in mesh spring Gᵀ diag(k_v, k_v·(1 cm)²) G on its mesh
  // Jacobian (the core resists the mesh deflection; its actual stiffness is unknown until it is
  // in contact). Internal coordinates are not part of a rigid motion (they are relative to the
  // trunks): zero rows. The part of f0 along the modes is removed M-consistently,
  // f0 − M V (VᵀMV)⁻¹ Vᵀ f0, so that the train does not accelerate (as SolveStaticDeflection and
  // the nonlinear HB remove it).
  SystemWorkspace sws(model, StorageKind::kDense);
  guess_stiffness = MatrixX::Zero(n, n);
  guess_stiffness.topLeftCorner(num_dofs, num_dofs) = AssembleMeanStiffness(model, sws);
  for (const TdMeshTerm& t : terms) {
    if (t.kind != TdMeshTerm::Kind::kNonlinear) continue;
    Matrix2 kv = Matrix2::Zero();
    kv(0, 0) = kStandInMeshStiffness;
    kv(1, 1) = kStandInMeshStiffness * 1e-4;
    const Matrix12 kp = t.G.transpose() * kv * t.G;
    for (int a = 0; a < 12; ++a) {
      if (t.dofs[a] < 0) continue;
      for (int b = 0; b < 12; ++b) {
        if (t.dofs[b] >= 0) guess_stiffness(t.dofs[a], t.dofs[b]) += kp(a, b);
      }
    }
  }
  const RigidBodyModes rigid =
      ComputeRigidBodyModes(guess_stiffness.topLeftCorner(num_dofs, num_dofs));
  const VectorX f0 = model.constant_load();
  load0.head(num_dofs) = f0;
  rigid_modes = MatrixX::Zero(n, rigid.count());
  if (rigid.count() > 0) {
    rigid_modes.topRows(num_dofs) = rigid.modes;
    const MatrixX mv = mass * rigid_modes;
    const MatrixX vmv = rigid_modes.transpose() * mv;
    const VectorX coef = vmv.ldlt().solve(rigid_modes.transpose() * load0);
    unbalanced_fraction = rigid.UnbalancedFraction(f0);
    load0 -= mv * coef;
  }
  stiffness0_sparse = stiffness0.sparseView(0.0, 0.0);
  damping0_sparse = damping0.sparseView(0.0, 0.0);
}

bool TdSystem::has_nonlinear() const {
  for (const TdMeshTerm& t : terms)
    if (t.kind == TdMeshTerm::Kind::kNonlinear) return true;
  return false;
}

double TdSystem::NextBreakTime(double t, double theta0, double omega, double* margin) const {
  double best = std::numeric_limits<double>::infinity();
  *margin = 0.0;
  const double theta = theta0 + omega * t;
  for (const TdMeshTerm& term : terms) {
    const double rate = term.phase_ratio * omega;
    if (term.breaks.empty() || rate == 0.0) continue;
    const double th = term.phase_ratio * theta + term.phase_offset;
    const double gap = BreakGap(th);
    for (const auto& [b, period] : term.breaks) {
      const double u = th - period * std::floor(th / period);  // in [0, period)
      double d = std::numeric_limits<double>::infinity();
      if (rate > 0.0) {
        const auto* it = std::upper_bound(b.data(), b.data() + b.size(), u);
        d = it != b.data() + b.size() ? *it - u : b(0) + period - u;
      } else {
        const auto* it = std::lower_bound(b.data(), b.data() + b.size(), u);
        d = it != b.data() ? u - *(it - 1) : u - (b(b.size() - 1) - period);
      }
      const double tb = t + d / std::abs(rate);
      if (tb < best) {
        best = tb;
        *margin = gap / std::abs(rate);
      }
    }
  }
  return best;
}

TdWorkspace::TdWorkspace(const TdSystem& sys) {
  force = VectorX::Zero(sys.n);
  tangent_k = MatrixX::Zero(sys.n, sys.n);
  tangent_c = MatrixX::Zero(sys.n, sys.n);
  switching = VectorX::Zero(sys.num_switching);
  switching_live.assign(static_cast<std::size_t>(sys.num_switching), 0);
  const std::size_t meshes = sys.terms.size();
  force_eta.assign(meshes, 0.0);
  contacts.assign(meshes, -1);
  mesh_tangent.assign(meshes, Matrix2::Zero());
  core_ws.resize(meshes);
  core_out.resize(meshes);
  core_x.resize(meshes);
  core_v.resize(meshes);
  slice.resize(meshes);
  slice_k.resize(meshes);
  slice_e.resize(meshes);
  for (const TdMeshTerm& t : sys.terms) {
    const auto k = static_cast<std::size_t>(t.mesh);
    if (t.kind == TdMeshTerm::Kind::kSlice) {
      slice[k] = std::make_unique<SliceMeshWorkspace>(*t.slice);
    } else if (t.kind == TdMeshTerm::Kind::kNonlinear) {
      core_ws[k] = t.nonlinear->MakeWorkspace();
      core_out[k] = t.nonlinear->MakeOutput();
      core_x[k] = VectorX::Zero(t.nonlinear->num_coordinates());
      core_v[k] = VectorX::Zero(t.nonlinear->num_coordinates());
    }
    if (t.kind == TdMeshTerm::Kind::kSlice) {
      slice_k[k] = VectorX::Zero(t.slice->num_slices());
      slice_e[k] = VectorX::Zero(t.slice->num_slices());
    }
  }
}

void EvalForces(const TdSystem& sys, TdWorkspace& ws, double theta, double theta_rate,
                const Eigen::Ref<const VectorX>& x, const Eigen::Ref<const VectorX>& v,
                bool with_jacobians) {
  ws.force = sys.load0;
  ws.mesh_phase_power = 0.0;
  // Harmonic loads f_h(θ) = Re(F e^{imθ}); their power f_hᵀv is booked with the phase power
  // (the work of a time-varying load is ∫ f_h(θ)ᵀ v dt, not f_hᵀΔx).
  for (const SystemHarmonicLoad& h : sys.model.harmonic_loads()) {
    const double c = std::cos(h.order * theta), s = std::sin(h.order * theta);
    for (int a = 0; a < kBodyDofs; ++a) {
      if (h.dofs[a] < 0) continue;
      const double f = h.amplitude(a).real() * c - h.amplitude(a).imag() * s;
      ws.force(h.dofs[a]) += f;
      ws.mesh_phase_power += f * v(h.dofs[a]);
    }
  }
  ws.force.noalias() -= sys.stiffness0_sparse * x;
  ws.force.noalias() -= sys.damping0_sparse * v;
  const bool sparse = with_jacobians && ws.sparse_tangents;
  auto& kt = ws.tangent_k_triplets;
  auto& ct = ws.tangent_c_triplets;
  if (sparse) {
    kt.clear();
    ct.clear();
    AppendTriplets(sys.stiffness0_sparse, 1.0, &kt);
    AppendTriplets(sys.damping0_sparse, 1.0, &ct);
  } else if (with_jacobians) {
    ws.tangent_k = sys.stiffness0;
    ws.tangent_c = sys.damping0;
  }
  ws.mesh_energy = 0.0;
  ws.mesh_dissipation = 0.0;
  for (const TdMeshTerm& t : sys.terms) {
    const auto k = static_cast<std::size_t>(t.mesh);
    const double th = t.phase_ratio * theta + t.phase_offset;
    const double th_rate = t.phase_ratio * theta_rate;
    if (t.kind == TdMeshTerm::Kind::kNonlinear) {
      VectorX& xk = ws.core_x[k];
      VectorX& vk = ws.core_v[k];
      for (int a = 0; a < 12; ++a) {
        xk(a) = t.dofs[a] >= 0 ? x(t.dofs[a]) : 0.0;
        vk(a) = t.dofs[a] >= 0 ? v(t.dofs[a]) : 0.0;
      }
      xk.tail(t.num_internal) = x.segment(t.internal_offset, t.num_internal);
      vk.tail(t.num_internal) = v.segment(t.internal_offset, t.num_internal);
      NonlinearMeshCoreOutput& out = ws.core_out[k];
      out.want_triplets = sparse;
      t.nonlinear->CalcForces(*ws.core_ws[k], th, th_rate, xk, vk, with_jacobians, &out);
      const int nc = static_cast<int>(xk.size());
      auto index = [&](int a) { return a < 12 ? t.dofs[a] : t.internal_offset + a - 12; };
      for (int a = 0; a < nc; ++a) {
        const int ia = index(a);
        if (ia >= 0) ws.force(ia) += out.force(a);
      }
      if (sparse && out.has_triplets) {
        // The core's own sparse Jacobians, mapped to the system's coordinates.
        for (const auto& e : out.stiffness_triplets) {
          const int ia = index(e.row()), ib = index(e.col());
          if (ia >= 0 && ib >= 0) kt.emplace_back(ia, ib, e.value());
        }
        for (const auto& e : out.damping_triplets) {
          const int ia = index(e.row()), ib = index(e.col());
          if (ia >= 0 && ib >= 0) ct.emplace_back(ia, ib, e.value());
        }
      } else if (with_jacobians) {
        for (int a = 0; a < nc; ++a) {
          const int ia = index(a);
          if (ia < 0) continue;
          for (int b = 0; b < nc; ++b) {
            const int ib = index(b);
            if (ib < 0) continue;
            const double kab = out.stiffness(a, b), cab = out.damping(a, b);
            if (!sparse) {
              ws.tangent_k(ia, ib) += kab;
              ws.tangent_c(ia, ib) += cab;
            } else {  // a dense-only core: its nonzeros
              if (kab != 0.0) kt.emplace_back(ia, ib, kab);
              if (cab != 0.0) ct.emplace_back(ia, ib, cab);
            }
          }
        }
      }
      ws.mesh_energy += out.energy;
      ws.mesh_dissipation += out.dissipation_power;
      ws.mesh_phase_power += out.phase_power;
      ws.contacts[k] = out.num_contacts;
      ws.force_eta[k] = 0.0;
      for (int i = 0; i < t.num_switching; ++i) {
        ws.switching(t.switching_offset + i) = out.switching(i);
        ws.switching_live[static_cast<std::size_t>(t.switching_offset + i)] = 1;
      }
      continue;
    }
    // Pair deflection δ = G q_pair and its rate.
    Vector2 delta = Vector2::Zero(), rate = Vector2::Zero();
    for (int a = 0; a < 12; ++a) {
      if (t.dofs[a] < 0) continue;
      delta += t.G.col(a) * x(t.dofs[a]);
      rate += t.G.col(a) * v(t.dofs[a]);
    }
    Vector2 F;
    Matrix2 J, C2;
    if (t.kind == TdMeshTerm::Kind::kLinear) {
      // F = K2(δ − ε) + C2 δ̇ (B–S Eq. 39); E = ½ eᵀK2e; P = ∂E/∂θ_k θ̇_k at fixed δ.
      const LinearMeshCore& core = *t.linear;
      // P = θ̇_k (∂E/∂θ_K + ∂E/∂θ_ε) at fixed δ: ∂E/∂θ_K = ½ eᵀK2'e, ∂E/∂θ_ε = −eᵀK2 ε'. A
      // Fourier stiffness gives K2 and K2' in one pass (its derivative is exact, and the ISO
      // series of a helical mesh has ~10³ terms: three passes per mesh and force evaluation were
      // most of a run's time); otherwise a central difference with the step of its shape
      // (stepwise: held, its jumps are phase events), and likewise for ε.
      Matrix2 dK = Matrix2::Zero();
      const auto* fourier = std::get_if<FourierCoefficient>(&core.stiffness());
      if (fourier != nullptr) {
        Vector3 c, dc;
        EvaluateWithDerivative(*fourier, th, c, dc);
        J = StiffnessCoreFromChannels(core.level(), c);
        dK = StiffnessCoreFromChannels(core.level(), dc);
      } else {
        J = EvalStiffnessCore(core, th);
        const double hk =
            Classify(core) != TimeDependence::kConstant ? PhaseStep(t.stiffness_shape, th) : 0.0;
        if (hk > 0.0) {
          dK = (EvalStiffnessCore(core, th + hk) - EvalStiffnessCore(core, th - hk)) / (2.0 * hk);
        }
      }
      // C2 = (c_m/K) K2 (B–S Eq. 39), as EvalDampingCore, from the K2 just evaluated.
      C2 = J(0, 0) > 0.0 ? Matrix2((t.damping_coefficient / J(0, 0)) * J) : Matrix2::Zero();
      const Vector2 e = delta - EvalTransmissionError(core, th);
      F = J * e + C2 * rate;
      ws.mesh_energy += 0.5 * e.dot(J * e);
      double dE = 0.5 * e.dot(dK * e);
      const double he = core.has_transmission_error() ? PhaseStep(t.offset_shape, th) : 0.0;
      if (he > 0.0) {
        const Vector2 de =
            (EvalTransmissionError(core, th + he) - EvalTransmissionError(core, th - he)) /
            (2.0 * he);
        dE -= e.dot(J * de);
      }
      ws.mesh_phase_power += th_rate * dE;
      ws.contacts[k] = -1;
    } else {
      // Slice force with contact loss and back flank; the constant damper C̄2 of the HB.
      const SliceMeshCore& core = *t.slice;
      SliceMeshWorkspace& sw = *ws.slice[k];
      const SliceForce f = EvalSliceForce(core, sw, th, delta(0), delta(1));
      // Phase power: one central difference per coefficient (stiffness k_s, separation e_s) with
      // the step of its shape (stepwise: held, its jumps are phase events).
      VectorX& ks = ws.slice_k[k];
      VectorX& es = ws.slice_e[k];
      double dU = 0.0;
      const double hk = PhaseStep(t.stiffness_shape, th);
      if (hk > 0.0) {
        const double tp = th + hk, tm = th - hk;
        Evaluate(core.stiffness(), tp, ks);
        const double up = CalcSliceForce(core, ks, sw.separation, delta(0), delta(1)).energy;
        Evaluate(core.stiffness(), tm, ks);
        const double um = CalcSliceForce(core, ks, sw.separation, delta(0), delta(1)).energy;
        dU += (up - um) / (tp - tm);
      }
      const double he = core.separation() ? PhaseStep(t.offset_shape, th) : 0.0;
      if (he > 0.0) {
        const double tp = th + he, tm = th - he;
        Evaluate(*core.separation(), tp, es);
        const double up = CalcSliceForce(core, sw.stiffness, es, delta(0), delta(1)).energy;
        Evaluate(*core.separation(), tm, es);
        const double um = CalcSliceForce(core, sw.stiffness, es, delta(0), delta(1)).energy;
        dU += (up - um) / (tp - tm);
      }
      C2 = t.mean_damping;
      J = f.jacobian;
      F = f.force + C2 * rate;
      ws.mesh_energy += f.energy;
      ws.mesh_phase_power += th_rate * dU;
      ws.contacts[k] = f.num_loaded;
      // Switching functions: drive gap a_s and back gap a_s + j of every slice; watched only
      // where the slice has stiffness (a gap of an unloaded slice switches nothing).
      const VectorX& sigma = core.sigma();
      const bool back = core.has_back_flank();
      const int ns = core.num_slices();
      for (int s = 0; s < ns; ++s) {
        const double a = delta(0) - sigma(s) * delta(1) - sw.separation(s);
        const char live = sw.stiffness(s) > 0.0 ? 1 : 0;
        const int i0 = t.switching_offset + (back ? 2 * s : s);
        ws.switching(i0) = a;
        ws.switching_live[static_cast<std::size_t>(i0)] = live;
        if (back) {
          ws.switching(i0 + 1) = a + core.backlash();
          ws.switching_live[static_cast<std::size_t>(i0 + 1)] = live;
        }
      }
    }
    ws.mesh_dissipation += rate.dot(C2 * rate);
    ws.force_eta[k] = F(0);
    if (with_jacobians) ws.mesh_tangent[k] = J;
    // Force on the pair's coordinates −Gᵀ F; tangents Gᵀ J G and Gᵀ C2 G.
    const Vector12 fp = -t.G.transpose() * F;
    Matrix12 kp, cp;
    if (with_jacobians) {
      kp.noalias() = t.G.transpose() * J * t.G;
      cp.noalias() = t.G.transpose() * C2 * t.G;
    }
    for (int a = 0; a < 12; ++a) {
      const int ia = t.dofs[a];
      if (ia < 0) continue;
      ws.force(ia) += fp(a);
      if (!with_jacobians) continue;
      for (int b = 0; b < 12; ++b) {
        const int ib = t.dofs[b];
        if (ib < 0) continue;
        if (sparse) {
          kt.emplace_back(ia, ib, kp(a, b));
          ct.emplace_back(ia, ib, cp(a, b));
        } else {
          ws.tangent_k(ia, ib) += kp(a, b);
          ws.tangent_c(ia, ib) += cp(a, b);
        }
      }
    }
  }
}

double StoredEnergy(const TdSystem& sys, const TdWorkspace& ws, const Eigen::Ref<const VectorX>& x,
                    const Eigen::Ref<const VectorX>& v) {
  return 0.5 * v.dot(sys.mass_sparse * v) + 0.5 * x.dot(sys.stiffness0_sparse * x) + ws.mesh_energy;
}

double DissipationPower(const TdSystem& sys, const TdWorkspace& ws,
                        const Eigen::Ref<const VectorX>& v) {
  return v.dot(sys.damping0_sparse * v) + ws.mesh_dissipation;
}

double EstimateHighestFrequency(const TdSystem& sys, TdWorkspace& ws, double theta,
                                const VectorX& x) {
  EvalForces(sys, ws, theta, 0.0, x, VectorX::Zero(sys.n), true);
  // Power iteration on M⁻¹K (K symmetric PSD, M SPD: real non-negative spectrum); 60 iterations
  // give the top eigenvalue within a few per cent, enough for the kAuto rule.
  VectorX z = VectorX::Ones(sys.n);
  double lambda = 0.0;
  for (int it = 0; it < 60; ++it) {
    VectorX y;
    sys.mass_solver->Solve(ws.tangent_k * z, &y);
    const double norm = y.norm();
    if (!(norm > 0.0) || !std::isfinite(norm)) break;
    lambda = norm / z.norm();
    z = y / norm;
  }
  return std::sqrt(std::max(lambda, 0.0));
}

}  // namespace geardyn::internal

namespace geardyn::internal {

bool SolveBordered(const MatrixX& A, const MatrixX& mv, const VectorX& b, VectorX* dx) {
  const auto n = A.rows(), r = mv.cols();
  MatrixX a = MatrixX::Zero(n + r, n + r);
  a.topLeftCorner(n, n) = A;
  a.topRightCorner(n, r) = mv;
  a.bottomLeftCorner(r, n) = mv.transpose();
  VectorX rhs = VectorX::Zero(n + r);
  rhs.head(n) = b;
  VectorX s = VectorX::Ones(n + r);
  for (Eigen::Index i = 0; i < n; ++i) {
    const double d = std::abs(a(i, i));
    if (d > 0.0) s(i) = 1.0 / std::sqrt(d);
  }
  for (Eigen::Index j = 0; j < r; ++j) {
    const double c = (s.head(n).asDiagonal() * mv.col(j)).norm();
    if (c > 0.0) s(n + j) = 1.0 / c;
  }
  a = s.asDiagonal() * a * s.asDiagonal();
  rhs = s.asDiagonal() * rhs;
  Eigen::FullPivLU<MatrixX> lu(a);
  lu.setThreshold(1e-13);
  if (!lu.isInvertible()) return false;
  *dx = (s.asDiagonal() * lu.solve(rhs)).head(n);
  return dx->allFinite();
}

MatrixX RestStiffness(const TdSystem& sys, const TdWorkspace& ws) {
  MatrixX k = sys.guess_stiffness;
  for (const TdMeshTerm& t : sys.terms) {
    if (t.kind != TdMeshTerm::Kind::kNonlinear || t.num_internal == 0) continue;
    k.block(t.internal_offset, t.internal_offset, t.num_internal, t.num_internal) =
        ws.tangent_k.block(t.internal_offset, t.internal_offset, t.num_internal, t.num_internal);
  }
  return k;
}

TdStatic SolveStatic(const TdSystem& sys, TdWorkspace& ws, double theta0, const VectorX* start) {
  TdStatic out;
  out.x = VectorX::Zero(sys.n);
  const VectorX zero = VectorX::Zero(sys.n);
  const MatrixX mv = sys.mass * sys.rigid_modes;
  // Starting guess: the linear problem with every slice loaded, the stand-in springs of the
  // nonlinear cores and their tangents at rest (their internal springs).
  EvalForces(sys, ws, theta0, 0.0, zero, zero, true);
  const MatrixX guess = RestStiffness(sys, ws);
  VectorX x_guess;
  if (start != nullptr) {
    out.x = *start;
  } else if (SolveBordered(guess, mv, ws.force, &x_guess)) {
    out.x = x_guess;
  }
  // Newton on force(x, 0, θ₀) = 0, dx = K_t⁻¹ force, bordered by VᵀM dx = 0 on the rigid modes
  // (the rigid coordinates stay where they are: the solution is unique in the complement).
  EvalForces(sys, ws, theta0, 0.0, out.x, zero, true);
  for (int it = 1; it <= 60; ++it) {
    out.iterations = it;
    VectorX dx;
    if (!SolveBordered(ws.tangent_k, mv, ws.force, &dx)) {
      out.message = "static equilibrium: the tangent stiffness is singular at iteration " +
                    std::to_string(it) + " (a mesh out of contact, or an unsupported body)";
      return out;
    }
    // Backtracking on ‖force‖ (the slice force is only piecewise linear).
    const double f_norm = ws.force.norm();
    double step = 1.0;
    VectorX trial = out.x + dx;
    EvalForces(sys, ws, theta0, 0.0, trial, zero, true);
    while (ws.force.norm() > f_norm && step > 1e-4) {
      step *= 0.5;
      trial = out.x + step * dx;
      EvalForces(sys, ws, theta0, 0.0, trial, zero, true);
    }
    out.x = trial;
    const double scale = std::max(out.x.lpNorm<Eigen::Infinity>(), 1e-300);
    if (step * dx.lpNorm<Eigen::Infinity>() <= 1e-12 * scale) {
      out.ok = true;
      return out;
    }
  }
  out.message = "static equilibrium: Newton did not converge in 60 iterations";
  return out;
}

}  // namespace geardyn::internal
