/// @file
/// @brief θ-coefficients: multi-channel periodic functions of the mesh phase θ (spec 01 §4,
/// spec 02; architecture §3.4), as a closed `std::variant` of four representations.
///
/// A coefficient holds `num_channels` real functions f_c(θ) that share one representation
/// (breakpoints, samples or harmonics), so evaluating all of them at θ is one lookup. Typical
/// channels are the entries of a mesh stiffness core, e.g. (K, K·h, K·μ·b²) [N/m, N, N·m] (see
/// geardyn/models/mesh/contact_lines.hpp), or transmission errors ε_η, ε_ζ.
///
/// **Period.** Every representation is periodic in θ [rad] with period T = 2π·P, where the
/// integer P = `period_meshes()` is 1 for mesh-periodic functions and the hunting-period mesh
/// count lcm(z_1, z_2) when tooth-to-tooth errors repeat only over the hunting period (spec 01
/// §1). θ may be any finite real number; it is reduced modulo T.
///
/// **Representations** (all validate their inputs on construction and are immutable):
/// * ConstantCoefficient — f_c(θ) = v_c.
/// * PiecewiseConstantCoefficient — exact steps: breakpoints 0 ≤ θ_0 < … < θ_{K−1} < T, value
///   column k on the half-open interval [θ_k, θ_{k+1}) (right-continuous), the last interval
///   wrapping around to θ_0 + T. What the exact exponential Floquet path needs (spec 02).
/// * FourierCoefficient — f_c(θ) = m_c + 2 Re Σ_{n=1..N} c_{c,n} e^{i n θ/P}, i.e.
///   m_c + Σ (a_{c,n} cos(nθ/P) + b_{c,n} sin(nθ/P)) with a = 2 Re c, b = −2 Im c. The c_n are
///   the complex Fourier coefficients (1/T)∫ f e^{−inθ/P} dθ for n ≥ 1; c_{−n} = conj(c_n).
/// * TableCoefficient — S uniform samples f_c(θ_s), θ_s = s·T/S, s = 0…S−1, evaluated by
///   periodic **linear** interpolation (continuous, piecewise linear, exact at the samples; error
///   O((T/S)²) for smooth f). Its ToFourier is the trigonometric interpolant of the samples (see
///   ToFourier), which agrees with the linear interpolant at the samples only.
///
/// **Hot path.** `Evaluate(coef, θ, out)` writes all channels into a caller-sized buffer and
/// never allocates; the overloads on the concrete types skip the variant dispatch.
#pragma once

#include <cstdint>
#include <variant>

#include "geardyn/common/eigen_types.hpp"

namespace geardyn {

/// @brief How a coefficient (or a whole system) depends on θ. Ordered: the dependence of a
/// combination is the largest of its parts (see Combine).
enum class TimeDependence {
  kConstant = 0,           ///< independent of θ → LTI paths
  kPiecewiseConstant = 1,  ///< exact steps → exact matrix-exponential products (spec 02)
  kSmoothPeriodic = 2,     ///< anything else periodic (Fourier, tables) → general LTV paths
  kNonlinear = 3,          ///< never returned by Classify; for nonlinear mesh cores (system level)
};

/// @brief The larger (more general) of two time dependences.
constexpr TimeDependence Combine(TimeDependence a, TimeDependence b) {
  return static_cast<int>(a) >= static_cast<int>(b) ? a : b;
}

/// @brief Text name ("constant", "piecewise_constant", "smooth_periodic", "nonlinear").
const char* TimeDependenceName(TimeDependence dependence);

/// @brief f_c(θ) = v_c for every θ.
class ConstantCoefficient {
 public:
  /// @param[in] values (num_channels) the constant values, finite, num_channels ≥ 1.
  /// @param[in] period_meshes P ≥ 1: the period is 2π·P [rad] (matters only when combined).
  /// @throws InvalidInput naming `values` or `period_meshes`.
  explicit ConstantCoefficient(VectorX values, std::int64_t period_meshes = 1);

