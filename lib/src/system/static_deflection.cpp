#include "geardyn/system/static_deflection.hpp"

#include <chrono>
#include <cmath>
#include <sstream>

#include "geardyn/common/check.hpp"
#include "geardyn/numerics/rigid_modes.hpp"
#include "geardyn/system/workspace.hpp"

namespace geardyn {

bool StaticDeflectionOptions::IsValid(std::string* why) const {
  std::ostringstream os;
  if (!(null_tol > 0.0 && null_tol < 1.0)) {
    os << "null_tol: must be in (0, 1), got " << null_tol;
  } else if (!(balance_tol > 0.0 && std::isfinite(balance_tol))) {
    os << "balance_tol: must be finite and > 0, got " << balance_tol;
  } else if (samples_per_period < 1) {
    os << "samples_per_period: must be ≥ 1, got " << samples_per_period;
  } else {
    return true;
  }
  if (why != nullptr) *why = os.str();
  return false;
}

StaticDeflectionResult SolveStaticDeflection(const SystemModel& model,
                                             const StaticDeflectionOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  std::string why;
  GEARDYN_THROW_UNLESS(options.IsValid(&why), why);
  StaticDeflectionResult result;
  const int n = model.num_dofs();
  SystemWorkspace ws(model, StorageKind::kDense);
  const MatrixX kbar = AssembleMeanStiffness(model, ws);
  result.load = AssembleMeanLoad(model, ws, options.samples_per_period);

  // K̄ = V Λ Vᵀ in the √diag(K̄)-scaled coordinates (rigid_modes.hpp); the deflection is the
  // solution orthogonal to the rigid modes there, the load's part along them is dropped.
  const RigidBodyModes rigid = ComputeRigidBodyModes(kbar, options.null_tol);
  if (!rigid.ok) {
    result.summary.status = Status::kNumericalIssue;
    result.summary.message = "eigen-decomposition of the mean stiffness failed";
    return result;
  }
  const int r0 = rigid.count();
  const VectorX fs = rigid.inv_sqrt_d.asDiagonal() * result.load;  // load in scaled coordinates
  VectorX ys = VectorX::Zero(n);
  for (int r = r0; r < n; ++r) {
    const double proj = rigid.eigenvectors.col(r).dot(fs);
    ys += (proj / rigid.eigenvalues(r)) * rigid.eigenvectors.col(r);
  }
  result.num_rigid_modes = r0;
  result.deflection = rigid.inv_sqrt_d.asDiagonal() * ys;
  const double fnorm = fs.norm();
  const double unbalanced = rigid.UnbalancedFraction(result.load) * fnorm;
  result.unbalanced_load = unbalanced;
  if (result.num_rigid_modes > 0) {
    std::ostringstream os;
    os << result.num_rigid_modes << " rigid-body mode(s) of the mean stiffness; solved in the "
       << "complement";
    result.summary.warnings.push_back(os.str());
  }
  if (fnorm > 0.0 && unbalanced > options.balance_tol * fnorm) {
    std::ostringstream os;
    os << "the mean load is not balanced: a part " << unbalanced / fnorm
       << " (relative) acts on rigid-body modes (the torques do not balance through the meshes "
          "and supports); it was removed";
    result.summary.warnings.push_back(os.str());
  }

  // Meshes.
  const std::vector<SystemMesh>& meshes = model.meshes();
  for (int k = 0; k < static_cast<int>(meshes.size()); ++k) {
    const SystemMesh& mesh = meshes[k];
    Vector12 q = Vector12::Zero();
    for (int a = 0; a < 12; ++a) {
      if (mesh.dofs[a] >= 0) q(a) = result.deflection(mesh.dofs[a]);
    }
    const Vector2 delta = mesh.G * q;
    // Mean mesh force F̄ = K̄2 δ̄ − mean(K2 ε) (spec 01 §3: F = K2 (δ − ε)).
    Vector2 te_load = Vector2::Zero();
    if (const auto* core = std::get_if<LinearMeshCore>(&mesh.core)) {
      te_load = CalcMeanTransmissionErrorLoad(*core, options.samples_per_period);
    }
    const Vector2 force = mesh.mean_core_stiffness * delta - te_load;
    MeshStaticState state;
    state.name = mesh.name;
    state.delta_eta = delta(0);
    state.delta_zeta = delta(1);
    state.force_eta = force(0);
    state.moment_zeta = force(1);
    const bool has_stiffness = mesh.mean_core_stiffness(0, 0) > 0.0;
    state.contact_open = has_stiffness && force(0) <= 0.0;
    if (state.contact_open) {
      std::ostringstream os;
      os << "mesh '" << mesh.name << "': the mean load would open the contact (mean mesh force "
         << force(0) << " N ≤ 0 with the drive convention: the torque drives the other flank)";
      result.summary.warnings.push_back(os.str());
    }
    result.meshes.push_back(state);
  }

  for (const SystemElement& e : model.elements()) {
    VectorX qe = VectorX::Zero(static_cast<int>(e.dofs.size()));
    for (std::size_t a = 0; a < e.dofs.size(); ++a) {
      if (e.dofs[a] >= 0) qe(a) = result.deflection(e.dofs[a]);
    }
    result.element_forces.push_back(e.stiffness * qe);
  }
  result.summary.counters["num_dofs"] = n;
  result.summary.counters["rigid_modes"] = result.num_rigid_modes;
  result.summary.wall_time_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace geardyn
