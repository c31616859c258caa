// Time samples of the harmonic-balance response and the probe outputs (hb_internal.hpp):
// q(θ_s) = Σ_k Q_k e^{2πiks/S} by one batched FFTW c2r (n signals), likewise q̇ with ikΩ Q_k; the
// DTE harmonics by one batched r2c of the DTE samples.
#include <fftw3.h>

#include <algorithm>
#include <cmath>
#include <mutex>
#include <numbers>
#include <variant>

#include "geardyn/common/check.hpp"
#include "geardyn/numerics/fftw_planner.hpp"
#include "hb_internal.hpp"

namespace geardyn::internal {

struct HbOutputSampler::Fft {
  int n = 0, S = 0, meshes = 0;
  fftw_complex* spec = nullptr;  // (n × (S/2+1)) one-sided spectra, DOF-major
  double* samples = nullptr;     // (n × S) time samples, DOF-major
  fftw_complex* dte_spec = nullptr;
  double* dte_samples = nullptr;
  fftw_plan c2r = nullptr;
  fftw_plan r2c = nullptr;

  Fft(int n_, int S_, int meshes_) : n(n_), S(S_), meshes(meshes_) {
    const int half = S / 2 + 1;
    spec = fftw_alloc_complex(static_cast<size_t>(std::max(n, 1)) * half);
    samples = fftw_alloc_real(static_cast<size_t>(std::max(n, 1)) * S);
    dte_spec = fftw_alloc_complex(static_cast<size_t>(std::max(meshes, 1)) * half);
    dte_samples = fftw_alloc_real(static_cast<size_t>(std::max(meshes, 1)) * S);
    GEARDYN_DEMAND(spec && samples && dte_spec && dte_samples);
    int size[1] = {S};
    const std::lock_guard<std::mutex> lock(FftwPlannerMutex());
    c2r = fftw_plan_many_dft_c2r(1, size, std::max(n, 1), spec, nullptr, 1, half, samples, nullptr,
                                 1, S, FFTW_ESTIMATE);
    r2c = fftw_plan_many_dft_r2c(1, size, std::max(meshes, 1), dte_samples, nullptr, 1, S, dte_spec,
                                 nullptr, 1, half, FFTW_ESTIMATE);
    GEARDYN_DEMAND(c2r && r2c);
  }
  ~Fft() {
    {
      const std::lock_guard<std::mutex> lock(FftwPlannerMutex());
      fftw_destroy_plan(c2r);
      fftw_destroy_plan(r2c);
    }
    fftw_free(spec);
    fftw_free(samples);
    fftw_free(dte_spec);
    fftw_free(dte_samples);
  }
  // Synthesizes the n signals with one-sided spectra factor(k)·Q(:, k) into `samples`.
  template <class Factor>
  void Synthesize(const MatrixXc& Q, Factor factor) {
    const int half = S / 2 + 1;
    const int H = static_cast<int>(Q.cols()) - 1;
    for (int d = 0; d < n; ++d) {
      fftw_complex* row = spec + static_cast<size_t>(d) * half;
      for (int k = 0; k < half; ++k) {
        const Complex c = k <= H ? factor(k) * Q(d, k) : Complex(0.0, 0.0);
        row[k][0] = c.real();
        row[k][1] = k == 0 ? 0.0 : c.imag();  // q real: the mean is real
      }
    }
    fftw_execute_dft_c2r(c2r, spec, samples);
  }
};

HbOutputSampler::HbOutputSampler(const SystemModel& model, int harmonics, int time_samples)
    : model_(model),
      H_(harmonics),
      S_(time_samples),
      fft_(std::make_unique<Fft>(model.num_dofs(), time_samples, model.num_meshes())),
      probe_ws_(model),
      q_(model.num_dofs()),
      v_(model.num_dofs()),
      dte_(model.num_meshes(), time_samples),
      force_(model.num_meshes(), time_samples) {
  GEARDYN_DEMAND(S_ > 2 * H_);
  for (const SystemElement& e : model.elements()) {
    element_force_.emplace_back(static_cast<Eigen::Index>(e.dofs.size()));
  }
  const double period = 2.0 * std::numbers::pi * static_cast<double>(model.period_meshes());
  const int num_meshes = model.num_meshes();
  k2_.resize(num_meshes);
  c2_.resize(num_meshes);
  eps_.resize(num_meshes);
  for (int k = 0; k < num_meshes; ++k) {
    const SystemMesh& mesh = model.meshes()[k];
    const auto* core = std::get_if<LinearMeshCore>(&mesh.core);
    if (core == nullptr) continue;
    // K2, C2 repeat every `cycle` samples when S holds a whole number of stiffness periods
    // (ChooseTimeSamples): evaluated once per period, copied over the hunting period.
    const std::int64_t repeats = model.period_meshes() / PeriodMeshes(core->stiffness());
    const int cycle = S_ % repeats == 0 ? static_cast<int>(S_ / repeats) : S_;
    k2_[k].reserve(static_cast<size_t>(S_));
    c2_[k].reserve(static_cast<size_t>(S_));
    eps_[k].reserve(static_cast<size_t>(S_));
    for (int s = 0; s < S_; ++s) {
      const double phase = mesh.MeshPhase(period * s / S_);
      if (s < cycle) {
        k2_[k].push_back(EvalStiffnessCore(*core, phase));
        c2_[k].push_back(EvalDampingCore(*core, phase, mesh.damping_coefficient));
      } else {
        k2_[k].push_back(k2_[k][s % cycle]);
        c2_[k].push_back(c2_[k][s % cycle]);
      }
      eps_[k].push_back(EvalTransmissionError(*core, phase));
    }
  }
}

HbOutputSampler::~HbOutputSampler() = default;

double HbOutputSampler::Evaluate(const MatrixXc& Q, double omega, bool forces, bool keep,
                                 HbResult* result) {
  const int n = model_.num_dofs();
  const int num_meshes = model_.num_meshes();
  const int num_elements = static_cast<int>(model_.elements().size());
  const int S = S_;
  const double period = 2.0 * std::numbers::pi * static_cast<double>(model_.period_meshes());
  // q samples, then q̇ samples (ikΩ Q_k), kept side by side.
  fft_->Synthesize(Q, [](int) { return Complex(1.0, 0.0); });
  const Eigen::Map<const MatrixX> q_samples(fft_->samples, S, n);  // column d = DOF d over s
  q_all_ = q_samples;
  const MatrixX& q_all = q_all_;
  fft_->Synthesize(Q, [omega](int k) { return Complex(0.0, k * omega); });
  const Eigen::Map<const MatrixX> v_samples(fft_->samples, S, n);

  std::vector<Vector6> e_sum(num_elements, Vector6::Zero()), e_sq(num_elements, Vector6::Zero());
  for (int s = 0; s < S; ++s) {
    const double theta = period * s / S;
    q_ = q_all.row(s).transpose();
    v_ = v_samples.row(s).transpose();
    for (int k = 0; k < num_meshes; ++k) {
      if (k2_[k].empty()) {
        const MeshProbeValues p = EvalMeshProbe(model_, probe_ws_, MeshIndex(k), theta, q_, v_);
        dte_(k, s) = p.dte;
        force_(k, s) = p.force(0);
        continue;
      }
      // probes.hpp: DTE = δ_η − ε_η, F = K2 (δ − ε) + C2 δ̇ with δ = G q_pair.
      const SystemMesh& mesh = model_.meshes()[k];
      Vector2 delta = Vector2::Zero(), rate = Vector2::Zero();
      for (int a = 0; a < 12; ++a) {
        if (mesh.dofs[a] < 0) continue;
        delta += mesh.G.col(a) * q_(mesh.dofs[a]);
        rate += mesh.G.col(a) * v_(mesh.dofs[a]);
      }
      const Vector2 elastic = delta - eps_[k][s];
      dte_(k, s) = elastic(0);
      force_(k, s) = (k2_[k][s] * elastic + c2_[k][s] * rate)(0);
    }
    if (!forces) continue;
    for (int e = 0; e < num_elements; ++e) {
      CalcElementForce(model_, ElementIndex(e), q_, v_, element_force_[e]);
      const Vector6 f = element_force_[e].head<6>();
      e_sum[e] += f;
      e_sq[e] += f.cwiseProduct(f);
    }
  }

  // DTE harmonics: r2c of the samples, amplitude |c_0|/S and 2|c_k|/S.
  const int half = S / 2 + 1;
  Eigen::Map<MatrixX>(fft_->dte_samples, S, std::max(num_meshes, 1)).leftCols(num_meshes) =
      dte_.transpose();
  if (num_meshes > 0) fftw_execute(fft_->r2c);

  result->meshes.assign(num_meshes, HbMeshOutput{});
  double max_rms = 0.0;
  const auto stats = [S](const auto& row, double* mean, double* rms, double* pp) {
    *mean = row.sum() / S;
    *rms = std::sqrt(std::max(0.0, (row.array() - *mean).square().sum() / S));
    *pp = row.maxCoeff() - row.minCoeff();
  };
  for (int k = 0; k < num_meshes; ++k) {
    HbMeshOutput& m = result->meshes[k];
    m.name = model_.meshes()[k].name;
    stats(dte_.row(k), &m.mean_dte, &m.rms_dte, &m.peak_to_peak_dte);
    stats(force_.row(k), &m.mean_force, &m.rms_force, &m.peak_to_peak_force);
    m.dte_amplitudes.resize(H_ + 1);
    for (int h = 0; h <= H_ && h < half; ++h) {
      const fftw_complex& c = fft_->dte_spec[static_cast<size_t>(k) * half + h];
      m.dte_amplitudes(h) = (h == 0 ? 1.0 : 2.0) * std::hypot(c[0], c[1]) / S;
    }
    max_rms = std::max(max_rms, m.rms_dte);
  }
  result->elements.clear();
  if (forces) {
    for (int e = 0; e < num_elements; ++e) {
      HbElementOutput out;
      out.name = model_.elements()[e].name;
      out.mean_force = e_sum[e] / S;
      out.rms_force =
          (e_sq[e] / S - out.mean_force.cwiseProduct(out.mean_force)).cwiseMax(0.0).cwiseSqrt();
      result->elements.push_back(out);
    }
  }
  result->time_samples = S;
  if (keep) {
    result->response_harmonics = Q;
    result->dte_samples = dte_;
  }
  return max_rms;
}

}  // namespace geardyn::internal
