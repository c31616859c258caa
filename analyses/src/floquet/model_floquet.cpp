// ComputeFloquet(SystemModel, options): checks, the block split, the method selection
// (internal::SelectFloquetMethod, the one place kAuto is decided) and the conversion of the model
// into the generic PeriodicSecondOrderSystem (steps, callback, harmonics or a modal projection).
#include <algorithm>
#include <cmath>
#include <memory>
#include <numbers>
#include <optional>
#include <sstream>
#include <utility>
#include <variant>
#include <vector>

#include "floquet/floquet_internal.hpp"
#include "geardyn/analyses/modal.hpp"
#include "geardyn/common/check.hpp"
#include "geardyn/common/errors.hpp"
#include "geardyn/system/common_period.hpp"
#include "geardyn/system/system_harmonics.hpp"
#include "geardyn/system/system_steps.hpp"
#include "geardyn/system/workspace.hpp"

namespace geardyn {
namespace internal {
namespace {

constexpr std::int64_t kMaxHillExpansion = 1 << 16;  // system harmonics expanded for Hill

// K(θ), C(θ) of the model, or Vᵀ K(θ) V and Vᵀ C(θ) V, in either storage. Projected, only the
// part that varies is projected at each θ: K(θ) = K0 + Σ meshes on their 12 DOFs (workspace.hpp,
// the same for C), so Vᵀ K(θ) V = Vᵀ K(θ₀) V + V_Dᵀ (K(θ) − K(θ₀))_DD V_D with D the meshes'
// DOFs: |D|²m + |D|m² flops per θ instead of 2n²m + 2nm² (geared shafts: 12 of 108 DOFs, ≈ 60×
// less; the projection was ≈ a third of kAuto's time on it).
class ModelAssembler {
 public:
  ModelAssembler(const SystemModel& m, StorageKind storage, const MatrixX& V)
      : model_(m), ws_(std::make_shared<SystemWorkspace>(m, storage)), V_(V) {
    if (V_.size() == 0) return;
    std::vector<int> dofs;
    for (const SystemMesh& mesh : model_.meshes()) {
      for (const int d : mesh.dofs) {
        if (d >= 0) dofs.push_back(d);
      }
    }
    std::sort(dofs.begin(), dofs.end());
    dofs.erase(std::unique(dofs.begin(), dofs.end()), dofs.end());
    dofs_ = dofs;
    const int nd = static_cast<int>(dofs_.size());
    VD_.resize(nd, V_.cols());
    for (int i = 0; i < nd; ++i) VD_.row(i) = V_.row(dofs_[i]);
    constexpr double kReferenceTheta = 0.0;
    FullProjection(kReferenceTheta, &K0r_, &C0r_);
    Block(kReferenceTheta, &K0D_, &C0D_);
  }
  // K(θ), C(θ) (n × n) when V is empty, else Vᵀ K(θ) V, Vᵀ C(θ) V (m × m).
  void Eval(double theta, MatrixX* K, MatrixX* C) const {
    if (V_.size() == 0) {
      if (ws_->storage == StorageKind::kDense) {
        *K = AssembleStiffness(model_, *ws_, theta);
        *C = AssembleDamping(model_, *ws_, theta);
      } else {
        *K = MatrixX(AssembleStiffnessSparse(model_, *ws_, theta));
        *C = MatrixX(AssembleDampingSparse(model_, *ws_, theta));
      }
      return;
    }
    MatrixX KD, CD;
    Block(theta, &KD, &CD);
    KD -= K0D_;
    CD -= C0D_;
    *K = K0r_;
    K->noalias() += VD_.transpose() * KD * VD_;
    *C = C0r_;
    C->noalias() += VD_.transpose() * CD * VD_;
  }

