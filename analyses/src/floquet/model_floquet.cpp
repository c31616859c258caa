// ComputeFloquet(SystemModel, options): checks, the block split, the method selection
// (internal::SelectFloquetMethod, the one place kAuto is decided) and the conversion of the model
// into the generic PeriodicSecondOrderSystem (steps, callback, harmonics or a modal projection).
#include <algorithm>
#include <cmath>
#include <memory>
#include <numbers>
#include <variant>

#include "floquet/floquet_internal.hpp"
#include "geardyn/analyses/modal.hpp"
#include "geardyn/common/check.hpp"
#include "geardyn/system/system_harmonics.hpp"
#include "geardyn/system/system_steps.hpp"
#include "geardyn/system/workspace.hpp"

namespace geardyn {
namespace internal {
namespace {

constexpr int kMaxHillSize = 1600;  // as hill.cpp: adaptive H stops at dim·(2H+1) ≤ this

// V ᵀ X V for the model's K(θ) and C(θ) in either storage.
struct ModelAssembler {
  SystemModel model;
  std::shared_ptr<SystemWorkspace> ws;
  explicit ModelAssembler(const SystemModel& m, StorageKind storage)
      : model(m), ws(std::make_shared<SystemWorkspace>(m, storage)) {}
  // K(θ), C(θ) projected on V (or dense when V is empty).
  void Eval(double theta, const MatrixX& V, MatrixX* K, MatrixX* C) const {
    if (ws->storage == StorageKind::kDense) {
      const MatrixX& Kd = AssembleStiffness(model, *ws, theta);
      const MatrixX& Cd = AssembleDamping(model, *ws, theta);
      if (V.size() == 0) {
        *K = Kd;
        *C = Cd;
      } else {
        *K = V.transpose() * Kd * V;
        *C = V.transpose() * Cd * V;
      }
    } else {
      const SparseMatrix& Ks = AssembleStiffnessSparse(model, *ws, theta);
      const SparseMatrix& Cs = AssembleDampingSparse(model, *ws, theta);
      if (V.size() == 0) {
        *K = MatrixX(Ks);
        *C = MatrixX(Cs);
      } else {
        *K = V.transpose() * (Ks * V);
        *C = V.transpose() * (Cs * V);
      }
    }
  }
};

// The model (projected on V if nonempty) as a generic system with the forms the method needs.
PeriodicSecondOrderSystem MakeModelSystem(const SystemModel& model, double omega_m,
                                          FloquetMethod method, int hill_harmonics,
                                          const MatrixX& V) {
  const bool piecewise = HasPiecewiseConstantOperator(model);
  const bool projected = V.size() != 0;
  const StorageKind storage = projected ? model.storage_hint() : StorageKind::kDense;
  const auto assembler = std::make_shared<ModelAssembler>(model, storage);
  PeriodicSecondOrderSystem s;
  const double P = static_cast<double>(model.period_meshes());
  s.period_s = 2.0 * std::numbers::pi * P / omega_m;
  if (projected) {
    s.mass = V.transpose() * (model.mass() * V);
    s.mass = 0.5 * (s.mass + s.mass.transpose()).eval();
  } else {
    s.mass = model.DenseMass();
  }
  if ((piecewise || method == FloquetMethod::kExactSteps) && method != FloquetMethod::kHill) {
    const SystemSteps steps = CollectSystemSteps(model);
    for (int k = 0; k < steps.num_intervals(); ++k) {
      PeriodicStep step;
      step.duration_s = steps.interval_width(k) / omega_m;
      assembler->Eval(steps.interval_midpoint(k), V, &step.stiffness, &step.damping);
      s.steps.push_back(std::move(step));
    }
  }
  if (!piecewise || method == FloquetMethod::kMagnus) {
    s.coefficients = [assembler, V, omega_m](double t, MatrixX* K, MatrixX* C) {
      assembler->Eval(omega_m * t, V, K, C);
    };
  }
  if (method == FloquetMethod::kHill) {
    const int dim = 2 * (projected ? static_cast<int>(V.cols()) : model.num_dofs());
    const int H = hill_harmonics > 0 ? hill_harmonics : std::max(1, (kMaxHillSize / dim - 1) / 2);
    const SystemHarmonics h = ExpandSystemHarmonics(model, 2 * H);
    const MatrixXc Vc = V.cast<std::complex<double>>();
    for (int m = 0; m <= h.num_harmonics(); ++m) {
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
  const FloquetMethod method = SelectFloquetMethod(model, options);
  const int n = model.num_dofs();
  if (method == FloquetMethod::kModalProjection) {
    const FloquetMethod inner =
        HasPiecewiseConstantOperator(model) ? FloquetMethod::kExactSteps : FloquetMethod::kMagnus;
    MatrixX cached;  // modes computed once for the largest m asked so far
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
    FloquetResult r = ModalProjectionFloquet(
        modes, n, [&](const MatrixX& V) { return MakeModelSystem(model, omega_m, inner, 0, V); },
        options);
    return r;
  }
  const PeriodicSecondOrderSystem system =
      MakeModelSystem(model, omega_m, method, options.hill_harmonics, MatrixX());
  const StateSystem sys = MakeStateSystem(system, options.deflate_rigid_modes);
  return ComputeFloquetState(sys, options, method);
}

}  // namespace

FloquetMethod SelectFloquetMethod(const SystemModel& model, const FloquetOptions& options) {
  if (options.method != FloquetMethod::kAuto) return options.method;
  if (model.num_dofs() >= options.modal_projection_min_dofs) return FloquetMethod::kModalProjection;
  return HasPiecewiseConstantOperator(model) ? FloquetMethod::kExactSteps : FloquetMethod::kMagnus;
}

}  // namespace internal

FloquetResult ComputeFloquet(const SystemModel& model, const FloquetOptions& options) {
  const auto start = std::chrono::steady_clock::now();
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
  CheckSingleMeshFrequency(model, "ComputeFloquet");
  GEARDYN_THROW_UNLESS(
      options.method != FloquetMethod::kArpackMonodromy ||
          options.arpack_nev <= 2 * model.num_dofs(),
      "arpack_nev: must be <= 2n = " << 2 * model.num_dofs() << ", got " << options.arpack_nev);
  FloquetResult result;
  const int num_blocks = options.split_blocks ? model.num_blocks() : 1;
  if (num_blocks <= 1) {
    result = internal::ComputeModelFloquet(model, options);
  } else {
    // Blocks do not couple: Φ is block diagonal (after the DOF permutation) and the multipliers
    // are the union of the blocks' multipliers.
    const int n = model.num_dofs();
    std::vector<FloquetResult> parts;
    int total = 0, largest = 0;
    for (int b = 0; b < num_blocks; ++b) {
      parts.push_back(internal::ComputeModelFloquet(model.RestrictToBlock(b), options));
      total += static_cast<int>(parts.back().multipliers.size());
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
          std::max(result.summary.error_estimate, p.summary.error_estimate);
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
    internal::SortSpectrum(&result.multipliers, &result.exponents);
    internal::FinishResult(0, options.tolerance, &result);
  }
  for (const std::string& w : warnings) result.summary.warnings.push_back(w);
  result.period_meshes = model.period_meshes();
  result.period_s = static_cast<double>(result.period_meshes) / options.mesh_frequency_hz;
  result.summary.wall_time_s = internal::SecondsSince(start);
  return result;
}

}  // namespace geardyn
