/// @file
/// @brief MakeSystemNhbProblem (system_nonlinear_hb.hpp): nonlinear coordinates per mesh, the
/// mean linear part, and the exact reduction q = T z that removes the rigid-body modes.
#include "system_nhb/system_problem.hpp"

#include <Eigen/QR>
#include <algorithm>
#include <cmath>
#include <sstream>
#include <variant>

#include "geardyn/analyses/system_nonlinear_hb.hpp"
#include "geardyn/common/check.hpp"
#include "geardyn/numerics/rigid_modes.hpp"
#include "geardyn/system/system_harmonics.hpp"
#include "geardyn/system/system_steps.hpp"
#include "geardyn/system/workspace.hpp"
#include "system_nhb/mesh_force_law.hpp"

namespace geardyn {
namespace {

/// Number of nonlinear coordinates of a mesh: δ_η, plus δ_ζ when its force depends on it.
int CoordinateCount(const SystemMesh& mesh, const VectorX& zeta_row) {
  const bool zeta_moves = zeta_row.lpNorm<Eigen::Infinity>() > 0.0;
  if (std::holds_alternative<SliceMeshCore>(mesh.core)) return zeta_moves ? 2 : 1;
  const auto& core = std::get<LinearMeshCore>(mesh.core);
  return core.level() == MeshCoreLevel::kBlankenshipSingh && zeta_moves ? 2 : 1;
}

/// θ-mean of the damping C(θ) = C0 + Σ Gᵀ C2(θ_k) G from each mesh's own-phase harmonic 0
/// (ExpandOwnPhaseMeshHarmonics): exact closed form for stepwise cores, the trigonometric
/// interpolant's mean on ≥ 256 samples per core period otherwise — no dense assembly per sample,
/// over the core's own period (not the hunting period of the forcing), and valid when the
/// meshes run at several frequencies.
MatrixX MeanDamping(const SystemModel& model) {
  MatrixX C = model.DenseConstantDamping();
  for (const SystemMesh& mesh : model.meshes()) {
    const Matrix2 c2 = ExpandOwnPhaseMeshHarmonics(mesh, 0).damping[0].real();
    const Eigen::Matrix<double, 12, 12> cb = mesh.G.transpose() * c2 * mesh.G;
    for (int a = 0; a < 12; ++a) {
      for (int c = 0; c < 12; ++c) {
        if (mesh.dofs[a] >= 0 && mesh.dofs[c] >= 0) C(mesh.dofs[a], mesh.dofs[c]) += cb(a, c);
      }
    }
  }
  return C;
}

}  // namespace

SystemNhbProblem MakeSystemNhbProblem(const SystemModel& model) {
  GEARDYN_THROW_UNLESS(model.num_meshes() > 0,
                       "nonlinear harmonic balance: the model has no "
                       "meshes (nothing is nonlinear; use the linear "
                       "harmonic balance)");
  CheckSingleMeshFrequency(model, "nonlinear harmonic balance");
  return internal::BuildSystemNhbProblem(model);
}

namespace internal {

VectorX ScatteredMeshRow(const SystemMesh& mesh, int channel, int dofs) {
  VectorX row = VectorX::Zero(dofs);
  for (int a = 0; a < 12; ++a) {
    if (mesh.dofs[a] >= 0) row(mesh.dofs[a]) += mesh.G(channel, a);
  }
  return row;
}

SystemNhbProblem BuildSystemNhbProblem(const SystemModel& model) {
  GEARDYN_THROW_UNLESS(model.num_meshes() > 0,
                       "nonlinear harmonic balance: the model has no "
                       "meshes (nothing is nonlinear; use the linear "
                       "harmonic balance)");
  const int N = model.num_dofs();
  SystemNhbProblem out;
  out.period_meshes = static_cast<int>(model.period_meshes());

  // Nonlinear coordinates and their rows P (n × N).
  std::vector<internal::MeshForceTerm> terms;
  std::vector<VectorX> rows;
  out.mesh_eta_coordinate.assign(model.num_meshes(), -1);
  for (int k = 0; k < model.num_meshes(); ++k) {
    const SystemMesh& mesh = model.meshes()[k];
    GEARDYN_THROW_UNLESS(
        !std::holds_alternative<std::shared_ptr<const NonlinearMeshCore>>(mesh.core),
        "nonlinear harmonic balance: mesh '"
            << mesh.name
            << "' has a NonlinearMeshCore (user code); only slice and linear "
               "cores are supported — use the time-domain simulator");
    const VectorX eta = internal::ScatteredMeshRow(mesh, 0, N);
    const VectorX zeta = internal::ScatteredMeshRow(mesh, 1, N);
    if (eta.lpNorm<Eigen::Infinity>() == 0.0) {
      out.warnings.push_back("mesh '" + mesh.name +
                             "': every coordinate of its deflection is held fixed; skipped");
      continue;
    }
    internal::MeshForceTerm term;
    term.mesh = k;
    term.first = static_cast<int>(rows.size());
    term.count = CoordinateCount(mesh, zeta);
    term.mean_k2 = mesh.mean_core_stiffness;
    out.mesh_eta_coordinate[k] = term.first;
    rows.push_back(eta);
    out.coordinate_mesh.push_back(k);
    out.coordinate_channel.push_back(0);
    if (term.count == 2) {
      rows.push_back(zeta);
      out.coordinate_mesh.push_back(k);
      out.coordinate_channel.push_back(1);
    }
    terms.push_back(term);
  }
  const int n = static_cast<int>(rows.size());
  MatrixX P(n, N);
  for (int i = 0; i < n; ++i) P.row(i) = rows[i].transpose();

  // Linear part: K̄ (θ-mean, all loaded), C̄, M, f0.
  SystemWorkspace ws(model, StorageKind::kDense);
  const MatrixX K = AssembleMeanStiffness(model, ws);
  const MatrixX C = MeanDamping(model);
  const MatrixX M = model.DenseMass();
  const VectorX f0 = model.constant_load();
  // Harmonic loads: the NhbProblem's f₁ at the excitation Ω = the mesh frequency (order 1).
  VectorXc f1 = VectorXc::Zero(N);
  for (const SystemHarmonicLoad& h : model.harmonic_loads()) {
    GEARDYN_THROW_UNLESS(h.order == 1,
                         "nonlinear harmonic balance: harmonic load '"
                             << h.name << "' has order " << h.order
                             << "; only order 1 (at the mesh frequency) is supported here (use "
                                "the linear harmonic balance or the time domain)");
    for (int a = 0; a < kBodyDofs; ++a) {
      if (h.dofs[a] >= 0) f1(h.dofs[a]) += h.amplitude(a);
    }
  }

  // The blocks (model.blocks(): decoupled DOF groups) that no mesh coordinate or harmonic load
  // touches are LTI and loaded by constants only: their steady state is static (solved here once);
  // keeping them out of the HB also keeps their undamped modes (|μ| = 1) out of the stability
  // verdict.
  std::vector<int> coupled, uncoupled;
  for (const std::vector<int>& block : model.blocks()) {
    bool touched = false;
    for (int d : block) {
      touched = touched || P.col(d).lpNorm<Eigen::Infinity>() > 0.0 || std::abs(f1(d)) > 0.0;
    }
    for (int d : block) (touched ? coupled : uncoupled).push_back(d);
  }
  std::sort(coupled.begin(), coupled.end());
  std::sort(uncoupled.begin(), uncoupled.end());
  out.static_response = VectorX::Zero(N);
  double unbalanced = 0.0;
  if (!uncoupled.empty()) {
    const RigidBodyModes r = ComputeRigidBodyModes(K(uncoupled, uncoupled));
    GEARDYN_THROW_UNLESS(r.ok,
                         "nonlinear harmonic balance: the eigen-decomposition of the "
                         "mean stiffness failed");
    const VectorX fu = f0(uncoupled);
    unbalanced = std::max(unbalanced, r.UnbalancedFraction(fu));
    const VectorX fs = r.inv_sqrt_d.cwiseProduct(fu);
    VectorX ys = VectorX::Zero(fu.size());
    for (Eigen::Index i = r.count(); i < ys.size(); ++i) {
      ys += (r.eigenvectors.col(i).dot(fs) / r.eigenvalues(i)) * r.eigenvectors.col(i);
    }
    out.static_response(uncoupled) = r.inv_sqrt_d.cwiseProduct(ys);
    out.rigid_modes += r.count();
  }

  // Rigid modes V of K̄ on the coupled DOFs and the reduction T: orthonormal basis of
  // {q : Vᵀ M q = 0} there, zero rows on the uncoupled DOFs.
  const int Nc = static_cast<int>(coupled.size());
  const MatrixX Kc = K(coupled, coupled), Mc = M(coupled, coupled);
  VectorX fc = f0(coupled);
  const RigidBodyModes rigid = ComputeRigidBodyModes(Kc);
  GEARDYN_THROW_UNLESS(rigid.ok,
                       "nonlinear harmonic balance: the eigen-decomposition of the "
                       "mean stiffness failed");
  out.rigid_modes += rigid.count();
  MatrixX Tc = MatrixX::Identity(Nc, Nc);
  if (rigid.count() > 0) {
    unbalanced = std::max(unbalanced, rigid.UnbalancedFraction(fc));
    fc = rigid.Balance(fc);
    Eigen::HouseholderQR<MatrixX> qr(Mc * rigid.modes);
    const MatrixX Q = qr.householderQ() * MatrixX::Identity(Nc, Nc);
    Tc = Q.rightCols(Nc - rigid.count());
  }
  out.unbalanced_load = unbalanced;
  if (unbalanced > 1e-9) {
    std::ostringstream os;
    os << "the mean load is not balanced: a part " << unbalanced
       << " (relative) acts on the rigid-body modes and was removed";
    out.warnings.push_back(os.str());
  }
  out.reduction = MatrixX::Zero(N, Tc.cols());
  out.reduction(coupled, Eigen::all) = Tc;
  const MatrixX Tt = Tc.transpose();
  NhbProblem& p = out.problem;
  p.mass = Tt * Mc * Tc;
  p.damping = Tt * C(coupled, coupled) * Tc;
  p.stiffness = Tt * Kc * Tc;
  p.mass = 0.5 * (p.mass + p.mass.transpose()).eval();
  p.damping = 0.5 * (p.damping + p.damping.transpose()).eval();
  p.stiffness = 0.5 * (p.stiffness + p.stiffness.transpose()).eval();
  p.projection = P(Eigen::all, coupled) * Tc;
  p.force_mean = Tt * fc;
  p.force_amplitude = Tt.cast<std::complex<double>>() * f1(coupled);
  p.law = std::make_shared<internal::MeshForceLaw>(model, std::move(terms));
  return out;
}

}  // namespace internal
}  // namespace geardyn