 private:
  // Vᵀ K(θ) V, Vᵀ C(θ) V in full (the reference).
  void FullProjection(double theta, MatrixX* K, MatrixX* C) const {
    if (ws_->storage == StorageKind::kDense) {
      *K = V_.transpose() * AssembleStiffness(model_, *ws_, theta) * V_;
      *C = V_.transpose() * AssembleDamping(model_, *ws_, theta) * V_;
    } else {
      *K = V_.transpose() * (AssembleStiffnessSparse(model_, *ws_, theta) * V_);
      *C = V_.transpose() * (AssembleDampingSparse(model_, *ws_, theta) * V_);
    }
  }
  // K(θ)_DD, C(θ)_DD.
  void Block(double theta, MatrixX* K, MatrixX* C) const {
    const int nd = static_cast<int>(dofs_.size());
    K->resize(nd, nd);
    C->resize(nd, nd);
    if (ws_->storage == StorageKind::kDense) {
      const MatrixX& Kd = AssembleStiffness(model_, *ws_, theta);
      for (int j = 0; j < nd; ++j)
        for (int i = 0; i < nd; ++i) (*K)(i, j) = Kd(dofs_[i], dofs_[j]);
      const MatrixX& Cd = AssembleDamping(model_, *ws_, theta);
      for (int j = 0; j < nd; ++j)
        for (int i = 0; i < nd; ++i) (*C)(i, j) = Cd(dofs_[i], dofs_[j]);
    } else {
      const SparseMatrix& Ks = AssembleStiffnessSparse(model_, *ws_, theta);
      for (int j = 0; j < nd; ++j)
        for (int i = 0; i < nd; ++i) (*K)(i, j) = Ks.coeff(dofs_[i], dofs_[j]);
      const SparseMatrix& Cs = AssembleDampingSparse(model_, *ws_, theta);
      for (int j = 0; j < nd; ++j)
        for (int i = 0; i < nd; ++i) (*C)(i, j) = Cs.coeff(dofs_[i], dofs_[j]);
    }
  }

