// HarmonicBalanceSolver: setup per H (mesh harmonics, mean matrices, mesh-deflection channels,
// rigid-body penalty, forcing) and the kDecoupled / kCondensed / kDirect solves
// (harmonic_balance.hpp).
#include <Eigen/LU>
#include <Eigen/SparseLU>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <numbers>

#include "geardyn/analyses/harmonic_balance.hpp"
#include "geardyn/common/check.hpp"
#include "geardyn/system/system_harmonics.hpp"
#include "geardyn/system/workspace.hpp"
#include "hb_internal.hpp"

namespace geardyn {
namespace {

using internal::Complex;
using ComplexSparse = Eigen::SparseMatrix<Complex, Eigen::ColMajor, int>;

// Relative size below which a θ-varying harmonic counts as zero (round-off of the expansion).
constexpr double kVaryingTol = 1e-13;
// Estimated reciprocal condition number below which a solve is reported as unreliable.
constexpr double kMinRcond = 1e-14;

// Scatters Gᵀ X2 G of a mesh (X2 2×2 real) into triplets.
void ScatterMesh(const SystemMesh& mesh, const Matrix2& X2,
                 std::vector<Eigen::Triplet<double>>* t) {
  const Matrix12 block = mesh.G.transpose() * X2 * mesh.G;
  for (int a = 0; a < 12; ++a) {
    if (mesh.dofs[a] < 0) continue;
    for (int b = 0; b < 12; ++b) {
      if (mesh.dofs[b] < 0 || block(a, b) == 0.0) continue;
      t->emplace_back(mesh.dofs[a], mesh.dofs[b], block(a, b));
    }
  }
}

}  // namespace

// Everything that depends on (model, H) but not on the frequency.
struct HbSetup {
  int H = 0;
  int n = 0;
  bool dense = true;
  std::vector<MeshHarmonics> mesh_harmonics;  // m = 0 … 2H
  SparseMatrix M, Kbar, Cbar;                 // mean system
  SparseMatrix Kbar0;                         // K̄ + rigid-body penalty W (harmonic 0 only)
  MatrixX M_d, Kbar_d, Kbar0_d, Cbar_d;       // dense copies (dense storage)
  std::vector<VectorXc> F;                    // k = 0 … H (F_0 balanced)
  double unbalanced = 0.0;
  // Mesh-deflection channels (rows of G_all) whose stiffness or damping varies with θ.
  int r = 0;
  MatrixX Gt_d;                  // (n × r) dense G_allᵀ
  SparseMatrix Gt;               // (n × r)
  SparseMatrix G;                // (r × n)
  std::vector<MatrixXc> dK, dC;  // m = 0 … 2H: (r × r) harmonics of the θ-varying part
  // Reused factorizations.
  Eigen::PartialPivLU<MatrixXc> dense_lu;
  Eigen::SparseLU<ComplexSparse> sparse_lu;
  bool pattern_analysed = false;
  std::unique_ptr<internal::HbOutputSampler> sampler;
};

struct HarmonicBalanceSolver::Impl {
  SystemModel model;
  HbOptions options;
  std::vector<std::string> warnings;
  internal::RigidModes rigid;
  bool rigid_done = false;
  std::map<int, std::unique_ptr<HbSetup>> setups;

