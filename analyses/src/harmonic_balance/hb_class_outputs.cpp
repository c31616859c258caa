// HbClassSampler: the linear HB's outputs from the class envelopes of a sparse-harmonics solve
// (harmonic_balance.hpp "Long hunting periods"), never from samples over the hunting period.
#include <algorithm>
#include <cmath>
#include <numbers>

#include "geardyn/common/check.hpp"
#include "geardyn/system/probes.hpp"
#include "hb_internal.hpp"

namespace geardyn::internal {

HbClassSampler::HbClassSampler(const SystemModel& model, int q, const std::vector<int>& ks,
                               const std::vector<int>& classes,
                               const std::vector<std::vector<Vector2c>>& eps, int samples)
    : model_(model), q_(q), ks_(ks), classes_(classes), eps_(eps), S_(samples) {
  const double period =
      2.0 * std::numbers::pi * static_cast<double>(model.period_meshes() / q);  // 2πP_K
  const int num_meshes = model.num_meshes();
  k2_.assign(num_meshes, {});
  c2_.assign(num_meshes, {});
  for (int k = 0; k < num_meshes; ++k) {
    const SystemMesh& mesh = model.meshes()[k];
    const auto* core = std::get_if<LinearMeshCore>(&mesh.core);
    GEARDYN_THROW_UNLESS(core != nullptr,
                         "harmonic balance: sparse harmonics need linear cores; "
                         "mesh '"
                             << mesh.name << "' is not one");
    for (int s = 0; s < S_; ++s) {
      const double phase = mesh.MeshPhase(period * s / S_);
      k2_[k].push_back(EvalStiffnessCore(*core, phase));
      c2_[k].push_back(EvalDampingCore(*core, phase, mesh.damping_coefficient));
    }
  }
}

double HbClassSampler::Evaluate(const MatrixXc& Q, double omega, bool forces, bool keep,
                                HbResult* result) const {
  const int n = model_.num_dofs();
  const int num_meshes = model_.num_meshes();
  const int num_elements = static_cast<int>(model_.elements().size());
  const int S = S_, q = q_;
  const auto pos = [&](int k) {
    const auto it = std::lower_bound(ks_.begin(), ks_.end(), k);
    GEARDYN_DEMAND(it != ks_.end() && *it == k);
    return static_cast<Eigen::Index>(it - ks_.begin());
  };
  // Per class: envelopes of DTE and mesh force (meshes × S), of the element forces, their
  // mean squares, and the DTE/force envelopes kept for the peak-to-peak window.
  const int num_classes = static_cast<int>(classes_.size());
  int H = 0;  // the largest kept mesh order: ks holds jq for j = 0 … H
  for (int k : ks_) {
    if (k % q == 0) H = k / q;
  }
  std::vector<MatrixXc> dte_env(num_classes), force_env(num_classes);
  VectorX dte_mean = VectorX::Zero(num_meshes), force_mean = VectorX::Zero(num_meshes);
  VectorX dte_sq = VectorX::Zero(num_meshes), force_sq = VectorX::Zero(num_meshes);
  std::vector<Vector6> e_mean(num_elements, Vector6::Zero()), e_sq(num_elements, Vector6::Zero());
  VectorX f_re(12), f_im(12);
  for (int ci = 0; ci < num_classes; ++ci) {
    const int c = classes_[ci];
    // Window k = c + jq, |k| ≤ Hq + c (as the solver's); Q_{−k} = conj Q_k.
    std::vector<int> window;
    for (int j = -H - 1; j <= H; ++j) {
      const int k = c + j * q;
      if (std::abs(k) <= H * q + c) window.push_back(k);
    }
    // E(θ_s) = Σ_k X_k e^{i(k−c)θ_s/P} = Σ_j X_{c+jq} e^{ijθ_s/P_K}, θ_s = 2πP_K s/S.
    MatrixXc env_q = MatrixXc::Zero(n, S), env_v = MatrixXc::Zero(n, S);
    MatrixXc env_e = MatrixXc::Zero(2 * num_meshes, S);
    for (int k : window) {
      const Eigen::Index i = pos(std::abs(k));
      const VectorXc qk = k >= 0 ? VectorXc(Q.col(i)) : VectorXc(Q.col(i).conjugate());
      const VectorXc vk = std::complex<double>(0.0, k * omega) * qk;
      VectorXc ek(2 * num_meshes);
      for (int m = 0; m < num_meshes; ++m) {
        const Vector2c e = eps_[m][static_cast<size_t>(i)];
        ek.segment<2>(2 * m) = k >= 0 ? e : Vector2c(e.conjugate());
      }
      const int j = (k - c) / q;
      for (int s = 0; s < S; ++s) {
        const double a =
            2.0 * std::numbers::pi * static_cast<double>((static_cast<long>(j) * s) % S) / S;
        const std::complex<double> z(std::cos(a), std::sin(a));
        env_q.col(s) += z * qk;
        env_v.col(s) += z * vk;
        env_e.col(s) += z * ek;
      }
    }
    const bool real_class = c == 0 || 2 * c == q;  // the window's sum is real by itself
    const double w = real_class ? 1.0 : 2.0;
    dte_env[ci].resize(num_meshes, S);
    force_env[ci].resize(num_meshes, S);
    for (int m = 0; m < num_meshes; ++m) {
      const SystemMesh& mesh = model_.meshes()[m];
      for (int s = 0; s < S; ++s) {
        Vector2c delta = Vector2c::Zero(), rate = Vector2c::Zero();
        for (int a = 0; a < 12; ++a) {
          if (mesh.dofs[a] < 0) continue;
          delta += mesh.G.col(a).cast<std::complex<double>>() * env_q(mesh.dofs[a], s);
          rate += mesh.G.col(a).cast<std::complex<double>>() * env_v(mesh.dofs[a], s);
        }
        // probes.hpp: DTE = δ_η − ε_η, F = K2 (δ − ε) + C2 δ̇ (K2, C2 of class 0: the class of
        // the product is that of δ).
        const Vector2c elastic = delta - env_e.col(s).segment<2>(2 * m);
        dte_env[ci](m, s) = elastic(0);
        force_env[ci](m, s) = (k2_[m][s].cast<std::complex<double>>() * elastic +
                               c2_[m][s].cast<std::complex<double>>() * rate)(0);
      }
      dte_sq(m) += w * dte_env[ci].row(m).cwiseAbs2().sum() / S;
      force_sq(m) += w * force_env[ci].row(m).cwiseAbs2().sum() / S;
      if (c == 0) {
        dte_mean(m) = dte_env[ci].row(m).real().sum() / S;
        force_mean(m) = force_env[ci].row(m).real().sum() / S;
      }
    }
    if (!forces) continue;
    VectorX qr(n), qi(n), vr(n), vi(n);
    for (int e = 0; e < num_elements; ++e) {
      const auto size = static_cast<Eigen::Index>(model_.elements()[e].dofs.size());
      f_re.resize(size);
      f_im.resize(size);
      for (int s = 0; s < S; ++s) {
        qr = env_q.col(s).real();
        qi = env_q.col(s).imag();
        vr = env_v.col(s).real();
        vi = env_v.col(s).imag();
        // f_e is linear in (q, q̇): f(E) = f(Re E) + i f(Im E).
        CalcElementForce(model_, ElementIndex(e), qr, vr, f_re);
        CalcElementForce(model_, ElementIndex(e), qi, vi, f_im);
        const Vector6 re = f_re.head<6>(), im = f_im.head<6>();
        e_sq[e] += w * (re.cwiseProduct(re) + im.cwiseProduct(im)) / S;
        if (c == 0) e_mean[e] += re / S;
      }
    }
  }

  // Peak-to-peak over a window of operator periods p spread over the hunting period: at
  // θ = 2πP_K p + θ_s, e^{icθ/P} = e^{2πi (cp mod q)/q} e^{icθ_s/P}.
  const int window = std::min(q, kHbPeakWindowPeriods);
  VectorX dte_lo = VectorX::Constant(num_meshes, INFINITY), dte_hi = -dte_lo;
  VectorX f_lo = dte_lo, f_hi = dte_hi;
  for (int i = 0; i < window; ++i) {
    const long p = static_cast<long>(i) * q / window;
    for (int s = 0; s < S; ++s) {
      for (int m = 0; m < num_meshes; ++m) {
        double y = 0.0, f = 0.0;
        for (int ci = 0; ci < num_classes; ++ci) {
          const int c = classes_[ci];
          const double a = 2.0 * std::numbers::pi *
                           (static_cast<double>((c * p) % q) + static_cast<double>(c) * s / S) / q;
          const std::complex<double> z(std::cos(a), std::sin(a));
          const double w = c == 0 || 2 * c == q ? 1.0 : 2.0;
          y += w * (z * dte_env[ci](m, s)).real();
          f += w * (z * force_env[ci](m, s)).real();
        }
        dte_lo(m) = std::min(dte_lo(m), y);
        dte_hi(m) = std::max(dte_hi(m), y);
        f_lo(m) = std::min(f_lo(m), f);
        f_hi(m) = std::max(f_hi(m), f);
      }
    }
  }

  result->meshes.assign(num_meshes, HbMeshOutput{});
  double max_rms = 0.0;
  for (int m = 0; m < num_meshes; ++m) {
    HbMeshOutput& out = result->meshes[m];
    const SystemMesh& mesh = model_.meshes()[m];
    out.name = mesh.name;
    out.mean_dte = dte_mean(m);
    out.rms_dte = std::sqrt(std::max(0.0, dte_sq(m) - dte_mean(m) * dte_mean(m)));
    out.peak_to_peak_dte = dte_hi(m) - dte_lo(m);
    out.mean_force = force_mean(m);
    out.rms_force = std::sqrt(std::max(0.0, force_sq(m) - force_mean(m) * force_mean(m)));
    out.peak_to_peak_force = f_hi(m) - f_lo(m);
    // Amplitudes at the kept harmonics: |Y_0|, 2|Y_k| with Y_k = (G Q_k)_η − ε_η,k (exact).
    out.dte_amplitudes.resize(static_cast<Eigen::Index>(ks_.size()));
    for (size_t i = 0; i < ks_.size(); ++i) {
      std::complex<double> y = -eps_[m][i](0);
      for (int a = 0; a < 12; ++a) {
        if (mesh.dofs[a] >= 0) y += mesh.G(0, a) * Q(mesh.dofs[a], static_cast<Eigen::Index>(i));
      }
      out.dte_amplitudes(static_cast<Eigen::Index>(i)) = (ks_[i] == 0 ? 1.0 : 2.0) * std::abs(y);
    }
    max_rms = std::max(max_rms, out.rms_dte);
  }
  result->elements.clear();
  if (forces) {
    for (int e = 0; e < num_elements; ++e) {
      HbElementOutput out;
      out.name = model_.elements()[e].name;
      out.mean_force = e_mean[e];
      out.rms_force = (e_sq[e] - e_mean[e].cwiseProduct(e_mean[e])).cwiseMax(0.0).cwiseSqrt();
      result->elements.push_back(out);
    }
  }
  result->time_samples = S;
  if (keep) result->response_harmonics = Q;
  return max_rms;
}

}  // namespace geardyn::internal
