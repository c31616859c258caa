// HarmonicBalanceSolver: setup per H (mesh harmonics, mean matrices, mesh-deflection channels,
// rigid-body penalty, forcing) and the kDecoupled / kCondensed / kDirect solves
// (harmonic_balance.hpp).
#include <Eigen/LU>
#include <Eigen/SparseLU>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <iomanip>
#include <limits>
#include <map>
#include <numbers>
#include <numeric>
#include <sstream>

#include "geardyn/analyses/harmonic_balance.hpp"
#include "geardyn/common/check.hpp"
#include "geardyn/numerics/symmetric_eigen.hpp"
#include "geardyn/system/system_harmonics.hpp"
#include "geardyn/system/workspace.hpp"
#include "hb_internal.hpp"
#include "hb_solver_impl.hpp"

namespace geardyn {
namespace {

using internal::Complex;
using internal::ComplexSparse;

using internal::kForcingTol;
using internal::kMaxHbBytes;
using internal::kMinRcond;
using internal::kVaryingTol;
using internal::kWarnRcond;

using internal::FormatG;
using internal::kIllConditionedText;
using internal::MergePointWarnings;
using internal::PointWarningPrefix;

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

namespace internal {

double EstimateSparseRcond(const ComplexSparse& A, Eigen::SparseLU<ComplexSparse>& lu) {
  const Eigen::Index n = A.cols();
  if (n == 0) return 1.0;
  double norm_a = 0.0;
  for (Eigen::Index c = 0; c < A.outerSize(); ++c) {
    double sum = 0.0;
    for (ComplexSparse::InnerIterator it(A, c); it; ++it) sum += std::abs(it.value());
    norm_a = std::max(norm_a, sum);
  }
  VectorXc x = VectorXc::Constant(n, Complex(1.0 / static_cast<double>(n), 0.0));
  double est = 0.0;
  for (int iter = 0; iter < 5; ++iter) {
    const VectorXc y = lu.solve(x);
    if (!y.allFinite()) return 0.0;
    const double norm_y = y.cwiseAbs().sum();
    if (iter > 0 && norm_y <= est) break;
    est = norm_y;
    VectorXc xi(n);
    for (Eigen::Index i = 0; i < n; ++i) {
      const double a = std::abs(y(i));
      xi(i) = a > 0.0 ? y(i) / a : Complex(1.0, 0.0);
    }
    const VectorXc z = lu.adjoint().solve(xi);
    Eigen::Index j = 0;
    const double zmax = z.cwiseAbs().maxCoeff(&j);
    if (iter > 0 && zmax <= z.dot(x).real()) break;
    x = VectorXc::Unit(n, j);
  }
  return norm_a > 0.0 && est > 0.0 ? 1.0 / (norm_a * est) : 0.0;
}

}  // namespace internal

using internal::EstimateSparseRcond;

HbSetup& HarmonicBalanceSolver::Impl::Setup(int H) {
  auto it = setups.find(H);
  if (it != setups.end()) return *it->second;
  auto s = std::make_unique<HbSetup>();
  const int n = model.num_dofs();
  const std::int64_t q64 = ClassModulus();
  GEARDYN_THROW_UNLESS(
      (2 * static_cast<std::int64_t>(H) + 2) * q64 < std::numeric_limits<int>::max(),
      "harmonic balance: H = " << H << " mesh orders over a period of " << q64
                               << " operator periods exceed the index range");
  s->H = H;
  s->n = n;
  s->q = static_cast<int>(q64);
  const int q = s->q;
  s->dense = model.storage_hint() == StorageKind::kDense;
  s->sparse = UseSparse(H);
  const auto& meshes = model.meshes();
  const int num_meshes = static_cast<int>(meshes.size());
  const int reach = H * q + q / 2;
  // Kept one-sided harmonics of the classes: jq ± c, j = 0 … H (the mesh orders and their
  // sidebands).
  const auto kept_of = [H, q](const std::vector<int>& classes) {
    std::vector<int> ks;
    for (int c : classes) {
      for (int j = 0; j <= H; ++j) {
        ks.push_back(j * q + c);
        if (c > 0 && j >= 1) ks.push_back(j * q - c);
      }
    }
    std::sort(ks.begin(), ks.end());
    ks.erase(std::unique(ks.begin(), ks.end()), ks.end());
    return ks;
  };
  s->op_stiffness.assign(num_meshes, {});
  s->op_damping.assign(num_meshes, {});
  s->load.assign(num_meshes, {});
  s->eps.assign(num_meshes, {});
  if (!s->sparse) {
    const std::vector<MeshHarmonics> mh = ExpandMeshHarmonics(model, (2 * H + 1) * q);
    // Classes of the forcing: c = k mod q folded to [0, q/2]; a class is solved when some load
    // harmonic k ≤ Hq + q/2 in it exceeds kForcingTol of the largest (0 always: the mean).
    std::vector<double> class_size(q / 2 + 1, 0.0);
    double largest = 0.0;
    for (int k = 0; k < num_meshes; ++k) {
      for (int m = 0; m <= reach; ++m) {
        const double a = mh[k].load[m].cwiseAbs().maxCoeff();
        const int c = m % q;
        class_size[std::min(c, q - c)] = std::max(class_size[std::min(c, q - c)], a);
        largest = std::max(largest, a);
      }
    }
    s->classes.push_back(0);
    for (int c = 1; c <= q / 2; ++c) {
      if (class_size[c] > kForcingTol * largest) s->classes.push_back(c);
    }
    s->ks = kept_of(s->classes);
    for (int k = 0; k < num_meshes; ++k) {
      for (int j = 0; j <= 2 * H + 1; ++j) {
        s->op_stiffness[k].push_back(mh[k].stiffness[static_cast<size_t>(j) * q]);
        s->op_damping[k].push_back(mh[k].damping[static_cast<size_t>(j) * q]);
      }
      for (int kk : s->ks) s->load[k].push_back(mh[k].load[kk]);
    }
  } else {
    std::string why;
    GEARDYN_THROW_UNLESS(
        EstimateSparseBytes(H, &why) <= kMaxHbBytes,
        "harmonic balance: sparse harmonics need "
            << (why.empty() ? "more than " + FormatG(kMaxHbBytes / 1e9) + " GB" : why));
    // Candidate classes (the lines the loads can reach), then the same size test as the dense
    // path on their kept harmonics.
    const std::vector<int> candidates = CandidateClasses();
    const std::vector<int> all = kept_of(candidates);
    const std::vector<std::int64_t> all64(all.begin(), all.end());
    const std::vector<SparseMeshHarmonics> sh =
        ExpandMeshHarmonicsSparse(model, OperatorPeriodMeshes(model), 2 * H + 1, all64);
    std::vector<double> class_size(candidates.size(), 0.0);
    double largest = 0.0;
    for (int k = 0; k < num_meshes; ++k) {
      for (size_t i = 0; i < all.size(); ++i) {
        const double a = sh[k].load[i].cwiseAbs().maxCoeff();
        const int c = all[i] % q;
        const auto ci = static_cast<size_t>(
            std::lower_bound(candidates.begin(), candidates.end(), std::min(c, q - c)) -
            candidates.begin());
        class_size[ci] = std::max(class_size[ci], a);
        largest = std::max(largest, a);
      }
    }
    s->classes.push_back(0);
    for (size_t ci = 1; ci < candidates.size(); ++ci) {
      if (class_size[ci] > kForcingTol * largest) s->classes.push_back(candidates[ci]);
    }
    s->ks = kept_of(s->classes);
    for (int k = 0; k < num_meshes; ++k) {
      s->op_stiffness[k] = sh[k].stiffness;
      s->op_damping[k] = sh[k].damping;
      for (int kk : s->ks) {
        const auto i =
            static_cast<size_t>(std::lower_bound(all.begin(), all.end(), kk) - all.begin());
        s->load[k].push_back(sh[k].load[i]);
        s->eps[k].push_back(sh[k].transmission_error[i]);
      }
    }
  }
  s->kmax = s->ks.back();
  const std::vector<int>& ks = s->ks;

  // Mean K̄, C̄ from the m = 0 harmonics (real) plus the constant parts.
  std::vector<Eigen::Triplet<double>> tk, tc;
  for (size_t k = 0; k < meshes.size(); ++k) {
    ScatterMesh(meshes[k], s->op_stiffness[k][0].real(), &tk);
    ScatterMesh(meshes[k], s->op_damping[k][0].real(), &tc);
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

  // Forcing F_k = δ_k0 f0 + Σ Gᵀ (K2 ε)_k at the kept harmonics.
  s->F.assign(ks.size(), VectorXc::Zero(n));
  s->F[0] = model.constant_load().cast<Complex>();
  for (size_t k = 0; k < meshes.size(); ++k) {
    const SystemMesh& mesh = meshes[k];
    const Eigen::Matrix<Complex, 12, 2> Gt = mesh.G.transpose().cast<Complex>();
    for (size_t i = 0; i < ks.size(); ++i) {
      const Eigen::Matrix<Complex, 12, 1> f = Gt * s->load[k][i];
      for (int a = 0; a < 12; ++a) {
        if (mesh.dofs[a] >= 0) s->F[i](mesh.dofs[a]) += f(a);
      }
    }
  }
  // Harmonic loads Re(F e^{ilθ}): F/2 at the kept harmonic l·P (class 0, kept when l·P_K ≤ H).
  for (const SystemHarmonicLoad& h : model.harmonic_loads()) {
    const std::int64_t kk = static_cast<std::int64_t>(h.order) * model.period_meshes();
    const auto at = std::lower_bound(ks.begin(), ks.end(), kk);
    if (at == ks.end() || *at != kk) continue;
    const auto i = static_cast<size_t>(at - ks.begin());
    for (int a = 0; a < kBodyDofs; ++a) {
      if (h.dofs[a] >= 0) s->F[i](h.dofs[a]) += 0.5 * h.amplitude(a);
    }
  }
  s->unbalanced = internal::BalanceMeanLoad(rigid, &s->F[0]);

  // Channels whose K2 or C2 varies with θ (the rank of the LTV part); only harmonics jq exist.
  std::vector<std::pair<int, int>> channels;  // (mesh, row of G)
  for (size_t k = 0; k < meshes.size(); ++k) {
    const std::vector<Matrix2c>& ks2 = s->op_stiffness[k];
    const std::vector<Matrix2c>& cs2 = s->op_damping[k];
    double scale_k = ks2[0].cwiseAbs().maxCoeff();
    double scale_c = cs2[0].cwiseAbs().maxCoeff();
    for (int c = 0; c < 2; ++c) {
      bool varies = false;
      // Only the harmonics jq of the operator exist (K, C repeat every P_K meshes).
      for (int j = 1; j <= 2 * H + 1 && !varies; ++j) {
        varies = ks2[j].row(c).cwiseAbs().maxCoeff() > kVaryingTol * scale_k ||
                 cs2[j].row(c).cwiseAbs().maxCoeff() > kVaryingTol * scale_c;
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
  s->dK.assign(2 * H + 2, MatrixXc::Zero(s->r, s->r));
  s->dC.assign(2 * H + 2, MatrixXc::Zero(s->r, s->r));
  for (int j = 1; j <= 2 * H + 1; ++j) {
    for (int a = 0; a < s->r; ++a) {
      for (int b = 0; b < s->r; ++b) {
        if (channels[a].first != channels[b].first) continue;  // meshes do not couple
        const int mesh = channels[a].first;
        s->dK[j](a, b) = s->op_stiffness[mesh][j](channels[a].second, channels[b].second);
        s->dC[j](a, b) = s->op_damping[mesh][j](channels[a].second, channels[b].second);
      }
    }
  }
  GEARDYN_THROW_UNLESS(options.time_samples == 0 || options.time_samples > 2 * s->kmax,
                       "HbOptions::time_samples: must exceed 2 k_max = "
                           << 2 * s->kmax << " (the highest kept harmonic of the period, H = " << H
                           << " mesh orders with their sidebands), got " << options.time_samples);
  if (s->sparse) {
    // One operator period of the class envelopes: time_samples/q when given, else what the
    // dense sampler takes for q = 1 (ChooseTimeSamples: a power of two ≥ max(256, 8(H+1))).
    const int per_period = options.time_samples > 0
                               ? std::max((options.time_samples + q - 1) / q, 2 * H + 4)
                               : internal::ChooseTimeSamples(H, 0, 1);
    s->class_sampler = std::make_unique<internal::HbClassSampler>(model, s->q, s->ks, s->classes,
                                                                  s->eps, per_period);
  } else {
    s->sampler = std::make_unique<internal::HbOutputSampler>(
        model, s->kmax, internal::ChooseTimeSamples(s->kmax, options.time_samples, s->q));
  }
  if (!undamped.checked) FindUndampedModes(*s);
  HbSetup& ref = *s;
  setups.emplace(H, std::move(s));
  return ref;
}

MatrixXc HarmonicBalanceSolver::Impl::SolveDecoupledOrCondensed(HbSetup& s, double omega,
                                                                bool condensed, double* rcond,
                                                                long* factorizations) {
  const int n = s.n, q = s.q, H = s.H;
  const int r = condensed ? s.r : 0;
  const int num = static_cast<int>(s.ks.size());
  std::vector<MatrixXc> Y(num);  // n × (1 + r): A_k⁻¹ [F_k, G_allᵀ]
  MatrixXc rhs(n, 1 + r);
  *rcond = 1.0;
  for (int i = 0; i < num; ++i) {
    const int k = s.ks[i];
    const double kw = k * omega;
    rhs.col(0) = s.F[i];
    if (r > 0) rhs.rightCols(r) = s.Gt_d.cast<Complex>();
    if (s.dense) {
      MatrixXc A = (k == 0 ? s.Kbar0_d : s.Kbar_d).cast<Complex>();
      A += Complex(-kw * kw, 0.0) * s.M_d.cast<Complex>();
      A += Complex(0.0, kw) * s.Cbar_d.cast<Complex>();
      s.dense_lu.compute(A);
      *rcond = std::min(*rcond, s.dense_lu.rcond());
      Y[i] = s.dense_lu.solve(rhs);
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
        return MatrixXc::Constant(n, num, Complex(NAN, NAN));
      }
      *rcond = std::min(*rcond, EstimateSparseRcond(A, s.sparse_lu));
      Y[i] = s.sparse_lu.solve(rhs);
    }
    ++*factorizations;
  }
  MatrixXc Q = MatrixXc::Zero(n, num);  // column i: Q_{ks[i]}
  if (r == 0) {
    for (int i = 0; i < num; ++i) Q.col(i) = Y[i].col(0);
    return Q;
  }
  // Y_k for k < 0 by conjugation (A_{−k} = conj A_k, F_{−k} = conj F_k, G real).
  const auto y_at = [&](int k) -> MatrixXc {
    const MatrixXc& y = Y[static_cast<size_t>(s.Pos(std::abs(k)))];
    return k >= 0 ? y : MatrixXc(y.conjugate());
  };
  // Toeplitz block T_{k,j} = ΔK_{k−j} + i jΩ ΔC_{k−j}.
  const auto T = [&](int k, int j) -> MatrixXc {
    return s.DeltaAt(s.dK, k - j) + Complex(0.0, j * omega) * s.DeltaAt(s.dC, k - j);
  };
  const MatrixXc Gc = s.G.cast<Complex>();
  for (int c : s.classes) {
    if (c == 0) {
      // Real layout over k = jq, j = 0 … H (Q_{−k} = conj Q_k), as for P = 1 with stride q.
      const int size = r * (2 * H + 1);
      MatrixX A = MatrixX::Identity(size, size);
      std::vector<VectorXc> d0(H + 1);
      std::vector<MatrixXc> R(H + 1);
      for (int j = 0; j <= H; ++j) {
        const MatrixXc y = y_at(j * q);
        R[j] = Gc * y.rightCols(r);
        d0[j] = Gc * y.col(0);
      }
      for (int k = 0; k <= H; ++k) {
        for (int j = std::max(-H, k - 2 * H); j <= H; ++j) {
          internal::AddRealBlock(r, k, j, R[k] * T(k * q, j * q), &A);
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
          td += T(k * q, j * q) * dj;
        }
        const MatrixXc y = y_at(k * q);
        Q.col(s.Pos(k * q)) = y.col(0) - y.rightCols(r) * td;
      }
      continue;
    }
    // Two-sided window k = c + jq, |k| ≤ Hq + c: j = −H … H (and j = −H−1 when c = q/2).
    std::vector<int> window;
    for (int j = -H - 1; j <= H; ++j) {
      const int k = c + j * q;
      if (std::abs(k) <= H * q + c) window.push_back(k);
    }
    const int w = static_cast<int>(window.size());
    MatrixXc A = MatrixXc::Identity(r * w, r * w);
    VectorXc d0(r * w);
    std::vector<MatrixXc> ys(w);
    for (int a = 0; a < w; ++a) {
      ys[a] = y_at(window[a]);
      const MatrixXc R = Gc * ys[a].rightCols(r);
      d0.segment(a * r, r) = Gc * ys[a].col(0);
      for (int b = 0; b < w; ++b) {
        A.block(a * r, b * r, r, r) += R * T(window[a], window[b]);
      }
    }
    Eigen::PartialPivLU<MatrixXc> lu(A);
    *rcond = std::min(*rcond, lu.rcond());
    ++*factorizations;
    const VectorXc D = lu.solve(d0);
    for (int a = 0; a < w; ++a) {
      VectorXc td = VectorXc::Zero(r);
      for (int b = 0; b < w; ++b) td += T(window[a], window[b]) * D.segment(b * r, r);
      const VectorXc qk = ys[a].col(0) - ys[a].rightCols(r) * td;
      if (window[a] >= 0) {
        Q.col(s.Pos(window[a])) = qk;
      } else {
        Q.col(s.Pos(-window[a])) = qk.conjugate();  // Q_{−k} = conj Q_k (class q − c)
      }
    }
  }
  return Q;
}

MatrixXc HarmonicBalanceSolver::Impl::SolveDirect(HbSetup& s, double omega, double* rcond) {
  // Every harmonic 0 … kmax of Ω (a superset of the kept ones: same answer up to truncation).
  const LinearHbSystem sys = MakeLinearHbSystem(
      model, s.kmax, omega * static_cast<double>(model.period_meshes()) / (2.0 * std::numbers::pi));
  Eigen::PartialPivLU<MatrixX> lu(sys.matrix);
  *rcond = lu.rcond();
  const MatrixXc all = internal::FromRealLayout(lu.solve(sys.rhs), s.n, s.kmax);
  MatrixXc Q(s.n, static_cast<Eigen::Index>(s.ks.size()));
  for (size_t i = 0; i < s.ks.size(); ++i) Q.col(static_cast<Eigen::Index>(i)) = all.col(s.ks[i]);
  return Q;
}

HbResult HarmonicBalanceSolver::Impl::SolveFixed(int H, double f_m) {
  HbSetup& s = Setup(H);
  HbResult result;
  result.mesh_frequency_hz = f_m;
  result.period_meshes = model.period_meshes();
  result.harmonics = H;
  result.highest_harmonic = s.kmax;
  result.kept_harmonics = s.ks;
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
    GEARDYN_THROW_UNLESS(!s.sparse,
                         "HbOptions::method: 'direct' solves every harmonic up to k_max = "
                             << s.kmax << "; not with sparse harmonics (use condensed)");
    Q = SolveDirect(s, omega, &rcond);
    factorizations = 1;
    result.summary.counters["unknowns"] = static_cast<long>(s.n) * (2 * s.kmax + 1);
  } else {
    Q = SolveDecoupledOrCondensed(s, omega, method == HbMethod::kCondensed, &rcond,
                                  &factorizations);
    result.summary.counters["condensed_unknowns"] =
        method == HbMethod::kCondensed ? static_cast<long>(s.r) * (2 * H + 1) : 0L;
  }
  result.summary.counters["factorizations"] = factorizations;
  result.summary.counters["harmonics"] = H;
  result.summary.counters["kept_harmonics"] = static_cast<long>(s.ks.size());
  result.summary.counters["forcing_classes"] = static_cast<long>(s.classes.size());
  result.summary.counters["sparse_harmonics"] = s.sparse ? 1L : 0L;
  result.summary.counters["rigid_body_modes"] = rigid.count();  // rigid_modes.hpp criterion
  result.summary.warnings = warnings;
  if (!undamped.note.empty()) result.summary.warnings.push_back(undamped.note);
  if (s.unbalanced > 1e-8) {
    result.summary.warnings.push_back(
        "the mean load has a part along the rigid-body modes (relative size " +
        std::to_string(s.unbalanced) + "); removed (the supports cannot react it)");
  }
  result.reciprocal_condition = rcond;
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
        FormatG(rcond) + "): an undamped resonance at " + std::to_string(f_m) + " Hz?";
  } else if (rcond < kWarnRcond) {
    result.summary.warnings.push_back(PointWarningPrefix(f_m) + kIllConditionedText +
                                      FormatG(rcond) + "): expect to lose about " +
                                      FormatG(std::round(-std::log10(rcond))) + " digits");
  }
  result.sparse_harmonics = s.sparse;
  double max_rms = 0.0;
  if (s.sparse) {
    max_rms = s.class_sampler->Evaluate(Q, omega, options.compute_forces, options.keep_harmonics,
                                        &result);
  } else {
    MatrixXc full = MatrixXc::Zero(s.n, s.kmax + 1);  // column k: Q_k
    for (size_t i = 0; i < s.ks.size(); ++i)
      full.col(s.ks[i]) = Q.col(static_cast<Eigen::Index>(i));
    max_rms =
        s.sampler->Evaluate(full, omega, options.compute_forces, options.keep_harmonics, &result);
  }
  // Fixed-H estimate: RMS of the DTE harmonics above 3/4 of the kept mesh orders, relative to
  // the largest RMS DTE.
  double top = 0.0;
  const int first = (3 * H / 4) * s.q + 1;
  for (const HbMeshOutput& m : result.meshes) {
    double e2 = 0.0;
    if (s.sparse) {  // amplitudes at the kept harmonics
      for (size_t i = 0; i < s.ks.size(); ++i) {
        const double a = m.dte_amplitudes(static_cast<Eigen::Index>(i));
        if (s.ks[i] >= first) e2 += 0.5 * a * a;
      }
    } else {
      for (int h = first; h <= s.kmax && h < m.dte_amplitudes.size(); ++h) {
        e2 += 0.5 * m.dte_amplitudes(h) * m.dte_amplitudes(h);
      }
    }
    top = std::max(top, std::sqrt(e2));
  }
  result.summary.error_estimate = max_rms > 0.0 ? top / max_rms : 0.0;
  CheckUndampedShare(s, Q, f_m, &result.summary);
  return result;
}

HarmonicBalanceSolver::HarmonicBalanceSolver(const SystemModel& model, const HbOptions& options)
    : impl_(std::make_unique<Impl>()) {
  std::string why;
  GEARDYN_THROW_UNLESS(options.IsValid(&why), why);
  impl_->model = model;
  impl_->options = options;
  impl_->warnings = internal::CheckLinearHbModel(model);
  const int first = options.harmonics > 0 ? options.harmonics : options.min_harmonics;
  std::string sparse_why;
  const double sparse_bytes = impl_->EstimateSparseBytes(first, &sparse_why);
  GEARDYN_THROW_UNLESS(
      options.harmonic_storage != HbHarmonicStorage::kSparse || sparse_bytes <= kMaxHbBytes,
      "HbOptions::harmonic_storage: sparse harmonics not possible for H = "
          << first << ": "
          << (sparse_why.empty() ? "would need about " + FormatG(sparse_bytes / 1e9) + " GB"
                                 : sparse_why));
  const double bytes = impl_->UseSparse(first) ? sparse_bytes : impl_->EstimateBytes(first);
  GEARDYN_THROW_UNLESS(
      bytes <= kMaxHbBytes,
      "HbOptions::harmonics: H = "
          << first << " over a period of " << model.period_meshes() << " mesh cycles (P/P_K = "
          << impl_->ClassModulus() << " sidebands per mesh order) would need about "
          << FormatG(bytes / 1e9) << " GB (limit " << FormatG(kMaxHbBytes / 1e9) << " GB)"
          << (sparse_why.empty()
                  ? std::string()
                  : "; sparse harmonics (a runout's sidebands) not possible: " + sparse_why)
          << "; lower H, or remove the tooth errors that make the hunting period");
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
        result.summary.message = "harmonic balance: tolerance " + FormatG(o.tolerance) +
                                 " not met with max_harmonics = " + std::to_string(H);
        break;
      }
      std::string why_next;
      const double next_bytes = impl_->UseSparse(next) ? impl_->EstimateSparseBytes(next, &why_next)
                                                       : impl_->EstimateBytes(next);
      if (next_bytes > kMaxHbBytes) {
        result.summary.status = Status::kToleranceNotMet;
        result.summary.message = "harmonic balance: tolerance " + FormatG(o.tolerance) +
                                 " not met with H = " + std::to_string(H) +
                                 "; H = " + std::to_string(next) + " would need about " +
                                 FormatG(next_bytes / 1e9) + " GB";
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
    if (options.cancel != nullptr && options.cancel->load()) {
      sweep.summary.status = Status::kInterrupted;
      sweep.summary.message = "interrupted after " + std::to_string(i) + " of " +
                              std::to_string(total) + " mesh frequencies";
      break;
    }
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
  // Every distinct warning of the points once, with the frequency range of per-point ones.
  sweep.summary.warnings = MergePointWarnings(sweep.points);
  sweep.summary.counters["points"] = static_cast<long>(sweep.points.size());
  sweep.summary.wall_time_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return sweep;
}

}  // namespace geardyn
