/// @file
/// @brief θ-coefficients: validation, evaluation, means, Fourier conversion (FFTW for tables),
/// tolerance-driven truncation and classification.
#include "geardyn/system/coefficient.hpp"

#include <fftw3.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <memory>
#include <mutex>
#include <vector>

#include "geardyn/common/check.hpp"
#include "geardyn/common/overloaded.hpp"
#include "geardyn/common/units.hpp"
#include "geardyn/numerics/fftw_planner.hpp"

namespace geardyn {
namespace {

using Complex = std::complex<double>;

double PeriodOf(std::int64_t period_meshes) {
  return 2.0 * kPi * static_cast<double>(period_meshes);
}

void CheckPeriodMeshes(std::int64_t period_meshes) {
  GEARDYN_THROW_UNLESS(period_meshes >= 1,
                       "period_meshes: must be >= 1 (period 2*pi*P), got " << period_meshes);
}

template <typename Derived>
void CheckFinite(const Eigen::DenseBase<Derived>& m, const char* name) {
  for (Eigen::Index c = 0; c < m.cols(); ++c) {
    for (Eigen::Index r = 0; r < m.rows(); ++r) {
      const auto v = m(r, c);
      GEARDYN_THROW_UNLESS(std::isfinite(std::real(v)) && std::isfinite(std::imag(v)),
                           name << "(" << r << ", " << c << ") = " << v << " is not finite");
    }
  }
}

/// θ reduced to [0, T).
double Wrap(double theta, double period) {
  double t = std::fmod(theta, period);
  if (t < 0.0) t += period;
  if (t >= period) t = 0.0;  // t + T rounded up to T
  return t;
}

void CheckEvaluateArgs(int num_channels, double theta, const Eigen::Ref<VectorX>& out) {
  GEARDYN_CHECK_SIZE(out.size(), num_channels, "Evaluate: out");
  GEARDYN_THROW_UNLESS(std::isfinite(theta), "Evaluate: theta = " << theta << " is not finite");
}

double Sinc(double x) { return std::abs(x) < 1e-8 ? 1.0 - x * x / 6.0 : std::sin(x) / x; }

/// c_n (n ≥ 1) of a piecewise-constant coefficient, all channels, into `column`.
void PiecewiseHarmonic(const PiecewiseConstantCoefficient& pc, int n, Eigen::Ref<VectorXc> column) {
  const double p = static_cast<double>(pc.period_meshes());
  const double period = PeriodOf(pc.period_meshes());
  column.setZero();
  for (int k = 0; k < pc.num_intervals(); ++k) {
    const double a = pc.interval_begin(k);
    const double b = pc.interval_end(k);
    const double width = b - a;
    // (1/T) ∫_a^b e^{-inθ/P} dθ = (Δ/T) sinc(nΔ/(2P)) e^{-in(a+b)/(2P)}.
    const double weight = width / period * Sinc(n * width / (2.0 * p));
    const Complex factor = std::polar(weight, -n * (a + b) / (2.0 * p));
    column += factor * pc.values().col(k).cast<Complex>();
  }
}

/// (1/S) Σ_s f_s e^{-2πi n s/S} for n = 0..S/2, one row per channel (FFTW r2c).
MatrixXc TableDft(const MatrixX& samples) {
  const int s_count = static_cast<int>(samples.cols());
  const int half = s_count / 2 + 1;
  struct Buffers {
    double* in = nullptr;
    fftw_complex* out = nullptr;
    ~Buffers() {
      fftw_free(in);
      fftw_free(out);
    }
  } buf;
  buf.in = fftw_alloc_real(static_cast<size_t>(s_count));
  buf.out = fftw_alloc_complex(static_cast<size_t>(half));
  GEARDYN_DEMAND(buf.in != nullptr && buf.out != nullptr);
  fftw_plan plan;
  {
    std::lock_guard<std::mutex> lock(FftwPlannerMutex());
    plan = fftw_plan_dft_r2c_1d(s_count, buf.in, buf.out, FFTW_ESTIMATE);
  }
  GEARDYN_DEMAND(plan != nullptr);
  MatrixXc dft(samples.rows(), half);
  for (Eigen::Index c = 0; c < samples.rows(); ++c) {
    for (int s = 0; s < s_count; ++s) buf.in[s] = samples(c, s);
    fftw_execute(plan);
    for (int n = 0; n < half; ++n) {
      dft(c, n) = Complex(buf.out[n][0], buf.out[n][1]) / static_cast<double>(s_count);
    }
  }
  {
    std::lock_guard<std::mutex> lock(FftwPlannerMutex());
    fftw_destroy_plan(plan);
  }
  return dft;
}

/// Harmonics c_1..c_M of the trigonometric interpolant of a table (Nyquist term halved).
MatrixXc TableHarmonics(const TableCoefficient& table) {
  const int s_count = table.num_samples();
  const MatrixXc dft = TableDft(table.samples());
  const int m = s_count / 2;  // highest harmonic of the interpolant
  MatrixXc harmonics(table.num_channels(), m);
  for (int n = 1; n <= m; ++n) {
    harmonics.col(n - 1) = dft.col(n);
    if (2 * n == s_count) harmonics.col(n - 1) *= 0.5;  // cos(Sθ/2) split between ±S/2
  }
  return harmonics;
}

/// Smallest N ≤ max_terms meeting the tolerance for a finite series with the given harmonics.
FourierFit FitFiniteSeries(const VectorX& mean, const MatrixXc& harmonics,
                           std::int64_t period_meshes, double rel_tol, int max_terms) {
  const Eigen::Index channels = harmonics.rows();
  const int available = static_cast<int>(harmonics.cols());
  // tail(c, N) = Σ_{n>N} |c_n|², accumulated from the top (no cancellation).
  MatrixX tail(channels, available + 1);
  tail.col(available).setZero();
  for (int n = available; n >= 1; --n) {
    tail.col(n - 1) = tail.col(n) + harmonics.col(n - 1).cwiseAbs2();
  }
  auto error_at = [&](int n_terms) {
    double e = 0.0;
    for (Eigen::Index c = 0; c < channels; ++c) {
      if (tail(c, 0) > 0.0) e = std::max(e, std::sqrt(tail(c, n_terms) / tail(c, 0)));
    }
    return e;
  };
  const int limit = std::min(available, max_terms);
  int n_terms = 0;
  while (n_terms < limit && error_at(n_terms) > rel_tol) ++n_terms;
  const double error = error_at(n_terms);
  return FourierFit{FourierCoefficient(mean, harmonics.leftCols(n_terms), period_meshes), n_terms,
                    error, error <= rel_tol};
}

FourierFit FitPiecewise(const PiecewiseConstantCoefficient& pc, double rel_tol, int max_terms) {
  const int channels = pc.num_channels();
  const double period = PeriodOf(pc.period_meshes());
  VectorX mean = VectorX::Zero(channels);
  for (int k = 0; k < pc.num_intervals(); ++k) {
    mean += pc.values().col(k) * (pc.interval_width(k) / period);
  }
  // Variation energy (1/T)∫(f − m)² = Σ_k (v_k − m)² Δ_k/T: exact, no cancellation.
  VectorX variation = VectorX::Zero(channels);
  for (int k = 0; k < pc.num_intervals(); ++k) {
    variation += (pc.values().col(k) - mean).cwiseAbs2() * (pc.interval_width(k) / period);
  }
  // Parseval: variation = 2 Σ_{n≥1} |c_n|²; tail(N) = variation − 2 Σ_{n≤N} |c_n|².
  std::vector<long double> partial(static_cast<size_t>(channels), 0.0L);
  auto error_now = [&]() {
    double e = 0.0;
    for (int c = 0; c < channels; ++c) {
      if (variation[c] <= 0.0) continue;
      const long double tail = std::max(0.0L, static_cast<long double>(variation[c]) - partial[c]);
      e = std::max(e, static_cast<double>(std::sqrt(tail / variation[c])));
    }
    return e;
  };
  std::vector<Complex> flat;  // column-major (channels × N)
  VectorXc column(channels);
  int n_terms = 0;
  double error = error_now();
  while (error > rel_tol && n_terms < max_terms) {
    ++n_terms;
    PiecewiseHarmonic(pc, n_terms, column);
    for (int c = 0; c < channels; ++c) {
      flat.push_back(column[c]);
      partial[c] += 2.0L * static_cast<long double>(std::norm(column[c]));
    }
    error = error_now();
  }
  MatrixXc harmonics =
      Eigen::Map<const MatrixXc>(flat.data(), channels, static_cast<Eigen::Index>(n_terms));
  return FourierFit{FourierCoefficient(mean, std::move(harmonics), pc.period_meshes()), n_terms,
                    error, error <= rel_tol};
}

}  // namespace

const char* TimeDependenceName(TimeDependence dependence) {
  switch (dependence) {
    case TimeDependence::kConstant:
      return "constant";
    case TimeDependence::kPiecewiseConstant:
      return "piecewise_constant";
    case TimeDependence::kSmoothPeriodic:
      return "smooth_periodic";
    case TimeDependence::kNonlinear:
      return "nonlinear";
  }
  return "unknown";
}

// ---------------------------------------------------------------- constructors

ConstantCoefficient::ConstantCoefficient(VectorX values, std::int64_t period_meshes)
    : values_(std::move(values)), period_meshes_(period_meshes) {
  CheckPeriodMeshes(period_meshes_);
  GEARDYN_THROW_UNLESS(values_.size() >= 1, "values: needs at least one channel, got 0");
  CheckFinite(values_, "ConstantCoefficient values");
}

PiecewiseConstantCoefficient::PiecewiseConstantCoefficient(VectorX breakpoints, MatrixX values,
                                                           std::int64_t period_meshes)
    : breakpoints_(std::move(breakpoints)),
      values_(std::move(values)),
      period_meshes_(period_meshes) {
  CheckPeriodMeshes(period_meshes_);
  const double period = PeriodOf(period_meshes_);
  GEARDYN_THROW_UNLESS(breakpoints_.size() >= 1, "breakpoints: needs at least one entry, got 0");
  GEARDYN_THROW_UNLESS(values_.rows() >= 1, "values: needs at least one channel (row), got 0");
  GEARDYN_THROW_UNLESS(values_.cols() == breakpoints_.size(),
                       "values: has " << values_.cols() << " columns but breakpoints has "
                                      << breakpoints_.size()
                                      << " entries (one column per interval)");
  for (Eigen::Index k = 0; k < breakpoints_.size(); ++k) {
    const double t = breakpoints_[k];
    GEARDYN_THROW_UNLESS(std::isfinite(t) && t >= 0.0 && t < period,
                         "breakpoints[" << k << "] = " << t << " is outside [0, " << period
                                        << ") (period 2*pi*" << period_meshes_ << ")");
    if (k > 0) {
      GEARDYN_THROW_UNLESS(t > breakpoints_[k - 1],
                           "breakpoints: must be strictly increasing, but breakpoints["
                               << k << "] = " << t << " follows breakpoints[" << k - 1
                               << "] = " << breakpoints_[k - 1]);
    }
  }
  CheckFinite(values_, "PiecewiseConstantCoefficient values");
}

double PiecewiseConstantCoefficient::interval_end(int k) const {
  return k + 1 < num_intervals() ? breakpoints_[k + 1] : breakpoints_[0] + PeriodOf(period_meshes_);
}

int PiecewiseConstantCoefficient::FindInterval(double theta) const {
  const double t = Wrap(theta, PeriodOf(period_meshes_));
  const double* begin = breakpoints_.data();
  const double* end = begin + breakpoints_.size();
  const auto k = static_cast<int>(std::upper_bound(begin, end, t) - begin) - 1;
  return k < 0 ? num_intervals() - 1 : k;  // [0, θ_0) belongs to the last interval
}

FourierCoefficient::FourierCoefficient(VectorX mean, MatrixXc harmonics, std::int64_t period_meshes)
    : mean_(std::move(mean)), harmonics_(std::move(harmonics)), period_meshes_(period_meshes) {
  CheckPeriodMeshes(period_meshes_);
  GEARDYN_THROW_UNLESS(mean_.size() >= 1, "mean: needs at least one channel, got 0");
  if (harmonics_.cols() == 0 && harmonics_.rows() == 0) harmonics_.resize(mean_.size(), 0);
  GEARDYN_THROW_UNLESS(harmonics_.rows() == mean_.size(),
                       "harmonics: has " << harmonics_.rows() << " rows but mean has "
                                         << mean_.size() << " channels");
  CheckFinite(mean_, "FourierCoefficient mean");
  CheckFinite(harmonics_, "FourierCoefficient harmonics");
}

FourierCoefficient FourierCoefficient::FromCosSin(const VectorX& mean,
                                                  const MatrixX& cos_coefficients,
                                                  const MatrixX& sin_coefficients,
                                                  std::int64_t period_meshes) {
  GEARDYN_THROW_UNLESS(cos_coefficients.rows() == sin_coefficients.rows() &&
                           cos_coefficients.cols() == sin_coefficients.cols(),
                       "sin_coefficients: is "
                           << sin_coefficients.rows() << "x" << sin_coefficients.cols()
                           << " but cos_coefficients is " << cos_coefficients.rows() << "x"
                           << cos_coefficients.cols());
  // a cos + b sin = 2 Re(c e^{inθ}) with c = (a − i b)/2.
  MatrixXc harmonics(cos_coefficients.rows(), cos_coefficients.cols());
  harmonics.real() = 0.5 * cos_coefficients;
  harmonics.imag() = -0.5 * sin_coefficients;
  return FourierCoefficient(mean, std::move(harmonics), period_meshes);
}

TableCoefficient::TableCoefficient(MatrixX samples, std::int64_t period_meshes)
    : samples_(std::move(samples)), period_meshes_(period_meshes) {
  CheckPeriodMeshes(period_meshes_);
  GEARDYN_THROW_UNLESS(samples_.rows() >= 1, "samples: needs at least one channel (row), got 0");
  GEARDYN_THROW_UNLESS(samples_.cols() >= 1, "samples: needs at least one sample (column), got 0");
  CheckFinite(samples_, "TableCoefficient samples");
}

double TableCoefficient::sample_theta(int s) const {
  return PeriodOf(period_meshes_) * static_cast<double>(s) / static_cast<double>(num_samples());
}

// ---------------------------------------------------------------- queries

int NumChannels(const Coefficient& coef) {
  return std::visit([](const auto& c) { return c.num_channels(); }, coef);
}

std::int64_t PeriodMeshes(const Coefficient& coef) {
  return std::visit([](const auto& c) { return c.period_meshes(); }, coef);
}

double Period(const Coefficient& coef) { return PeriodOf(PeriodMeshes(coef)); }

// ---------------------------------------------------------------- evaluation (no allocation)

void Evaluate(const ConstantCoefficient& coef, double theta, Eigen::Ref<VectorX> out) {
  CheckEvaluateArgs(coef.num_channels(), theta, out);
  out = coef.values();
}

void Evaluate(const PiecewiseConstantCoefficient& coef, double theta, Eigen::Ref<VectorX> out) {
  CheckEvaluateArgs(coef.num_channels(), theta, out);
  out = coef.values().col(coef.FindInterval(theta));
}

namespace {

// Σ over the Fourier terms of f (and of f' when `derivative` is given): e^{inφ} by rotation,
// re-anchored every 32 terms to bound round-off growth; d/dθ e^{inθ/P} = (in/P) e^{inθ/P}, so
// f' gets 2 Re(i s c z) = −2 s Im(c z), s = n/P.
void SumFourier(const FourierCoefficient& coef, double theta, Eigen::Ref<VectorX> out,
                Eigen::Ref<VectorX>* derivative) {
  const double p = static_cast<double>(coef.period_meshes());
  const double phi = Wrap(theta, PeriodOf(coef.period_meshes())) / p;
  const Complex step = std::polar(1.0, phi);
  const MatrixXc& h = coef.harmonics();
  const Eigen::Index channels = h.rows();
  out = coef.mean();
  if (derivative != nullptr) derivative->setZero();
  Complex rotation(1.0, 0.0);
  for (int n = 1; n <= coef.num_terms(); ++n) {
    rotation = ((n - 1) % 32 == 0) ? std::polar(1.0, n * phi) : rotation * step;
    const Complex* column = h.data() + (n - 1) * channels;
    for (Eigen::Index c = 0; c < channels; ++c) {
      out[c] += 2.0 * (column[c].real() * rotation.real() - column[c].imag() * rotation.imag());
    }
    if (derivative == nullptr) continue;
    const double scale = 2.0 * static_cast<double>(n) / p;
    for (Eigen::Index c = 0; c < channels; ++c) {
      (*derivative)[c] -=
          scale * (column[c].real() * rotation.imag() + column[c].imag() * rotation.real());
    }
  }
}

}  // namespace

void Evaluate(const FourierCoefficient& coef, double theta, Eigen::Ref<VectorX> out) {
  CheckEvaluateArgs(coef.num_channels(), theta, out);
  SumFourier(coef, theta, out, nullptr);
}

void EvaluateWithDerivative(const FourierCoefficient& coef, double theta, Eigen::Ref<VectorX> out,
                            Eigen::Ref<VectorX> derivative) {
  CheckEvaluateArgs(coef.num_channels(), theta, out);
  CheckEvaluateArgs(coef.num_channels(), theta, derivative);
  SumFourier(coef, theta, out, &derivative);
}

void Evaluate(const TableCoefficient& coef, double theta, Eigen::Ref<VectorX> out) {
  CheckEvaluateArgs(coef.num_channels(), theta, out);
  const int s_count = coef.num_samples();
  const double u = Wrap(theta, PeriodOf(coef.period_meshes())) / PeriodOf(coef.period_meshes()) *
                   static_cast<double>(s_count);
  int i = static_cast<int>(std::floor(u));
  if (i >= s_count) i = s_count - 1;
  if (i < 0) i = 0;
  const double frac = u - static_cast<double>(i);
  const int j = (i + 1) % s_count;
  out = (1.0 - frac) * coef.samples().col(i) + frac * coef.samples().col(j);
}

void Evaluate(const Coefficient& coef, double theta, Eigen::Ref<VectorX> out) {
  std::visit(Overloaded{
                 [&](const ConstantCoefficient& c) { Evaluate(c, theta, out); },
                 [&](const PiecewiseConstantCoefficient& c) { Evaluate(c, theta, out); },
                 [&](const FourierCoefficient& c) { Evaluate(c, theta, out); },
                 [&](const TableCoefficient& c) { Evaluate(c, theta, out); },
             },
             coef);
}

// ---------------------------------------------------------------- mean, Fourier, classification

VectorX Mean(const Coefficient& coef) {
  return std::visit(
      Overloaded{
          [](const ConstantCoefficient& c) -> VectorX { return c.values(); },
          [](const PiecewiseConstantCoefficient& c) -> VectorX {
            const double period = PeriodOf(c.period_meshes());
            VectorX mean = VectorX::Zero(c.num_channels());
            for (int k = 0; k < c.num_intervals(); ++k) {
              mean += c.values().col(k) * (c.interval_width(k) / period);
            }
            return mean;
          },
          [](const FourierCoefficient& c) -> VectorX { return c.mean(); },
          // Mean of the periodic linear interpolant = trapezoid rule = mean of the samples.
          [](const TableCoefficient& c) -> VectorX { return c.samples().rowwise().mean(); },
      },
      coef);
}

FourierCoefficient ToFourier(const Coefficient& coef, int num_terms) {
  GEARDYN_THROW_UNLESS(num_terms >= 0, "num_terms: must be >= 0, got " << num_terms);
  return std::visit(
      Overloaded{
          [&](const ConstantCoefficient& c) {
            return FourierCoefficient(c.values(), MatrixXc::Zero(c.num_channels(), num_terms),
                                      c.period_meshes());
          },
          [&](const PiecewiseConstantCoefficient& c) {
            MatrixXc harmonics(c.num_channels(), num_terms);
            for (int n = 1; n <= num_terms; ++n) PiecewiseHarmonic(c, n, harmonics.col(n - 1));
            return FourierCoefficient(Mean(coef), std::move(harmonics), c.period_meshes());
          },
          [&](const FourierCoefficient& c) {
            MatrixXc harmonics = MatrixXc::Zero(c.num_channels(), num_terms);
            const int kept = std::min(num_terms, c.num_terms());
            harmonics.leftCols(kept) = c.harmonics().leftCols(kept);
            return FourierCoefficient(c.mean(), std::move(harmonics), c.period_meshes());
          },
          [&](const TableCoefficient& c) {
            const MatrixXc all = TableHarmonics(c);
            MatrixXc harmonics = MatrixXc::Zero(c.num_channels(), num_terms);
            const int kept = std::min(num_terms, static_cast<int>(all.cols()));
            harmonics.leftCols(kept) = all.leftCols(kept);
            return FourierCoefficient(c.samples().rowwise().mean(), std::move(harmonics),
                                      c.period_meshes());
          },
      },
      coef);
}

FourierFit ToFourierWithTolerance(const Coefficient& coef, double rel_tol, int max_terms) {
  GEARDYN_THROW_UNLESS(std::isfinite(rel_tol) && rel_tol > 0.0,
                       "rel_tol: must be finite and > 0, got " << rel_tol);
  GEARDYN_THROW_UNLESS(max_terms >= 0, "max_terms: must be >= 0, got " << max_terms);
  return std::visit(Overloaded{
                        [&](const ConstantCoefficient&) {
                          return FourierFit{ToFourier(coef, 0), 0, 0.0, true};
                        },
                        [&](const PiecewiseConstantCoefficient& c) {
                          return FitPiecewise(c, rel_tol, max_terms);
                        },
                        [&](const FourierCoefficient& c) {
                          return FitFiniteSeries(c.mean(), c.harmonics(), c.period_meshes(),
                                                 rel_tol, max_terms);
                        },
                        [&](const TableCoefficient& c) {
                          return FitFiniteSeries(c.samples().rowwise().mean(), TableHarmonics(c),
                                                 c.period_meshes(), rel_tol, max_terms);
                        },
                    },
                    coef);
}

TimeDependence Classify(const Coefficient& coef) {
  // A matrix whose columns are all equal (exactly) is constant in θ.
  auto columns_equal = [](const MatrixX& m) {
    for (Eigen::Index k = 1; k < m.cols(); ++k) {
      if (!(m.col(k).array() == m.col(0).array()).all()) return false;
    }
    return true;
  };
  return std::visit(Overloaded{
                        [](const ConstantCoefficient&) { return TimeDependence::kConstant; },
                        [&](const PiecewiseConstantCoefficient& c) {
                          return columns_equal(c.values()) ? TimeDependence::kConstant
                                                           : TimeDependence::kPiecewiseConstant;
                        },
                        [](const FourierCoefficient& c) {
                          return (c.harmonics().array() == Complex(0.0, 0.0)).all()
                                     ? TimeDependence::kConstant
                                     : TimeDependence::kSmoothPeriodic;
                        },
                        [&](const TableCoefficient& c) {
                          return columns_equal(c.samples()) ? TimeDependence::kConstant
                                                            : TimeDependence::kSmoothPeriodic;
                        },
                    },
                    coef);
}

}  // namespace geardyn
