/// @file
/// @brief The d-dimensional FFTW c2c transforms of the torus AFT (nonlinear_quasi_periodic_hb.hpp):
/// synthesis of a trigonometric polynomial on the N^d grid and analysis of samples into grid
/// coefficients, with the index map of the orders κ (row-major, axis 0 slowest, κ_b mod N).
#pragma once

#include <fftw3.h>

#include <complex>
#include <cstdint>
#include <mutex>
#include <numbers>
#include <vector>

#include "geardyn/numerics/fftw_planner.hpp"
#include "torus_harmonics.hpp"

namespace geardyn::internal {

/// @brief Plans made once for an N^d grid; one object per thread (the buffer is shared by the
/// calls).
class TorusFft {
 public:
  using Complex = std::complex<double>;

  TorusFft(int d, int N) : d_(d), N_(N) {
    points_ = 1;
    for (int b = 0; b < d; ++b) points_ *= N;
    buffer_.assign(static_cast<std::size_t>(points_), Complex(0.0, 0.0));
    std::vector<int> dims(static_cast<std::size_t>(d), N);
    auto* data = reinterpret_cast<fftw_complex*>(buffer_.data());
    std::lock_guard<std::mutex> lock(FftwPlannerMutex());
    backward_ = fftw_plan_dft(d, dims.data(), data, data, FFTW_BACKWARD, FFTW_ESTIMATE);
    forward_ = fftw_plan_dft(d, dims.data(), data, data, FFTW_FORWARD, FFTW_ESTIMATE);
  }
  ~TorusFft() {
    std::lock_guard<std::mutex> lock(FftwPlannerMutex());
    fftw_destroy_plan(backward_);
    fftw_destroy_plan(forward_);
  }
  TorusFft(const TorusFft&) = delete;
  TorusFft& operator=(const TorusFft&) = delete;

  std::int64_t points() const { return points_; }

  /// Grid index of the order κ (κ_b mod N per axis).
  std::int64_t Index(const std::vector<int>& kappa) const {
    std::int64_t idx = 0;
    for (int b = 0; b < d_; ++b) {
      idx = idx * N_ + ((kappa[static_cast<std::size_t>(b)] % N_) + N_) % N_;
    }
    return idx;
  }
  /// Grid index of κ − κ' (sign = −1) or κ + κ' (sign = +1).
  std::int64_t Index(const std::vector<int>& a, const std::vector<int>& c, int sign) const {
    std::int64_t idx = 0;
    for (int b = 0; b < d_; ++b) {
      const int v = a[static_cast<std::size_t>(b)] + sign * c[static_cast<std::size_t>(b)];
      idx = idx * N_ + ((v % N_) + N_) % N_;
    }
    return idx;
  }
  /// Angle ψ_b = 2π j_b / N of grid point p on axis b [rad].
  double Angle(std::int64_t p, int b) const {
    std::int64_t stride = 1;
    for (int c = b + 1; c < d_; ++c) stride *= N_;
    return 2.0 * std::numbers::pi * static_cast<double>((p / stride) % N_) / N_;
  }

  /// Re Σ_κ c_κ e^{iκ·ψ} at every grid point into out (points values); c over the whole set
  /// (both signs of κ), indices[i] = Index(κ_i).
  void Synthesize(const std::vector<std::int64_t>& indices, const Complex* coefficients,
                  double* out) {
    std::fill(buffer_.begin(), buffer_.end(), Complex(0.0, 0.0));
    for (std::size_t i = 0; i < indices.size(); ++i) {
      buffer_[static_cast<std::size_t>(indices[i])] += coefficients[i];
    }
    fftw_execute(backward_);
    for (std::int64_t p = 0; p < points_; ++p) out[p] = buffer_[static_cast<std::size_t>(p)].real();
  }
  /// The grid coefficients (1/N^d) Σ_p x_p e^{−i j·ψ_p} of real samples x into out (points).
  void Analyze(const double* samples, Complex* out) {
    for (std::int64_t p = 0; p < points_; ++p) {
      buffer_[static_cast<std::size_t>(p)] = Complex(samples[p], 0.0);
    }
    fftw_execute(forward_);
    const double scale = 1.0 / static_cast<double>(points_);
    for (std::int64_t p = 0; p < points_; ++p)
      out[p] = scale * buffer_[static_cast<std::size_t>(p)];
  }

 private:
  int d_, N_;
  std::int64_t points_ = 1;
  std::vector<Complex> buffer_;
  fftw_plan backward_ = nullptr, forward_ = nullptr;
};

}  // namespace geardyn::internal