  SystemModel model_;
  std::shared_ptr<SystemWorkspace> ws_;
  MatrixX V_, VD_, K0r_, C0r_, K0D_, C0D_;
  std::vector<int> dofs_;
};

}  // namespace

// The model (projected on V if nonempty) as a generic system with the forms the method needs,
// over the operator period P_K (OperatorPeriodMeshes), not the hunting period of ε.
PeriodicSecondOrderSystem MakeModelSystem(const SystemModel& model, double omega_m,
                                          FloquetMethod method, int hill_harmonics,
                                          const MatrixX& V) {
  const bool piecewise = HasPiecewiseConstantOperator(model);
  const bool projected = V.size() != 0;
  const StorageKind storage = projected ? model.storage_hint() : StorageKind::kDense;
  const auto assembler = std::make_shared<ModelAssembler>(model, storage, V);
  PeriodicSecondOrderSystem s;
  const std::int64_t operator_period = FloquetPeriodMeshes(model);
  const double P = static_cast<double>(operator_period);
  s.period_s = 2.0 * std::numbers::pi * P / omega_m;
  if (projected) {
    s.mass = V.transpose() * (model.mass() * V);
    s.mass = 0.5 * (s.mass + s.mass.transpose()).eval();
  } else {
    s.mass = model.DenseMass();
  }
  if ((piecewise || method == FloquetMethod::kExactSteps) && method != FloquetMethod::kHill) {
    const SystemSteps steps = OperatorSteps(model, operator_period);
    for (int k = 0; k < steps.num_intervals(); ++k) {
      PeriodicStep step;
      step.duration_s = steps.interval_width(k) / omega_m;
      assembler->Eval(steps.interval_midpoint(k), &step.stiffness, &step.damping);
      s.steps.push_back(std::move(step));
    }
  }
  if (!piecewise || method == FloquetMethod::kMagnus) {
    s.coefficients = [assembler, omega_m](double t, MatrixX* K, MatrixX* C) {
      assembler->Eval(omega_m * t, K, C);
    };
    // Where K(θ), C(θ) jump or kink (steps, table samples): Magnus ends its steps there.
    const VectorX kinks = CollectSystemKinks(model, operator_period);
    for (const double theta : kinks) s.kinks_s.push_back(theta / omega_m);
  }
  if (method == FloquetMethod::kHill) {
    const int dim = 2 * (projected ? static_cast<int>(V.cols()) : model.num_dofs());
    const int H = hill_harmonics > 0 ? hill_harmonics
                                     : std::max(1, static_cast<int>((kMaxHillSize / dim - 1) / 2));
    CheckHillSize(dim, H, hill_harmonics > 0);
    // System harmonic m·q (q = P/P_K) is harmonic m of the operator period; the others are
    // harmonics of ε only (the load), which Hill does not see.
    const std::int64_t q = model.period_meshes() / operator_period;
    GEARDYN_THROW_UNLESS(2 * H * q <= kMaxHillExpansion,
                         "method: hill needs " << 2 * H << " harmonics of the operator period, "
                                               << 2 * H * q << " of the model's period of "
                                               << model.period_meshes() << " meshes (at most "
                                               << kMaxHillExpansion
                                               << "); use exact_steps, magnus or ode_stepper");
    const SystemHarmonics h = ExpandSystemHarmonics(model, static_cast<int>(2 * H * q));
    const MatrixXc Vc = V.cast<std::complex<double>>();
    for (std::int64_t mq = 0; mq <= h.num_harmonics(); mq += q) {
      const auto m = static_cast<std::size_t>(mq);
      s.stiffness_harmonics.push_back(projected ? MatrixXc(Vc.transpose() * h.stiffness[m] * Vc)
                                                : h.stiffness[m]);
      s.damping_harmonics.push_back(projected ? MatrixXc(Vc.transpose() * h.damping[m] * Vc)
                                              : h.damping[m]);
    }
  }
  return s;
}

// One block (or the whole model): selection, then the generic engine.
FloquetResult ComputeModelFloquet(const SystemModel& model, const FloquetOptions& options) {
  const double omega_m = 2.0 * std::numbers::pi * options.mesh_frequency_hz;
  MeshDrivenBasis basis;
  const FloquetMethod method = SelectFloquetMethod(model, options, &basis);
  const int n = model.num_dofs();
  if (method == FloquetMethod::kModalProjection) {
    const FloquetMethod inner =
        HasPiecewiseConstantOperator(model) ? FloquetMethod::kExactSteps : FloquetMethod::kMagnus;
    MatrixX cached;  // modes computed once for the largest m asked so far
    int initial = 0;
    if (options.num_modes == 0) {
      // Automatic basis: the modes that drive the parametric resonances at this f_m first.
      cached = basis.modes;
      initial = basis.num_priority;
    }
    auto modes = [&](int m) {
      if (cached.cols() < m) {
        ModalOptions mo;
        mo.num_modes = std::min(n, std::max(m, static_cast<int>(std::ceil(1.5 * m))));
        if (mo.num_modes >= n) mo.method = ModalMethod::kDense;
        mo.compute_shapes = true;
        mo.compute_energy_fractions = false;
        const ModalResult r = ComputeModes(model, mo);
        GEARDYN_THROW_UNLESS(
            r.summary.ok() || r.shapes.cols() >= m,
            "modal_projection: the modes of the mean system failed: " << r.summary.message);
        cached = r.shapes;
      }
      return MatrixX(cached.leftCols(std::min<int>(m, static_cast<int>(cached.cols()))));
    };
    auto project = [&](const MatrixX& V) { return MakeModelSystem(model, omega_m, inner, 0, V); };
    FloquetResult r;
    if (options.method == FloquetMethod::kAuto && options.num_modes == 0) {
      // kAuto: accept a basis whose estimate of max|λ| does not decide the verdict, else widen,
      // else the unprojected system (auto_projection.cpp).
      auto full = [&]() {
        const PeriodicSecondOrderSystem system =
            MakeModelSystem(model, omega_m, inner, 0, MatrixX());
        const StateSystem sys = MakeStateSystem(system, options.deflate_rigid_modes);
        return ComputeFloquetState(sys, options, inner);
      };
      r = AutoModalProjectionFloquet(modes, n, project, full, options, initial);
    } else {
      r = ModalProjectionFloquet(modes, n, project, options, initial);
    }
    if (initial > 0) r.summary.counters["modes_priority"] = initial;
    return r;
  }
  const PeriodicSecondOrderSystem system =
      MakeModelSystem(model, omega_m, method, options.hill_harmonics, MatrixX());
  const StateSystem sys = MakeStateSystem(system, options.deflate_rigid_modes);
  return ComputeFloquetState(sys, options, method);
}

MeshDrivenBasis SelectMeshDrivenBasis(const SystemModel& model, double mesh_frequency_hz) {
  const int n = model.num_dofs();
  ModalOptions mo;
  mo.num_modes = std::min(n, kMaxBasisModes);
  if (mo.num_modes >= n) mo.method = ModalMethod::kDense;
  mo.compute_shapes = true;
  mo.compute_energy_fractions = true;  // the mesh strain-energy fractions
  const ModalResult r = ComputeModes(model, mo);
  GEARDYN_THROW_UNLESS(
      r.summary.ok() || r.shapes.cols() > 0,
      "modal_projection: the modes of the mean system failed: " << r.summary.message);
  const int m = static_cast<int>(r.shapes.cols());
  // Principal resonances f_m = 2 f_p / k put f_p = k f_m / 2; sum combinations f_m = (f_p+f_q)/k
  // with f_p ≪ f_q put f_q ≤ k f_m. Cover k ≤ kBasisResonanceOrder of the principal ones with
  // the margin kBasisFrequencyMargin: f_p ≤ 1.5 · 3 · f_m / 2 = 2.25 f_m (this also covers the
  // k = 1, 2 sum combinations). Modes above that which store a share ≥ kMeshStrainShare of their
  // strain energy in a mesh are added: they carry the mesh stiffness variation (the "mesh
  // modes" of a stiff gear pair, often far above f_m) and their couplings to the low modes.
  const double cover = kBasisFrequencyMargin * kBasisResonanceOrder * mesh_frequency_hz / 2.0;
  std::vector<int> mesh_columns;
  for (std::size_t c = 0; c < r.strain_names.size(); ++c) {
    if (r.strain_names[c].rfind("mesh:", 0) == 0) mesh_columns.push_back(static_cast<int>(c));
  }
  std::vector<int> priority, rest;
  std::vector<bool> wanted(m, false);
  for (int k = 0; k < m; ++k) {
    double mesh_share = 0.0;
    for (const int c : mesh_columns) {
      if (r.strain_fractions.rows() > k) mesh_share += r.strain_fractions(k, c);
    }
    wanted[k] = r.frequencies_hz[k] <= cover || mesh_share >= kMeshStrainShare;
  }
  // Decay over one period of the uncoupled mode, ρ_k = exp(−2π ζ_k f_k T) (ζ_k = φᵀC̄φ/(2ω_k),
  // the mean system's): a mode left out contributes nothing to max|λ|, so every mode that decays
  // no faster than the slowest-decaying wanted flexible mode joins the basis (an undamped mode
  // anywhere: ρ = 1). Without it a dropped undamped mode would turn "stable, marginal" into
  // "stable" with a max|λ| below 1.
  const double period_s = static_cast<double>(FloquetPeriodMeshes(model)) / mesh_frequency_hz;
  auto decay = [&](int k) {
    const double zeta = r.modal_damping_ratios.size() > k ? r.modal_damping_ratios[k] : 0.0;
    return std::exp(-2.0 * std::numbers::pi * zeta * r.frequencies_hz[k] * period_s);
  };
  double slowest = 0.0;
  for (int k = 0; k < m; ++k) {
    if (wanted[k] && r.frequencies_hz[k] > 0.0) slowest = std::max(slowest, decay(k));
  }
  for (int k = 0; k < m; ++k) {
    if (!wanted[k] && r.frequencies_hz[k] > 0.0 && decay(k) >= slowest) wanted[k] = true;
    (wanted[k] ? priority : rest).push_back(k);
  }
  MeshDrivenBasis out;
  out.num_priority = std::max(static_cast<int>(priority.size()), std::min(12, m));
  out.modes.resize(n, m);
  out.frequencies_hz.resize(m);
  int col = 0;
  for (const std::vector<int>* group : {&priority, &rest}) {
    for (const int k : *group) {
      out.frequencies_hz[col] = r.frequencies_hz[k];
      out.modes.col(col++) = r.shapes.col(k);
    }
  }
  return out;
}

int NextBasisSize(int m, int num_dofs) {
  return std::min(num_dofs, std::max(m + 1, static_cast<int>(std::ceil(1.5 * m))));
}

double MagnusWork(double f_max_hz, double period_s, int dofs) {
  const double steps = std::max(static_cast<double>(kMinMagnusSteps),
                                2.0 * 2.0 * std::numbers::pi * f_max_hz * period_s);
  const double d = 2.0 * dofs;
  return steps * d * d * d;
}

std::vector<UndampedMode> UndampedModes(const SystemModel& model) {
  // Modes of the mean system (K̄, M) with ζ = φᵀC̄φ/(2ω) below kUndampedRatio: their
  // multipliers sit on the unit circle whatever the speed (outside the parametric resonances).
  constexpr double kUndampedRatio = 1e-9;
  ModalOptions mo;
  mo.compute_shapes = true;
  mo.compute_energy_fractions = false;
  mo.num_modes = std::min(model.num_dofs(), kMaxUndampedModesListed);
  if (mo.num_modes >= model.num_dofs()) mo.method = ModalMethod::kDense;
  std::vector<UndampedMode> out;
  ModalResult r;
  try {
    r = ComputeModes(model, mo);
  } catch (const InvalidInput&) {
    return out;  // the list is a diagnostic; the verdict does not depend on it
  }
  if (r.shapes.cols() == 0) return out;
  // Mean damping C̄ (the θ-mean over one operator period by the midpoint rule on 64 samples;
  // exact for piecewise-constant damping with breakpoints on the samples, a diagnostic else).
  SystemWorkspace ws(model, StorageKind::kDense);
  const int n = model.num_dofs();
  MatrixX C = MatrixX::Zero(n, n);
  constexpr int kSamples = 64;
  const double period = 2.0 * std::numbers::pi * static_cast<double>(FloquetPeriodMeshes(model));
  for (int j = 0; j < kSamples; ++j) {
    C += AssembleDamping(model, ws, period * (j + 0.5) / kSamples) / kSamples;
  }
  const MatrixX M = model.DenseMass();
  for (int k = 0; k < r.shapes.cols(); ++k) {
    const double f = r.frequencies_hz[k];
    if (!(f > 0.0)) continue;  // rigid-body modes are deflated, not "undamped"
    const VectorX phi = r.shapes.col(k);
    const double zeta = phi.dot(C * phi) / (2.0 * 2.0 * std::numbers::pi * f);
    if (!(std::abs(zeta) < kUndampedRatio)) continue;
    Eigen::Index dof = 0;
    (phi.array().square() * M.diagonal().array()).maxCoeff(&dof);
    UndampedMode m;
    m.index = k;
    m.frequency_hz = f;
    m.damping_ratio = zeta;
    m.dominant_dof = model.dof_map().dof_name(static_cast<int>(dof));
    out.push_back(std::move(m));
  }
  return out;
}

FloquetMethod SelectFloquetMethod(const SystemModel& model, const FloquetOptions& options) {
  return SelectFloquetMethod(model, options, nullptr);
}

std::optional<FloquetMethod> FrequencyIndependentMethod(const SystemModel& model,
                                                        const FloquetOptions& options) {
  if (options.method != FloquetMethod::kAuto) return options.method;
  const int n = model.num_dofs();
  if (n >= options.modal_projection_min_dofs) return FloquetMethod::kModalProjection;
  // Piecewise-constant: the exact product (one expm per distinct step; no step count to choose).
  if (HasPiecewiseConstantOperator(model)) return FloquetMethod::kExactSteps;
  // Smooth coefficients: Magnus on the full system or on the mesh-driven modal basis, by cost
  // (SelectFloquetMethod). Only worth asking when the check basis ⌈2.25 m₀⌉ (m₀ ≥ min(12, n))
  // can be smaller than n. A user-sized basis (num_modes > 0) keeps the former rule below
  // modal_projection_min_dofs: the full system (its fixed-size projection has no verdict-based
  // acceptance).
  const int m0_least = std::min(12, n);
  if (options.num_modes != 0 || NextBasisSize(NextBasisSize(m0_least, n), n) >= n) {
    return FloquetMethod::kMagnus;
  }
  return std::nullopt;
}

FloquetMethod SelectFloquetMethod(const SystemModel& model, const FloquetOptions& options,
                                  MeshDrivenBasis* basis) {
  const bool automatic_basis = options.num_modes == 0;
  if (const std::optional<FloquetMethod> fixed = FrequencyIndependentMethod(model, options)) {
    if (*fixed == FloquetMethod::kModalProjection && automatic_basis && basis != nullptr) {
      *basis = SelectMeshDrivenBasis(model, options.mesh_frequency_hz);
    }
    return *fixed;
  }
  // By cost (MagnusWork: steps ∝ the highest frequency kept, work ∝ steps × (2m)³).
  const int n = model.num_dofs();
  MeshDrivenBasis b = SelectMeshDrivenBasis(model, options.mesh_frequency_hz);
  const int m = static_cast<int>(b.modes.cols());
  const int m0 = std::min(b.num_priority, m), m1 = NextBasisSize(m0, n), m2 = NextBasisSize(m1, n);
  if (m < n || m2 >= n) return FloquetMethod::kMagnus;
  const double period_s =
      static_cast<double>(FloquetPeriodMeshes(model)) / options.mesh_frequency_hz;
  auto highest = [&](int cols) { return b.frequencies_hz.head(cols).maxCoeff(); };
  const double full_work = MagnusWork(b.frequencies_hz.maxCoeff(), period_s, n);
  const double projection_work = MagnusWork(highest(m0), period_s, m0) +
                                 MagnusWork(highest(m1), period_s, m1) +
                                 MagnusWork(highest(m2), period_s, m2);
  if (!(kProjectionWorkMargin * projection_work < full_work)) return FloquetMethod::kMagnus;
  if (basis != nullptr) *basis = std::move(b);
  return FloquetMethod::kModalProjection;
}

FloquetResult CombineBlockResults(const SystemModel& model, const FloquetOptions& options,
                                  const std::vector<FloquetResult>& parts) {
  // Blocks do not couple: Φ is block diagonal (after the DOF permutation) and the multipliers
  // are the union of the blocks' multipliers.
  const int n = model.num_dofs();
  const int num_blocks = static_cast<int>(parts.size());
  FloquetResult result;
  int total = 0, largest = 0;
  for (int b = 0; b < num_blocks; ++b) {
    total += static_cast<int>(parts[b].multipliers.size());
    if (model.blocks()[b].size() > model.blocks()[largest].size()) largest = b;
  }
  result.method_used = parts[largest].method_used;
  result.multipliers.resize(total);
  result.exponents.resize(total);
  if (options.keep_monodromy) result.monodromy = MatrixX::Zero(2 * n, 2 * n);
  int at = 0;
  for (int b = 0; b < num_blocks; ++b) {
    const FloquetResult& p = parts[b];
    const int k = static_cast<int>(p.multipliers.size());
    result.multipliers.segment(at, k) = p.multipliers;
    result.exponents.segment(at, k) = p.exponents;
    at += k;
    result.summary.error_estimate =
        MaxPropagatingNaN(result.summary.error_estimate, p.summary.error_estimate);
    for (const auto& [name, value] : p.summary.counters) result.summary.counters[name] += value;
    for (const std::string& w : p.summary.warnings) {
      result.summary.warnings.push_back("block " + std::to_string(b) + ": " + w);
    }
    if (!p.summary.ok() && result.summary.ok()) {
      result.summary.status = p.summary.status;
      result.summary.message = "block " + std::to_string(b) + ": " + p.summary.message;
    }
    if (p.method_used != result.method_used) {
      result.summary.warnings.push_back("block " + std::to_string(b) + " used method " +
                                        ToString(p.method_used));
    }
    if (options.keep_monodromy && p.monodromy.size()) {
      const std::vector<int>& dofs = model.blocks()[b];
      const int nb = static_cast<int>(dofs.size());
      for (int i = 0; i < 2 * nb; ++i) {
        const int gi = i < nb ? dofs[i] : n + dofs[i - nb];
        for (int j = 0; j < 2 * nb; ++j) {
          const int gj = j < nb ? dofs[j] : n + dofs[j - nb];
          result.monodromy(gi, gj) = p.monodromy(i, j);
        }
      }
    }
  }
  result.summary.counters["blocks"] = num_blocks;
  SortSpectrum(&result.multipliers, &result.exponents);
  FinishResult(0, options.tolerance, &result);
  // The blocks' own verdicts (each with its own status and estimate), combined.
  result.verdict = parts[0].verdict;
  bool marginal = parts[0].marginal;
  for (int b = 1; b < num_blocks; ++b) {
    result.verdict = CombineVerdicts(result.verdict, parts[b].verdict);
    marginal = marginal || parts[b].marginal;
  }
  result.marginal = result.verdict == FloquetVerdict::kStable && marginal;
  return result;
}

// "mesh 'sun-planet_1' and 5 more at 0.175", one entry per distinct ratio other than 1.
std::string MeshRatiosText(const SystemModel& model) {
  // "mesh 'sun-planet_1' and 5 more at 0.175", one entry per distinct ratio.
  std::vector<std::pair<double, std::vector<std::string>>> groups;
  for (const SystemMesh& mesh : model.meshes()) {
    if (std::abs(mesh.phase_ratio - 1.0) <= 1e-12) continue;
    auto it = std::find_if(groups.begin(), groups.end(), [&](const auto& g) {
      return std::abs(g.first - mesh.phase_ratio) <= 1e-12 * g.first;
    });
    if (it == groups.end()) {
      groups.push_back({mesh.phase_ratio, {}});
      it = groups.end() - 1;
    }
    it->second.push_back(mesh.name);
  }
  std::ostringstream listed;
  for (std::size_t g = 0; g < groups.size() && g < 4; ++g) {
    listed << (g ? "; " : "") << "mesh '" << groups[g].second.front() << "'";
    if (groups[g].second.size() > 1) listed << " and " << groups[g].second.size() - 1 << " more";
    listed << " at " << groups[g].first;
  }
  return listed.str();
}

std::vector<std::string> CheckFloquetModel(const SystemModel& model,
                                           const FloquetOptions& options) {
  std::string why;
  GEARDYN_THROW_UNLESS(options.IsValid(&why), why);
  GEARDYN_THROW_UNLESS(model.num_dofs() > 0, "model: has no DOF");
  std::vector<std::string> warnings;
  for (const SystemMesh& mesh : model.meshes()) {
    GEARDYN_THROW_UNLESS(
        !std::holds_alternative<std::shared_ptr<const NonlinearMeshCore>>(mesh.core),
        "model: mesh '" << mesh.name
                        << "' has a nonlinear core; Floquet analysis needs a linear operator");
    if (std::holds_alternative<SliceMeshCore>(mesh.core)) {
      warnings.push_back("mesh '" + mesh.name +
                         "': slice core linearized with every slice in contact (all-loaded)");
    }
  }
  if (HasSeveralMeshFrequencies(model)) {
    // Several mesh frequencies: the monodromy over their common period (FloquetPeriodMeshes).
    const std::string ratios = MeshRatiosText(model);
    GEARDYN_THROW_UNLESS(
        FloquetPeriodMeshes(model) > 0,
        "model: the meshes run at incommensurate frequencies ("
            << ratios << " times the first mesh's): no common period of at most "
            << kMaxFloquetCommonPeriodMeshes
            << " mesh cycles, so there is no monodromy to compute; ComputeFloquet (geardyn "
               "floquet) analyses rational approximants of the ratios instead when "
               "max_approximant_period_meshes > 0, and the quasi-periodic harmonic balance "
               "(geardyn hb) gives the steady response");
    GEARDYN_THROW_UNLESS(options.method != FloquetMethod::kHill,
                         "method: hill expands the operator in harmonics of one mesh frequency; "
                         "the meshes run at several ("
                             << ratios
                             << " times the first mesh's): use auto, exact_steps, magnus, "
                                "ode_stepper, modal_projection or arpack_monodromy");
    warnings.push_back("meshes at several frequencies (" + ratios +
                       " times the first mesh's): the monodromy spans their common period of " +
                       std::to_string(FloquetPeriodMeshes(model)) + " mesh cycles");
  }
  GEARDYN_THROW_UNLESS(
      options.method != FloquetMethod::kArpackMonodromy ||
          options.arpack_nev <= 2 * model.num_dofs(),
      "arpack_nev: must be <= 2n = " << 2 * model.num_dofs() << ", got " << options.arpack_nev);
  return warnings;
}

void FinishModelFloquet(const SystemModel& model, const FloquetOptions& options,
                        const std::vector<std::string>& warnings,
                        const std::chrono::steady_clock::time_point& start, FloquetResult* result) {
  if (result->marginal && options.list_undamped_modes) {
    result->undamped_modes = UndampedModes(model);
  }
  for (const std::string& w : warnings) result->summary.warnings.push_back(w);
  result->period_meshes = FloquetPeriodMeshes(model);
  result->period_s = static_cast<double>(result->period_meshes) / options.mesh_frequency_hz;
  if (result->period_meshes < model.period_meshes()) {
    result->summary.counters["load_period_meshes"] = model.period_meshes();
  }
  result->summary.wall_time_s = SecondsSince(start);
}

}  // namespace internal

FloquetResult ComputeFloquet(const SystemModel& model, const FloquetOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  if (options.max_approximant_period_meshes > 0 && HasSeveralMeshFrequencies(model) &&
      internal::FloquetPeriodMeshes(model) == 0) {
    std::string why;
    GEARDYN_THROW_UNLESS(options.IsValid(&why), why);
    FloquetResult result =
        internal::ComputeApproximantFloquet(model, options, internal::MeshRatiosText(model));
    result.summary.wall_time_s = internal::SecondsSince(start);
    return result;
  }
  const std::vector<std::string> warnings = internal::CheckFloquetModel(model, options);
  FloquetResult result;
  // Blocks of a model with several mesh frequencies share its common period, which a block alone
  // may not have (a block of ratio-1 meshes repeats after one cycle): no split there.
  const int num_blocks =
      options.split_blocks && !HasSeveralMeshFrequencies(model) ? model.num_blocks() : 1;
  if (num_blocks <= 1) {
    result = internal::ComputeModelFloquet(model, options);
  } else {
    std::vector<FloquetResult> parts;
    for (int b = 0; b < num_blocks; ++b) {
      parts.push_back(internal::ComputeModelFloquet(model.RestrictToBlock(b), options));
    }
    result = internal::CombineBlockResults(model, options, parts);
  }
  internal::FinishModelFloquet(model, options, warnings, start, &result);
  return result;
}

}  // namespace geardyn