  /// Number of channels [-].
  int num_channels() const { return static_cast<int>(values_.size()); }
  /// P [-]: the period is 2π·P [rad].
  std::int64_t period_meshes() const { return period_meshes_; }
  /// (num_channels) the values, in the channels' units.
  const VectorX& values() const { return values_; }

 private:
  VectorX values_;
  std::int64_t period_meshes_;
};

/// @brief Exact steps: value column k on [θ_k, θ_{k+1}), θ_K ≡ θ_0 + T (right-continuous).
///
/// The interval structure is what the exact Floquet path multiplies over:
/// Φ(θ_0 + T, θ_0) = Π_k expm(A_k Δθ_k/ω_m) with Δθ_k = interval_width(k). Between 0 and θ_0 the
/// value is the last column (the last interval wraps around the period end).
class PiecewiseConstantCoefficient {
 public:
  /// @param[in] breakpoints (K) θ_k [rad], K ≥ 1, finite, strictly increasing, in [0, 2πP).
  /// @param[in] values (num_channels × K) value of each channel on each interval, finite.
  /// @param[in] period_meshes P ≥ 1: the period is T = 2π·P [rad].
  /// @throws InvalidInput naming `breakpoints`, `values` or `period_meshes` (index and value).
  PiecewiseConstantCoefficient(VectorX breakpoints, MatrixX values, std::int64_t period_meshes = 1);

  /// Number of channels [-].
  int num_channels() const { return static_cast<int>(values_.rows()); }
  /// Number of intervals K [-] (= number of breakpoints).
  int num_intervals() const { return static_cast<int>(breakpoints_.size()); }
  /// P [-]: the period is 2π·P [rad].
  std::int64_t period_meshes() const { return period_meshes_; }
  /// (K) interval starts θ_k [rad].
  const VectorX& breakpoints() const { return breakpoints_; }
  /// (num_channels × K) interval values.
  const MatrixX& values() const { return values_; }
  /// Start θ_k of interval k [rad].
  double interval_begin(int k) const { return breakpoints_[k]; }
  /// End of interval k [rad]: θ_{k+1}, or θ_0 + T for the last one (may exceed T).
  double interval_end(int k) const;
  /// Width θ_end − θ_begin of interval k [rad] (all widths sum to T).
  double interval_width(int k) const { return interval_end(k) - interval_begin(k); }
  /// Index k of the interval containing θ (θ reduced modulo T; the wrap-around part [0, θ_0)
  /// belongs to the last interval).
  int FindInterval(double theta) const;

 private:
  VectorX breakpoints_;
  MatrixX values_;
  std::int64_t period_meshes_;
};

/// @brief Truncated Fourier series f_c(θ) = m_c + 2 Re Σ_{n=1..N} c_{c,n} e^{inθ/P}.
class FourierCoefficient {
 public:
  /// @param[in] mean (num_channels) m_c, finite, num_channels ≥ 1.
  /// @param[in] harmonics (num_channels × N) complex c_{c,n} in column n−1, finite; N ≥ 0.
  /// @param[in] period_meshes P ≥ 1: harmonic n has the frequency n/P of the mesh frequency.
  /// @throws InvalidInput naming `mean`, `harmonics` or `period_meshes`.
  FourierCoefficient(VectorX mean, MatrixXc harmonics, std::int64_t period_meshes = 1);

  /// @brief From real cosine/sine amplitudes: f = m + Σ a_n cos(nθ/P) + b_n sin(nθ/P).
  /// @param[in] cos_coefficients, sin_coefficients (num_channels × N) a_n, b_n in column n−1.
  static FourierCoefficient FromCosSin(const VectorX& mean, const MatrixX& cos_coefficients,
                                       const MatrixX& sin_coefficients,
                                       std::int64_t period_meshes = 1);

