// PreparedFloquet: the frequency-independent part of ComputeFloquet(model) built once, A(θ) as a
// verified Fourier series in the phase (prepared_floquet.hpp).
#include "geardyn/analyses/prepared_floquet.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include "floquet/floquet_internal.hpp"
#include "geardyn/common/check.hpp"
#include "geardyn/common/errors.hpp"
#include "geardyn/system/common_period.hpp"

namespace geardyn {

struct PreparedFloquet::Impl {
  internal::StateSystem state;   ///< at ω_m = 1 rad/s (t = θ); evaluate empty
  double period_phase = 0.0;     ///< 2π·P_K [rad]
  double operator_period = 1.0;  ///< P_K [-]
  MatrixX constant;              ///< A₀ (dim × dim)
  std::vector<MatrixX> cosine;   ///< A_m^c, m = 1 … M: the lower f rows (f × dim)
  std::vector<MatrixX> sine;     ///< A_m^s, likewise

  // A(θ) = A₀ + Σ_m (A_m^c cos mφ + A_m^s sin mφ), φ = θ/P_K (only the lower rows vary).
  void Evaluate(double theta, MatrixX* A) const {
    *A = constant;
    const Eigen::Index f = constant.rows() / 2;
    const double phi = theta / operator_period;
    for (std::size_t k = 0; k < cosine.size(); ++k) {
      const double x = static_cast<double>(k + 1) * phi;
      A->bottomRows(f) += std::cos(x) * cosine[k] + std::sin(x) * sine[k];
    }
  }
};

namespace {

constexpr int kFitSamples = 64;             // S: harmonics up to S/2 − 1 are represented
constexpr double kDroppedHarmonic = 1e-13;  // relative to max|A_ij|: a zero harmonic

double MaxAbs(const MatrixX& A) { return A.size() == 0 ? 0.0 : A.cwiseAbs().maxCoeff(); }

}  // namespace

std::shared_ptr<const PreparedFloquet::Impl> PreparedFloquet::Prepare(const SystemModel& model,
                                                                      const FloquetOptions& options,
                                                                      double* fit_error) {
  const std::optional<FloquetMethod> method = internal::FrequencyIndependentMethod(model, options);
  if (!method || *method != FloquetMethod::kMagnus) return nullptr;

  // The ordinary system at ω_m = 1 rad/s: t = θ, T = 2π·P_K.
  constexpr double kUnitOmega = 1.0;
  const PeriodicSecondOrderSystem system =
      internal::MakeModelSystem(model, kUnitOmega, FloquetMethod::kMagnus, 0, MatrixX());
  if (!system.steps.empty() || !system.coefficients) return nullptr;  // durations scale with 1/ω
  auto impl = std::make_shared<Impl>();
  try {
    impl->state = internal::MakeStateSystem(system, options.deflate_rigid_modes);
  } catch (const InvalidInput&) {
    return nullptr;
  }
  internal::StateSystem& state = impl->state;
  const double T = state.period_s;
  // ω_s = 2π/T only without any stiffness: then it depends on the frequency.
  if (state.dim == 0 || !state.evaluate || state.omega_s == 2.0 * std::numbers::pi / T) {
    return nullptr;
  }
  impl->period_phase = T;
  impl->operator_period = static_cast<double>(internal::FloquetPeriodMeshes(model));

  // DFT of S samples θ_j = T j/S (φ_j = 2π j/S).
  const int dim = state.dim, f = dim / 2;
  std::vector<MatrixX> samples(kFitSamples);
  double scale = 0.0;
  for (int j = 0; j < kFitSamples; ++j) {
    state.evaluate(T * j / kFitSamples, &samples[j]);
    scale = internal::MaxPropagatingNaN(scale, MaxAbs(samples[j]));
  }
  if (!(scale > 0.0) || !std::isfinite(scale)) return nullptr;
  impl->constant = MatrixX::Zero(dim, dim);
  for (const MatrixX& A : samples) impl->constant += A;
  impl->constant /= kFitSamples;
  impl->constant.topRows(f) = samples[0].topRows(f);  // [0, ω_s I]: constant by construction
  int highest = 0;
  std::vector<MatrixX> cosine, sine;
  for (int m = 1; m < kFitSamples / 2; ++m) {
    MatrixX c = MatrixX::Zero(f, dim), s = MatrixX::Zero(f, dim);
    for (int j = 0; j < kFitSamples; ++j) {
      const double x = 2.0 * std::numbers::pi * m * j / kFitSamples;
      c += std::cos(x) * samples[j].bottomRows(f);
      s += std::sin(x) * samples[j].bottomRows(f);
    }
    c *= 2.0 / kFitSamples;
    s *= 2.0 / kFitSamples;
    if (std::max(MaxAbs(c), MaxAbs(s)) > kDroppedHarmonic * scale) highest = m;
    cosine.push_back(std::move(c));
    sine.push_back(std::move(s));
  }
  cosine.resize(highest);
  sine.resize(highest);
  impl->cosine = std::move(cosine);
  impl->sine = std::move(sine);

  // The check: the series against the ordinary A(θ) at the S midpoints.
  double error = 0.0;
  MatrixX direct, series;
  for (int j = 0; j < kFitSamples; ++j) {
    const double theta = T * (j + 0.5) / kFitSamples;
    state.evaluate(theta, &direct);
    impl->Evaluate(theta, &series);
    error = internal::MaxPropagatingNaN(error, MaxAbs(series - direct));
  }
  *fit_error = internal::MaxPropagatingNaN(*fit_error, error / scale);
  if (!(error / scale <= kPreparedFitTolerance)) return nullptr;
  state.evaluate = nullptr;  // releases the model assembler; Compute sets its own
  return impl;
}

PreparedFloquet::PreparedFloquet(std::shared_ptr<const SystemModel> model,
                                 const FloquetOptions& options)
    : model_(std::move(model)), options_(options), fit_error_(0.0) {
  GEARDYN_THROW_UNLESS(model_ != nullptr, "PreparedFloquet: model is null");
  FloquetOptions checked = options;
  checked.mesh_frequency_hz = 1.0;  // the frequency is given per call
  try {
    internal::CheckFloquetModel(*model_, checked);
  } catch (const InvalidInput&) {
    fit_error_ = std::numeric_limits<double>::quiet_NaN();
    return;  // Compute calls ComputeFloquet, which throws the same
  }
  // The blocks ComputeFloquet analyses (the whole model when it does not split).
  // As ComputeFloquet: no block split with several mesh frequencies (the blocks share one period).
  const int num_blocks =
      options.split_blocks && !HasSeveralMeshFrequencies(*model_) ? model_->num_blocks() : 1;
  bool any = false;
  for (int b = 0; b < std::max(1, num_blocks); ++b) {
    Block block;
    block.model =
        num_blocks <= 1 ? model_ : std::make_shared<const SystemModel>(model_->RestrictToBlock(b));
    block.impl = Prepare(*block.model, options, &fit_error_);
    any = any || block.impl != nullptr;
    blocks_.push_back(std::move(block));
  }
  if (!any) {
    blocks_.clear();
    fit_error_ = std::numeric_limits<double>::quiet_NaN();
  }
}

int PreparedFloquet::harmonics() const {
  int m = -1;
  for (const Block& b : blocks_) {
    if (b.impl) m = std::max(m, static_cast<int>(b.impl->cosine.size()));
  }
  return m;
}

FloquetResult PreparedFloquet::Solve(const Block& block, const FloquetOptions& options) {
  if (!block.impl) return internal::ComputeModelFloquet(*block.model, options);
  // As MakeModelSystem and MakeStateSystem at ω_m: T = 2π P_K/ω_m, kinks at θ_k/ω_m.
  const double omega = 2.0 * std::numbers::pi * options.mesh_frequency_hz;
  internal::StateSystem sys = block.impl->state;
  sys.period_s = block.impl->period_phase / omega;
  for (double& t : sys.kinks) t /= omega;
  sys.evaluate = [impl = block.impl, omega](double t, MatrixX* A) { impl->Evaluate(omega * t, A); };
  sys.analytic = sys.kinks.empty();  // A(θ) is the verified Fourier series: entire in t
  return internal::ComputeFloquetState(sys, options, FloquetMethod::kMagnus);
}

FloquetResult PreparedFloquet::Compute(const FloquetOptions& options) const {
  const bool same_structure =
      options.method == options_.method && options.split_blocks == options_.split_blocks &&
      options.deflate_rigid_modes == options_.deflate_rigid_modes &&
      options.num_modes == options_.num_modes &&
      options.modal_projection_min_dofs == options_.modal_projection_min_dofs;
  if (blocks_.empty() || !same_structure) return ComputeFloquet(*model_, options);
  // ComputeFloquet(model, options) with the prepared blocks (model_floquet.cpp).
  const auto start = std::chrono::steady_clock::now();
  const std::vector<std::string> warnings = internal::CheckFloquetModel(*model_, options);
  FloquetResult result;
  if (blocks_.size() == 1) {
    result = Solve(blocks_[0], options);
  } else {
    std::vector<FloquetResult> parts;
    for (const Block& b : blocks_) parts.push_back(Solve(b, options));
    result = internal::CombineBlockResults(*model_, options, parts);
  }
  internal::FinishModelFloquet(*model_, options, warnings, start, &result);
  return result;
}

}  // namespace geardyn
