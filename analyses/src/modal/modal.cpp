// ComputeModes: options, method selection, assembly of the mean system and the single dispatch
// (the method paths are in dense.cpp, arpack.cpp, damped.cpp and classification.cpp).
#include "geardyn/analyses/modal.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <sstream>
#include <utility>
#include <variant>

#include "geardyn/common/check.hpp"
#include "geardyn/system/coefficient.hpp"
#include "geardyn/system/system_model.hpp"
#include "geardyn/system/workspace.hpp"
#include "modal/modal_internal.hpp"

namespace geardyn {

const char* ToString(ModalMethod method) {
  switch (method) {
    case ModalMethod::kAuto:
      return "auto";
    case ModalMethod::kDense:
      return "dense";
    case ModalMethod::kArpack:
      return "arpack";
  }
  return "unknown";
}

const char* ToString(ModeType type) {
  switch (type) {
    case ModeType::kRigidBody:
      return "rigid_body";
    case ModeType::kRotational:
      return "rotational";
    case ModeType::kTranslational:
      return "translational";
    case ModeType::kAxial:
      return "axial";
    case ModeType::kRocking:
      return "rocking";
  }
  return "unknown";
}

const char* ToString(DampingKind kind) {
  switch (kind) {
    case DampingKind::kNone:
      return "none";
    case DampingKind::kRayleigh:
      return "rayleigh";
    case DampingKind::kClassical:
      return "classical";
    case DampingKind::kNonProportional:
      return "non_proportional";
  }
  return "unknown";
}

bool ModalOptions::IsValid(std::string* why) const {
  std::ostringstream out;
  if (method != ModalMethod::kAuto && method != ModalMethod::kDense &&
      method != ModalMethod::kArpack) {
    out << "ModalOptions.method: unknown value " << static_cast<int>(method);
  } else if (num_modes < 0) {
    out << "ModalOptions.num_modes: must be ≥ 0 (0 = all for dense, " << kDefaultArpackModes
        << " for ARPACK), got " << num_modes;
  } else if (shift.has_value() && !std::isfinite(*shift)) {
    out << "ModalOptions.shift: must be finite, got " << *shift;
  } else if (dense_max_dofs < 1) {
    out << "ModalOptions.dense_max_dofs: must be ≥ 1, got " << dense_max_dofs;
  } else if (damped_max_dofs < 1) {
    out << "ModalOptions.damped_max_dofs: must be ≥ 1, got " << damped_max_dofs;
  } else if (!(multiplicity_rel_tol > 0.0 && multiplicity_rel_tol < 1.0)) {
    out << "ModalOptions.multiplicity_rel_tol: must be in (0, 1), got " << multiplicity_rel_tol;
  } else if (!(zero_tol >= 0.0 && zero_tol < 1.0)) {
    out << "ModalOptions.zero_tol: must be in [0, 1), got " << zero_tol;
  } else if (!(arpack_tol >= 0.0 && arpack_tol < 1.0)) {
    out << "ModalOptions.arpack_tol: must be in [0, 1), got " << arpack_tol;
  } else if (!(proportional_damping_tol > 0.0 && proportional_damping_tol < 1.0)) {
    out << "ModalOptions.proportional_damping_tol: must be in (0, 1), got "
        << proportional_damping_tol;
  } else {
    return true;
  }
  if (why != nullptr) *why = out.str();
  return false;
}

namespace internal {

ModalMethod SelectModalMethod(int num_dofs, const ModalOptions& options, std::string* why) {
  const int wanted = options.num_modes > 0 ? options.num_modes : kDefaultArpackModes;
  // ARPACK needs 1 ≤ num_modes < ncv ≤ n; keep one vector of slack.
  const bool arpack_possible = num_dofs >= 3 && wanted < num_dofs - 1;
  switch (options.method) {
    case ModalMethod::kDense:
      return ModalMethod::kDense;
    case ModalMethod::kArpack:
      if (arpack_possible) return ModalMethod::kArpack;
      if (why != nullptr) {
        std::ostringstream out;
        out << "method kArpack: " << wanted << " modes of a " << num_dofs
            << "-DOF system is too many for ARPACK (it needs num_modes < n − 1); used the dense "
               "solver";
        *why = out.str();
      }
      return ModalMethod::kDense;
    case ModalMethod::kAuto:
      if (num_dofs <= options.dense_max_dofs || !arpack_possible || 2 * wanted >= num_dofs) {
        return ModalMethod::kDense;
      }
      return ModalMethod::kArpack;
  }
  return ModalMethod::kDense;
}

MeanSystem AssembleMeanSystem(const SystemModel& model, std::vector<std::string>* warnings) {
  MeanSystem sys;
  const int n = model.num_dofs();
  SystemWorkspace ws(model, StorageKind::kSparse);
  sys.K = AssembleMeanStiffnessSparse(model, ws);
  sys.M = model.mass();
  sys.mesh_stiffness = ws.mesh_stiffness;
  GEARDYN_DEMAND(static_cast<int>(sys.mesh_stiffness.size()) == model.num_meshes());

  // C̄: C0 plus each mesh's B–S Eq. (39) damper on its mean core, C̄2 = (c_m/K̄) K̄2.
  sys.C = model.constant_damping();
  std::vector<Eigen::Triplet<double>> triplets;
  bool nonlinear = false, slices = false;
  for (int k = 0; k < model.num_meshes(); ++k) {
    const SystemMesh& mesh = model.meshes()[k];
    const double mean_k = std::visit(
        [&](const auto& core) -> double {
          using T = std::decay_t<decltype(core)>;
          if constexpr (std::is_same_v<T, LinearMeshCore>) {
            return Mean(core.stiffness())(0);
          } else if constexpr (std::is_same_v<T, SliceMeshCore>) {
            slices = true;
            return Mean(core.stiffness()).sum();
          } else {
            nonlinear = true;
            return 0.0;
          }
        },
        mesh.core);
    if (!(mean_k > 0.0) || mesh.damping_coefficient == 0.0) continue;
    const double factor = mesh.damping_coefficient / mean_k;
    for (int a = 0; a < 12; ++a) {
      if (mesh.dofs[a] < 0) continue;
      for (int b = 0; b < 12; ++b) {
        if (mesh.dofs[b] < 0) continue;
        const double v = factor * sys.mesh_stiffness[k](a, b);
        if (v != 0.0) triplets.emplace_back(mesh.dofs[a], mesh.dofs[b], v);
      }
    }
  }
  if (!triplets.empty()) {
    SparseMatrix mesh_damping(n, n);
    mesh_damping.setFromTriplets(triplets.begin(), triplets.end());
    sys.C = sys.C + mesh_damping;
  }
  sys.C.prune(0.0);
  sys.has_damping = sys.C.nonZeros() > 0;
  if (slices) {
    warnings->push_back(
        "slice mesh cores enter the modes through their all-loaded linearization (every slice "
        "in contact)");
  }
  if (nonlinear) {
    warnings->push_back(
        "NonlinearMeshCore meshes contribute no stiffness or damping to the mean (LTI) system");
  }
  return sys;
}

namespace {

/// Largest system the dense solver re-solves when ARPACK missed a repeated mode under kAuto
/// (≈ 3.7 n³ flops: about 10 s at 3000 DOFs on one core); above it the status stays.
constexpr int kDenseFallbackMaxDofs = 3000;

// Relative residual ‖K̄φ − λMφ‖ / (‖K̄φ‖ + |λ|‖Mφ‖); for a rigid mode ‖K̄φ‖/(s‖Mφ‖).
double MaxResidual(const MeanSystem& sys, const VectorX& lambda, const MatrixX& phi,
                   double spectrum_scale) {
  double worst = 0.0;
  for (Eigen::Index k = 0; k < phi.cols(); ++k) {
    const VectorX Kphi = sys.K * phi.col(k);
    const VectorX Mphi = sys.M * phi.col(k);
    const double r = (Kphi - lambda(k) * Mphi).norm();
    const double scale = lambda(k) == 0.0 ? spectrum_scale * Mphi.norm()
                                          : Kphi.norm() + std::abs(lambda(k)) * Mphi.norm();
    if (scale > 0.0) worst = std::max(worst, r / scale);
  }
  return worst;
}

}  // namespace
}  // namespace internal

ModalResult ComputeModes(const SystemModel& model, const ModalOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  std::string why;
  if (!options.IsValid(&why)) throw InvalidInput(why);
  const int n = model.num_dofs();
  GEARDYN_THROW_UNLESS(n > 0, "model: has no DOFs (build it with SystemBuilder)");
  // A system of n DOFs has n modes: more cannot be computed (0 = all).
  GEARDYN_THROW_UNLESS(options.num_modes <= n,
                       "ModalOptions.num_modes: must be ≤ the number of DOFs "
                           << n << " (0 = all), got " << options.num_modes);

  ModalResult result;
  Summary& summary = result.summary;
  std::string fallback;
  result.method_used = internal::SelectModalMethod(n, options, &fallback);
  if (!fallback.empty()) summary.warnings.push_back(fallback);

  const internal::MeanSystem sys = internal::AssembleMeanSystem(model, &summary.warnings);
  // Vectors only for the outputs that use them: shapes, energy fractions, the modal damping
  // ratios, and with damping the classification of a large system (its test runs on the modes)
  // and the damped modes above damped_max_dofs (from the modal ratios).
  const bool damping_needs_vectors =
      sys.has_damping && (options.compute_damping_ratios || n > kDenseDampingTestMaxDofs ||
                          (options.compute_damped && n > options.damped_max_dofs));
  const bool need_vectors =
      options.compute_shapes || options.compute_energy_fractions || damping_needs_vectors;

  GeneralizedEigenResult eig;
  switch (result.method_used) {
    case ModalMethod::kDense:
      eig = internal::SolveModesDense(sys, options, need_vectors);
      break;
    case ModalMethod::kArpack:
      eig = internal::SolveModesArpack(
          sys, options, options.num_modes > 0 ? options.num_modes : kDefaultArpackModes,
          need_vectors);
      // Lanczos can miss a repeated eigenvalue (the inertia check in
      // SolveGeneralizedEigenArpack); kAuto then answers with the dense solver where it is
      // affordable, and says so.
      if (options.method == ModalMethod::kAuto && eig.summary.status != Status::kSuccess &&
          eig.summary.counters.count("missed_eigenvalues") > 0 &&
          n <= internal::kDenseFallbackMaxDofs) {
        std::string missed = eig.summary.message;
        ModalOptions dense_options = options;
        dense_options.num_modes = options.num_modes > 0 ? options.num_modes : kDefaultArpackModes;
        eig = internal::SolveModesDense(sys, dense_options, need_vectors);
        eig.summary.warnings.push_back(missed + "; solved with the dense solver instead");
        result.method_used = ModalMethod::kDense;
      }
      break;
    case ModalMethod::kAuto:
      GEARDYN_DEMAND(result.method_used != ModalMethod::kAuto);
      break;
  }

  summary.status = eig.summary.status;
  summary.message = eig.summary.message;
  summary.counters = eig.summary.counters;
  summary.counters["num_dofs"] = n;
  for (std::string& w : eig.summary.warnings) summary.warnings.push_back(std::move(w));
  result.eigenvalues = std::move(eig.eigenvalues);
  result.num_rigid_body_modes = eig.num_rigid_body_modes;
  const Eigen::Index m = result.eigenvalues.size();
  summary.counters["num_modes"] = static_cast<long>(m);

  // f = √λ / 2π; a (tiny) negative λ left by a not-PSD status is reported as 0, never NaN.
  result.frequencies_hz.resize(m);
  for (Eigen::Index k = 0; k < m; ++k) {
    result.frequencies_hz(k) = std::sqrt(std::max(result.eigenvalues(k), 0.0)) / (2.0 * M_PI);
  }
  result.multiplicity_groups =
      internal::GroupMultiplicities(result.frequencies_hz, options.multiplicity_rel_tol);
  for (int b = 0; b < model.num_bodies(); ++b) {
    result.body_names.push_back(model.dof_map().body_name(BodyIndex(b)));
  }

  const bool have_vectors = need_vectors && eig.vectors.cols() == m && m > 0;
  if (have_vectors) {
    summary.error_estimate =
        internal::MaxResidual(sys, result.eigenvalues, eig.vectors, eig.spectrum_scale);
  }
  if (options.compute_energy_fractions && have_vectors) {
    internal::ClassifyModes(model, sys, eig.vectors, result.eigenvalues, &result);
  }

  // Damping: classification always; modal ratios when the vectors exist; damped modes if asked.
  internal::ClassifyDamping(sys, options, have_vectors ? eig.vectors : MatrixX(),
                            result.eigenvalues, &result);
  if (have_vectors && sys.has_damping) {
    result.modal_damping_ratios = VectorX::Zero(m);
    for (Eigen::Index k = 0; k < m; ++k) {
      const double omega = std::sqrt(std::max(result.eigenvalues(k), 0.0));
      if (omega > 0.0) {
        // φᵀCφ of a mode C does not damp (a mode beyond a scene's modal_ratios) is round-off:
        // read −1.7e-16 on geared-shafts. Below the rounding bound of the quadratic form,
        // γ_n |φ|ᵀ|C||φ| (Higham, Accuracy and Stability, §3.1; taken as 4nε), it is 0.
        const VectorX phi_abs = eig.vectors.col(k).cwiseAbs();
        const double bound = 4.0 * n * std::numeric_limits<double>::epsilon() *
                             phi_abs.dot(sys.C.cwiseAbs() * phi_abs);
        const double q = eig.vectors.col(k).dot(sys.C * eig.vectors.col(k));
        result.modal_damping_ratios(k) = std::abs(q) <= bound ? 0.0 : q / (2.0 * omega);
      }
    }
  }
  if (options.compute_damped && m > 0) {
    if (n <= options.damped_max_dofs) {
      result.damped_modes = internal::ComputeDampedModes(sys, eig.spectrum_scale,
                                                         result.num_rigid_body_modes, &summary);
    } else if (result.damping_kind != DampingKind::kNonProportional && have_vectors) {
      result.damped_modes =
          internal::DampedModesFromModalRatios(result.eigenvalues, result.modal_damping_ratios);
      summary.warnings.push_back(
          "damped modes from the modal damping ratios of the computed modes (proportional "
          "damping, n > damped_max_dofs: exact, no state-space solve)");
    } else {
      std::ostringstream out;
      out << "damped modes not computed: " << n
          << " DOFs > damped_max_dofs = " << options.damped_max_dofs << " and the damping is "
          << ToString(result.damping_kind);
      summary.warnings.push_back(out.str());
    }
  }

  if (options.compute_shapes && have_vectors) {
    result.shapes = std::move(eig.vectors);
    result.dof_names.reserve(n);
    for (int i = 0; i < n; ++i) result.dof_names.push_back(model.dof_map().dof_name(i));
  }
  summary.wall_time_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace geardyn