  /// Number of channels [-].
  int num_channels() const { return static_cast<int>(mean_.size()); }
  /// N, the highest harmonic kept.
  int num_terms() const { return static_cast<int>(harmonics_.cols()); }
  /// P [-]: harmonic n has n/P times the mesh frequency.
  std::int64_t period_meshes() const { return period_meshes_; }
  /// (num_channels) the mean m_c = c_{c,0}.
  const VectorX& mean() const { return mean_; }
  /// (num_channels × N) c_{c,n}, column n−1.
  const MatrixXc& harmonics() const { return harmonics_; }
  /// (num_channels × N) a_{c,n} = 2 Re c_{c,n}.
  MatrixX CosCoefficients() const { return 2.0 * harmonics_.real(); }
  /// (num_channels × N) b_{c,n} = −2 Im c_{c,n}.
  MatrixX SinCoefficients() const { return -2.0 * harmonics_.imag(); }

 private:
  VectorX mean_;
  MatrixXc harmonics_;
  std::int64_t period_meshes_;
};

/// @brief Uniform samples over one period, periodic linear interpolation in between.
class TableCoefficient {
 public:
  /// @param[in] samples (num_channels × S) f_c(s·T/S), finite; num_channels ≥ 1, S ≥ 1.
  /// @param[in] period_meshes P ≥ 1: the period is T = 2π·P [rad].
  /// @throws InvalidInput naming `samples` or `period_meshes`.
  explicit TableCoefficient(MatrixX samples, std::int64_t period_meshes = 1);

  /// Number of channels [-].
  int num_channels() const { return static_cast<int>(samples_.rows()); }
  /// Number of samples S per period [-].
  int num_samples() const { return static_cast<int>(samples_.cols()); }
  /// P [-]: the period is 2π·P [rad].
  std::int64_t period_meshes() const { return period_meshes_; }
  /// (num_channels × S) the samples.
  const MatrixX& samples() const { return samples_; }
  /// θ_s = s·T/S [rad].
  double sample_theta(int s) const;