  HbSetup& Setup(int H);
  MatrixXc SolveDecoupledOrCondensed(HbSetup& s, double omega, bool condensed, double* rcond,
                                     long* factorizations);
  MatrixXc SolveDirect(HbSetup& s, double omega, double* rcond);
  HbResult SolveFixed(int H, double f_m);
};

HbSetup& HarmonicBalanceSolver::Impl::Setup(int H) {
  auto it = setups.find(H);
  if (it != setups.end()) return *it->second;
  auto s = std::make_unique<HbSetup>();
  const int n = model.num_dofs();
  s->H = H;
  s->n = n;
  s->dense = model.storage_hint() == StorageKind::kDense;
  s->mesh_harmonics = ExpandMeshHarmonics(model, 2 * H);
  const auto& meshes = model.meshes();

  // Mean K̄, C̄ from the m = 0 harmonics (real) plus the constant parts.
  std::vector<Eigen::Triplet<double>> tk, tc;
  for (size_t k = 0; k < meshes.size(); ++k) {
    ScatterMesh(meshes[k], s->mesh_harmonics[k].stiffness[0].real(), &tk);
    ScatterMesh(meshes[k], s->mesh_harmonics[k].damping[0].real(), &tc);
  }
  SparseMatrix mk(n, n), mc(n, n);
  mk.setFromTriplets(tk.begin(), tk.end());
  mc.setFromTriplets(tc.begin(), tc.end());
  s->M = model.mass();
  s->Kbar = model.constant_stiffness() + mk;
  s->Cbar = model.constant_damping() + mc;
  if (!rigid_done) {
    rigid = internal::ComputeRigidModes(MatrixX(s->Kbar));
    rigid_done = true;
  }
  if (rigid.count() > 0) {
    // W = U Uᵀ from the thresholded (sparse) U: O(nnz) memory for large systems.
    const double umax = rigid.U.cwiseAbs().maxCoeff();
    const SparseMatrix U = rigid.U.sparseView(1e-14 * umax, 1.0);
    const SparseMatrix W = U * SparseMatrix(U.transpose());
    // K̄0 = K̄ + W for k = 0 only; K̄ keeps W's pattern (explicit zeros) so that every A_k has
    // one sparsity pattern.
    s->Kbar0 = s->Kbar + W;
    s->Kbar = s->Kbar + 0.0 * W;
  } else {
    s->Kbar0 = s->Kbar;
  }
  s->Kbar.makeCompressed();
  s->Kbar0.makeCompressed();
  if (s->dense) {
    s->M_d = MatrixX(s->M);
    s->Kbar_d = MatrixX(s->Kbar);
    s->Kbar0_d = MatrixX(s->Kbar0);
    s->Cbar_d = MatrixX(s->Cbar);
  }

  // Forcing F_k = δ_k0 f0 + Σ Gᵀ (K2 ε)_k.
  s->F.assign(H + 1, VectorXc::Zero(n));
  s->F[0] = model.constant_load().cast<Complex>();
  for (size_t k = 0; k < meshes.size(); ++k) {
    const SystemMesh& mesh = meshes[k];
    for (int h = 0; h <= H; ++h) {
      const Eigen::Matrix<Complex, 12, 1> f =
          mesh.G.transpose().cast<Complex>() * s->mesh_harmonics[k].load[h];
      for (int a = 0; a < 12; ++a) {
        if (mesh.dofs[a] >= 0) s->F[h](mesh.dofs[a]) += f(a);
      }
    }
  }
  s->unbalanced = internal::BalanceMeanLoad(rigid, &s->F[0]);

  // Channels whose K2 or C2 varies with θ (the rank of the LTV part).
  std::vector<std::pair<int, int>> channels;  // (mesh, row of G)
  for (size_t k = 0; k < meshes.size(); ++k) {
    const MeshHarmonics& mh = s->mesh_harmonics[k];
    double scale_k = mh.stiffness[0].cwiseAbs().maxCoeff();
    double scale_c = mh.damping[0].cwiseAbs().maxCoeff();
    for (int c = 0; c < 2; ++c) {
      bool varies = false;
      for (int m = 1; m <= 2 * H && !varies; ++m) {
        varies = mh.stiffness[m].row(c).cwiseAbs().maxCoeff() > kVaryingTol * scale_k ||
                 mh.damping[m].row(c).cwiseAbs().maxCoeff() > kVaryingTol * scale_c;
      }
      if (varies) channels.emplace_back(static_cast<int>(k), c);
    }
  }
  s->r = static_cast<int>(channels.size());
  std::vector<Eigen::Triplet<double>> tg;
  for (int row = 0; row < s->r; ++row) {
    const SystemMesh& mesh = meshes[channels[row].first];
    for (int a = 0; a < 12; ++a) {
      const double g = mesh.G(channels[row].second, a);
      if (mesh.dofs[a] >= 0 && g != 0.0) tg.emplace_back(row, mesh.dofs[a], g);
    }
  }
  s->G.resize(s->r, n);
  s->G.setFromTriplets(tg.begin(), tg.end());
  s->Gt = s->G.transpose();
  s->Gt_d = MatrixX(s->Gt);
  s->dK.assign(2 * H + 1, MatrixXc::Zero(s->r, s->r));
  s->dC.assign(2 * H + 1, MatrixXc::Zero(s->r, s->r));
  for (int m = 1; m <= 2 * H; ++m) {
    for (int a = 0; a < s->r; ++a) {
      for (int b = 0; b < s->r; ++b) {
        if (channels[a].first != channels[b].first) continue;  // meshes do not couple
        const MeshHarmonics& mh = s->mesh_harmonics[channels[a].first];
        s->dK[m](a, b) = mh.stiffness[m](channels[a].second, channels[b].second);
        s->dC[m](a, b) = mh.damping[m](channels[a].second, channels[b].second);
      }
    }
  }
  s->sampler = std::make_unique<internal::HbOutputSampler>(
      model, H, internal::ChooseTimeSamples(H, options.time_samples));
  HbSetup& ref = *s;
  setups.emplace(H, std::move(s));
  return ref;
}

// Block-diagonal LTI harmonics A_k = −k²Ω²M + ikΩC̄ + K̄ solved for [F_k, G_allᵀ]; with the
// coupling (condensed) the mesh-deflection system (I + R T) D = D⁰ in the real layout, then
// Q_k = A_k⁻¹ (F_k − G_allᵀ (T D)_k).
MatrixXc HarmonicBalanceSolver::Impl::SolveDecoupledOrCondensed(HbSetup& s, double omega,
                                                                bool condensed, double* rcond,
                                                                long* factorizations) {
  const int H = s.H, n = s.n;
  const int r = condensed ? s.r : 0;
  std::vector<MatrixXc> Y(H + 1);  // n × (1 + r): A_k⁻¹ [F_k, G_allᵀ]
  MatrixXc rhs(n, 1 + r);
  *rcond = 1.0;
  for (int k = 0; k <= H; ++k) {
    const double kw = k * omega;
    rhs.col(0) = s.F[k];
    if (r > 0) rhs.rightCols(r) = s.Gt_d.cast<Complex>();
    if (s.dense) {
      MatrixXc A = (k == 0 ? s.Kbar0_d : s.Kbar_d).cast<Complex>();
      A += Complex(-kw * kw, 0.0) * s.M_d.cast<Complex>();
      A += Complex(0.0, kw) * s.Cbar_d.cast<Complex>();
      s.dense_lu.compute(A);
      *rcond = std::min(*rcond, s.dense_lu.rcond());
      Y[k] = s.dense_lu.solve(rhs);
    } else {
      ComplexSparse A = (k == 0 ? s.Kbar0 : s.Kbar).cast<Complex>() +
                        Complex(-kw * kw, 0.0) * s.M.cast<Complex>() +
                        Complex(0.0, kw) * s.Cbar.cast<Complex>();
      A.makeCompressed();
      if (!s.pattern_analysed) {
        s.sparse_lu.analyzePattern(A);
        s.pattern_analysed = true;
      }
      s.sparse_lu.factorize(A);
      if (s.sparse_lu.info() != Eigen::Success) {
        *rcond = 0.0;
        return MatrixXc::Constant(n, H + 1, Complex(NAN, NAN));
      }
      Y[k] = s.sparse_lu.solve(rhs);
    }
    ++*factorizations;
  }
  MatrixXc Q(n, H + 1);
  if (r == 0) {
    for (int k = 0; k <= H; ++k) Q.col(k) = Y[k].col(0);
    return Q;
  }
  // Toeplitz block T_{k,j} = ΔK_{k−j} + i jΩ ΔC_{k−j} (ΔX_{−m} = conj ΔX_m).
  const auto T = [&](int k, int j) -> MatrixXc {
    const int m = k - j;
    const MatrixXc& dk = s.dK[std::abs(m)];
    const MatrixXc& dc = s.dC[std::abs(m)];
    const Complex iw(0.0, j * omega);
    return m >= 0 ? MatrixXc(dk + iw * dc) : MatrixXc(dk.conjugate() + iw * dc.conjugate());
  };
  const int size = r * (2 * H + 1);
  MatrixX A = MatrixX::Identity(size, size);
  std::vector<VectorXc> d0(H + 1);
  std::vector<MatrixXc> R(H + 1);
  for (int k = 0; k <= H; ++k) {
    R[k] = s.G.cast<Complex>() * Y[k].rightCols(r);
    d0[k] = s.G.cast<Complex>() * Y[k].col(0);
  }
  for (int k = 0; k <= H; ++k) {
    for (int j = std::max(-H, k - 2 * H); j <= H; ++j) {
      internal::AddRealBlock(r, k, j, R[k] * T(k, j), &A);
    }
  }
  Eigen::PartialPivLU<MatrixX> lu(A);
  *rcond = std::min(*rcond, lu.rcond());
  ++*factorizations;
  const MatrixXc D = internal::FromRealLayout(lu.solve(internal::ToRealLayout(d0)), r, H);
  for (int k = 0; k <= H; ++k) {
    VectorXc td = VectorXc::Zero(r);
    for (int j = std::max(-H, k - 2 * H); j <= H; ++j) {
      const VectorXc dj = j >= 0 ? VectorXc(D.col(j)) : VectorXc(D.col(-j).conjugate());
      td += T(k, j) * dj;
    }
    Q.col(k) = Y[k].col(0) - Y[k].rightCols(r) * td;
  }
  return Q;
}

MatrixXc HarmonicBalanceSolver::Impl::SolveDirect(HbSetup& s, double omega, double* rcond) {
  const LinearHbSystem sys = MakeLinearHbSystem(
      model, s.H, omega * static_cast<double>(model.period_meshes()) / (2.0 * std::numbers::pi));
  Eigen::PartialPivLU<MatrixX> lu(sys.matrix);
  *rcond = lu.rcond();
  return internal::FromRealLayout(lu.solve(sys.rhs), s.n, s.H);
}

HbResult HarmonicBalanceSolver::Impl::SolveFixed(int H, double f_m) {
  HbSetup& s = Setup(H);
  HbResult result;
  result.mesh_frequency_hz = f_m;
  result.period_meshes = model.period_meshes();
  result.harmonics = H;
  const double omega = 2.0 * std::numbers::pi * f_m / static_cast<double>(result.period_meshes);
  HbMethod method = options.method;
  if (method == HbMethod::kAuto) method = s.r == 0 ? HbMethod::kDecoupled : HbMethod::kCondensed;
  GEARDYN_THROW_UNLESS(method != HbMethod::kDecoupled || s.r == 0,
                       "HbOptions::method: 'decoupled' needs constant K and C (LTI), but "
                           << s.r << " mesh-deflection channels vary with θ");
  result.method_used = method;
  double rcond = 1.0;
  long factorizations = 0;
  MatrixXc Q;
  if (method == HbMethod::kDirect) {
    Q = SolveDirect(s, omega, &rcond);
    factorizations = 1;
    result.summary.counters["unknowns"] = static_cast<long>(s.n) * (2 * H + 1);
  } else {
    Q = SolveDecoupledOrCondensed(s, omega, method == HbMethod::kCondensed, &rcond,
                                  &factorizations);
    result.summary.counters["condensed_unknowns"] =
        method == HbMethod::kCondensed ? static_cast<long>(s.r) * (2 * H + 1) : 0L;
  }
  result.summary.counters["factorizations"] = factorizations;
  result.summary.counters["harmonics"] = H;
  result.summary.counters["rigid_body_modes"] = rigid.count();  // rigid_modes.hpp criterion
  result.summary.warnings = warnings;
  if (s.unbalanced > 1e-8) {
    result.summary.warnings.push_back(
        "the mean load has a part along the rigid-body modes (relative size " +
        std::to_string(s.unbalanced) + "); removed (the supports cannot react it)");
  }
  if (!Q.allFinite()) {
    result.summary.status = Status::kNumericalIssue;
    result.summary.message = "harmonic balance: the solve failed (singular operator at " +
                             std::to_string(f_m) + " Hz: an undamped resonance?)";
    return result;
  }
  if (rcond < kMinRcond) {
    result.summary.status = Status::kNumericalIssue;
    result.summary.message =
        "harmonic balance: the operator is singular to working precision "
        "(estimated 1/cond " +
        std::to_string(rcond) + "): an undamped resonance at " + std::to_string(f_m) + " Hz?";
  }
  const double max_rms =
      s.sampler->Evaluate(Q, omega, options.compute_forces, options.keep_harmonics, &result);
  // Fixed-H estimate: RMS of the DTE harmonics in (3H/4, H] relative to the largest RMS DTE.
  double top = 0.0;
  for (const HbMeshOutput& m : result.meshes) {
    double e2 = 0.0;
    for (int h = 3 * H / 4 + 1; h <= H; ++h) e2 += 0.5 * m.dte_amplitudes(h) * m.dte_amplitudes(h);
    top = std::max(top, std::sqrt(e2));
  }
  result.summary.error_estimate = max_rms > 0.0 ? top / max_rms : 0.0;
  return result;
}

HarmonicBalanceSolver::HarmonicBalanceSolver(const SystemModel& model, const HbOptions& options)
    : impl_(std::make_unique<Impl>()) {
  std::string why;
  GEARDYN_THROW_UNLESS(options.IsValid(&why), why);
  impl_->model = model;
  impl_->options = options;
  impl_->warnings = internal::CheckLinearHbModel(model);
}

HarmonicBalanceSolver::~HarmonicBalanceSolver() = default;

HbResult HarmonicBalanceSolver::Solve(double mesh_frequency_hz) {
  GEARDYN_THROW_UNLESS(std::isfinite(mesh_frequency_hz) && mesh_frequency_hz > 0.0,
                       "mesh_frequency_hz: must be finite and > 0, got " << mesh_frequency_hz);
  const auto start = std::chrono::steady_clock::now();
  const HbOptions& o = impl_->options;
  HbResult result;
  if (o.harmonics > 0) {
    result = impl_->SolveFixed(o.harmonics, mesh_frequency_hz);
  } else {
    // H, 2H, 4H, …: accept when the RMS DTE changed by at most tolerance (relative).
    HbResult previous = impl_->SolveFixed(o.min_harmonics, mesh_frequency_hz);
    result = previous;
    for (int H = o.min_harmonics; previous.summary.ok();) {
      const int next = std::min(2 * H, o.max_harmonics);
      if (next == H) {
        result.summary.status = Status::kToleranceNotMet;
        result.summary.message = "harmonic balance: tolerance " + std::to_string(o.tolerance) +
                                 " not met with max_harmonics = " + std::to_string(H);
        break;
      }
      result = impl_->SolveFixed(next, mesh_frequency_hz);
      if (!result.summary.ok()) break;
      double scale = 0.0, change = 0.0;
      for (size_t k = 0; k < result.meshes.size(); ++k) {
        scale = std::max(scale, result.meshes[k].rms_dte);
        change = std::max(change, std::abs(result.meshes[k].rms_dte - previous.meshes[k].rms_dte));
      }
      result.summary.error_estimate = scale > 0.0 ? change / scale : 0.0;
      if (result.summary.error_estimate <= o.tolerance) break;
      previous = result;
      H = next;
    }
  }
  result.summary.wall_time_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

HbResult SolveHarmonicBalance(const SystemModel& model, const HbOptions& options,
                              double mesh_frequency_hz) {
  HarmonicBalanceSolver solver(model, options);
  return solver.Solve(mesh_frequency_hz);
}

HbSweepResult SweepHarmonicBalance(const SystemModel& model,
                                   const std::vector<double>& mesh_frequencies_hz,
                                   const HbOptions& options, const HbProgress& progress) {
  for (size_t i = 0; i < mesh_frequencies_hz.size(); ++i) {
    const double f = mesh_frequencies_hz[i];
    GEARDYN_THROW_UNLESS(std::isfinite(f) && f > 0.0,
                         "mesh_frequencies_hz[" << i << "]: must be finite and > 0, got " << f);
  }
  const auto start = std::chrono::steady_clock::now();
  HarmonicBalanceSolver solver(model, options);
  HbSweepResult sweep;
  sweep.points.reserve(mesh_frequencies_hz.size());
  const int total = static_cast<int>(mesh_frequencies_hz.size());
  for (int i = 0; i < total; ++i) {
    sweep.points.push_back(solver.Solve(mesh_frequencies_hz[i]));
    const Summary& p = sweep.points.back().summary;
    for (const auto& [name, count] : p.counters) sweep.summary.counters[name] += count;
    sweep.summary.error_estimate = std::max(sweep.summary.error_estimate, p.error_estimate);
    if (static_cast<int>(p.status) > static_cast<int>(sweep.summary.status)) {
      sweep.summary.status = p.status;
      sweep.summary.message = p.message;
    }
    if (progress) progress(i + 1, total);
  }
  if (!sweep.points.empty()) sweep.summary.warnings = sweep.points.front().summary.warnings;
  sweep.summary.counters["points"] = total;
  sweep.summary.wall_time_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return sweep;
}

}  // namespace geardyn