 private:
  MatrixX samples_;
  std::int64_t period_meshes_;
};

/// @brief A θ-coefficient: the closed set of representations (architecture §3.4). Visit it with
/// overloaded lambdas and no catch-all, so that a new representation fails to compile.
using Coefficient = std::variant<ConstantCoefficient, PiecewiseConstantCoefficient,
                                 FourierCoefficient, TableCoefficient>;

/// @brief Number of channels of any representation.
int NumChannels(const Coefficient& coef);
/// @brief P: the period is 2π·P [rad].
std::int64_t PeriodMeshes(const Coefficient& coef);
/// @brief The period T = 2π·P [rad].
double Period(const Coefficient& coef);

/// @brief All channels at θ, written into `out`; never allocates.
/// @param[in] theta mesh phase [rad], any finite value (reduced modulo T).
/// @param[out] out (num_channels) the values, in the channels' units.
/// @throws InvalidInput if out has the wrong size or θ is not finite.
void Evaluate(const Coefficient& coef, double theta, Eigen::Ref<VectorX> out);
void Evaluate(const ConstantCoefficient& coef, double theta, Eigen::Ref<VectorX> out);
void Evaluate(const PiecewiseConstantCoefficient& coef, double theta, Eigen::Ref<VectorX> out);
/// Cost O(N·num_channels); e^{inθ/P} by complex rotation, re-anchored every 32 terms.
void Evaluate(const FourierCoefficient& coef, double theta, Eigen::Ref<VectorX> out);
/// Periodic linear interpolation between the two neighbouring samples.
void Evaluate(const TableCoefficient& coef, double theta, Eigen::Ref<VectorX> out);
/// @brief f_c(θ) and its exact derivative f_c'(θ) = Σ 2 Re(i(n/P) c_{c,n} e^{inθ/P}) [per rad]
/// in one pass over the terms (the cost of one Evaluate); never allocates.
/// @throws InvalidInput if out or derivative has the wrong size or θ is not finite.
void EvaluateWithDerivative(const FourierCoefficient& coef, double theta, Eigen::Ref<VectorX> out,
                            Eigen::Ref<VectorX> derivative);

/// @brief The mean (1/T)∫_0^T f_c dθ of each channel, exact for every representation (for a
/// table: the mean of its linear interpolant, which is the mean of the samples).
/// @return (num_channels).
VectorX Mean(const Coefficient& coef);

/// @brief The first `num_terms` harmonics of the coefficient's Fourier series.
///
/// * Constant: mean only, zero harmonics.
/// * PiecewiseConstant: closed form, per interval [α, β) of value v and width Δ = β − α:
///   c_n += v (Δ/T) sinc(nΔ/(2P)) e^{−in(α+β)/(2P)} with sinc(x) = sin x / x. Exact.
/// * Fourier: truncated, or padded with zeros.
/// * Table (S samples): the trigonometric interpolant of the samples, by FFT (FFTW):
///   c_n = (1/S) Σ_s f_s e^{−2πi n s/S} for n < S/2, c_{S/2} halved for even S, zero above.
///   Exact for trigonometric polynomials of degree < S/2; for other functions the usual aliasing
///   error. (This is NOT the series of the linear interpolant that Evaluate uses.)
/// @param[in] num_terms N ≥ 0.
/// @throws InvalidInput if num_terms < 0.
FourierCoefficient ToFourier(const Coefficient& coef, int num_terms);

/// @brief Result of ToFourierWithTolerance.
struct FourierFit {
  FourierCoefficient fourier;   ///< the series with num_terms harmonics
  int num_terms = 0;            ///< N, the smallest number of harmonics meeting rel_tol (or max)
  double error_estimate = 0.0;  ///< the error measure below for this N [-]
  bool tolerance_met = false;   ///< error_estimate ≤ rel_tol
};

/// @brief The shortest Fourier series whose relative L2 tail error is ≤ rel_tol.
///
/// Error measure, per channel c, maximised over channels:
/// \f[ e_c(N) = \frac{\| f_c - S_N f_c \|_{L^2}}{\| f_c - \bar f_c \|_{L^2}}
///            = \sqrt{\frac{\sum_{n>N} |c_{c,n}|^2}{\sum_{n\ge 1} |c_{c,n}|^2}} \f]
/// (Parseval), i.e. the L2 norm of the discarded tail relative to the L2 norm of the variation;
/// channels without variation count as e_c = 0. The denominators are exact: Σ_k (v_k − m)²Δ_k/T
/// for piecewise-constant, the finite sums for Fourier and tables (whose series is the
/// trigonometric interpolant, see ToFourier). For piecewise-constant input the tail is
/// variance − partial sum (compensated); it decays only like N^{-1/2} because of the jumps, so
/// small tolerances need many terms and may hit max_terms (then tolerance_met = false).
/// Resolvable down to rel_tol ≈ 1e-7 (round-off in the tail of slowly decaying series).
/// @param[in] rel_tol > 0 target relative L2 error [-].
/// @param[in] max_terms ≥ 0 upper bound on N.
/// @throws InvalidInput naming rel_tol or max_terms.
FourierFit ToFourierWithTolerance(const Coefficient& coef, double rel_tol, int max_terms = 1 << 16);

/// @brief Which analysis path the coefficient allows (spec 02 "skip what a scene doesn't need").
///
/// By value, not by type: kConstant when every channel is exactly constant (all piecewise values
/// or table samples equal per channel, all Fourier harmonics zero); otherwise kPiecewiseConstant
/// for PiecewiseConstantCoefficient and kSmoothPeriodic for Fourier and tables (a table is
/// piecewise linear, never stepwise). Never returns kNonlinear.
TimeDependence Classify(const Coefficient& coef);

}  // namespace geardyn
