/// @file
/// @brief Exact separation integrals over the clipped contact lines, their θ-coefficients over
/// the hunting period and the transmission-error pair ε (spec 01 §3, §4).
#include "geardyn/models/mesh/transmission_error.hpp"

#include <Eigen/LU>
#include <algorithm>
#include <array>
#include <climits>
#include <cmath>
#include <complex>
#include <utility>

#include "geardyn/common/check.hpp"
#include "geardyn/common/units.hpp"
#include "geardyn/models/mesh/stiffness_core.hpp"
#include "polynomial_fourier_moments.hpp"

namespace geardyn {
namespace {

using Complex = std::complex<double>;
constexpr double kTwoPi = 2.0 * kPi;
/// Breakpoints of g(τ) closer than this [rad] are one (coincident events up to round-off), as in
/// ContactLineModel::Breakpoints.
constexpr double kBreakpointMerge = 1e-12;

/// 3-point Gauss–Legendre on [−1, 1]: exact for degree ≤ 5 (the integrands have degree ≤ 4).
constexpr std::array<double, 3> kGaussNodes = {-0.7745966692414834, 0.0, 0.7745966692414834};
constexpr std::array<double, 3> kGaussWeights = {5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0};

/// θ reduced to [0, 2π) — the same expression as ContactLineModel's, so both models see the same
/// lines at the same phase to the last bit.
double WrapMeshPhase(double theta) {
  double t = std::fmod(theta, kTwoPi);
  if (t < 0.0) t += kTwoPi;
  if (t >= kTwoPi) t = 0.0;
  return t;
}

// ------------------------------------------------- exact transform of the single-line function

/// g(τ) is a polynomial of degree ≤ 5 between breakpoints: 6 Chebyshev nodes fit it exactly.
constexpr int kPolyNodes = 6;
constexpr int kLineChannels = 4;  // ∫k, ∫kσ, ∫k e_mod, ∫kσ e_mod

/// One piece τ = mid + w t, t ∈ [−1, 1], of g: q_c(t) = Σ_r alpha(c, r) t^r.
struct LinePiece {
  double mid = 0.0;
  double half_width = 0.0;
  Eigen::Matrix<double, kLineChannels, kPolyNodes> alpha;
};

std::vector<LinePiece> BuildLinePieces(const TransmissionErrorModel& model) {
  const std::vector<double> breaks = model.LineBreakpoints();
  const double p = model.contact_lines().zone().transverse_base_pitch;
  const internal::ChebyshevFit<kPolyNodes>& fit = internal::GetChebyshevFit<kPolyNodes>();
  std::vector<LinePiece> pieces;
  for (size_t k = 0; k + 1 < breaks.size(); ++k) {
    LinePiece piece;
    piece.mid = 0.5 * (breaks[k] + breaks[k + 1]);
    piece.half_width = 0.5 * (breaks[k + 1] - breaks[k]);
    Eigen::Matrix<double, kLineChannels, kPolyNodes> values;
    for (int i = 0; i < kPolyNodes; ++i) {
      const double tau = piece.mid + piece.half_width * fit.nodes[i];
      const LineIntegrals g = model.CalcLineIntegrals(tau * p / kTwoPi);
      values.col(i) << g.stiffness, g.first_moment, g.k_e, g.k_sigma_e;
    }
    if (values.isZero(0.0)) continue;  // the line is outside the zone on this piece
    piece.alpha = values * fit.inverse_vandermonde.transpose();  // values = alpha · Vᵀ
    pieces.push_back(piece);
  }
  return pieces;
}

using LineTransform = Eigen::Matrix<Complex, kLineChannels, 1>;

/// ĝ(ω) = ∫ g(τ) e^{−iωτ} dτ of the four line channels, exact for the fitted pieces.
LineTransform CalcLineTransform(const std::vector<LinePiece>& pieces, double omega) {
  LineTransform sum = LineTransform::Zero();
  for (const LinePiece& piece : pieces) {
    // ∫ q(t) e^{−iω(mid + w t)} w dt = w e^{−iω·mid} Σ_r α_r M_r(ω w).
    internal::AddPieceTransform<kPolyNodes>(piece.alpha, piece.mid, piece.half_width, omega, &sum);
  }
  return sum;
}

/// Σ_{n=0}^{P−1} F[n mod z] e^{−2πimn/P} = (P/z) Σ_r F[r] e^{−2πimr/P} if (P/z) | m, else 0.
Complex LagSequenceDft(const std::vector<double>& lags, std::int64_t period, std::int64_t m) {
  if (lags.empty()) return Complex(0.0, 0.0);
  const auto z = static_cast<std::int64_t>(lags.size());
  const std::int64_t repeats = period / z;
  if (m % repeats != 0) return Complex(0.0, 0.0);
  Complex sum(0.0, 0.0);
  const std::int64_t m_mod = m % period;
  for (std::int64_t r = 0; r < z; ++r) {
    // Reduce m·r modulo P in integers so that the angle keeps full precision.
    const std::int64_t k = (m_mod * r) % period;
    sum += lags[static_cast<size_t>(r)] *
           std::polar(1.0, -kTwoPi * static_cast<double>(k) / static_cast<double>(period));
  }
  return static_cast<double>(repeats) * sum;
}

std::int64_t TotalSamples(const TransmissionErrorModel& model, int samples_per_mesh) {
  GEARDYN_THROW_UNLESS(samples_per_mesh >= 1,
                       "samples_per_mesh: must be >= 1, got " << samples_per_mesh);
  const std::int64_t total = samples_per_mesh * model.period_meshes();
  GEARDYN_THROW_UNLESS(total <= INT_MAX, "samples_per_mesh: " << samples_per_mesh << " x "
                                                              << model.period_meshes()
                                                              << " mesh cycles = " << total
                                                              << " samples exceed " << INT_MAX);
  return total;
}

}  // namespace

// --------------------------------------------------------------------------------- model

TransmissionErrorModel::TransmissionErrorModel(ContactLineModel contact_lines,
                                               const ToothModifications& modifications,
                                               const ToothErrors& errors)
    : lines_(std::move(contact_lines)), separation_(lines_.zone(), modifications, errors) {
  const ZoneOfAction& zone = lines_.zone();
  b_ = lines_.half_face_width();
  tan_ = std::tan(zone.base_helix_angle);
  cos_ = std::cos(zone.base_helix_angle);
  sin_ = std::sin(zone.base_helix_angle);
  sign_ = static_cast<double>(zone.drive_sign);
  x_start_ = separation_.path_start();
  x_end_ = separation_.path_end();
  // Roll positions where k·e changes its polynomial: path ends, relief kinks, stiffness knots.
  roll_kinks_ = separation_.profile_kinks();
  const StiffnessProfile& profile = lines_.profile();
  if (!profile.is_constant()) {
    const std::vector<double>& knots = profile.knots();
    for (size_t i = 1; i + 1 < knots.size(); ++i) {
      const double x = x_start_ + knots[i];
      if (x > x_start_ && x < x_end_) roll_kinks_.push_back(x);
    }
  }
  roll_kinks_.push_back(x_start_);
  roll_kinks_.push_back(x_end_);
  std::sort(roll_kinks_.begin(), roll_kinks_.end());
  roll_kinks_.erase(std::unique(roll_kinks_.begin(), roll_kinks_.end()), roll_kinks_.end());
}

LineIntegrals TransmissionErrorModel::CalcLineIntegrals(double x_line) const {
  LineIntegrals out;
  const StiffnessProfile& profile = lines_.profile();
  // Integrates over the face coordinate y ∈ [ya, yb] of one polynomial piece (3-point
  // Gauss–Legendre, exact): x = x_line − y tan β_b, σ = s(y/cos β_b − x_line sin β_b),
  // dℓ = dy/cos β_b.
  auto add = [&](double ya, double yb) {
    const double mid = 0.5 * (ya + yb), half = 0.5 * (yb - ya);
    const double sigma0 = -sign_ * x_line * sin_;
    for (int i = 0; i < 3; ++i) {
      const double y = mid + half * kGaussNodes[i];
      const double x = x_line - y * tan_;
      const double w = kGaussWeights[i] * half / cos_;
      const double k = profile.ValueAt(x - x_start_) * w;
      const double sigma = sign_ * y / cos_ + sigma0;
      const double e = separation_.ProfileSeparation(x) + separation_.LeadSeparation(y);
      out.stiffness += k;
      out.first_moment += k * sigma;
      out.k_e += k * e;
      out.k_sigma_e += k * sigma * e;
    }
  };
  if (tan_ == 0.0) {
    // Spur: the whole face at roll x_line, if x_s ≤ x_line < x_e (as ContactLineModel).
    if (x_line < x_start_ || x_line >= x_end_) return out;
    out.in_contact = true;
    add(-b_, b_);
    return out;
  }
  // Helical: the y-range where x ∈ [xa, xb] is [(x_line − xb)/t, (x_line − xa)/t] (swapped for
  // t < 0), clipped to the face — the same expressions as ContactLineModel.
  auto y_range = [&](double xa, double xb, double* lo, double* hi) {
    const double y1 = (x_line - xb) / tan_;
    const double y2 = (x_line - xa) / tan_;
    *lo = std::max(-b_, std::min(y1, y2));
    *hi = std::min(b_, std::max(y1, y2));
  };
  double lo = 0.0, hi = 0.0;
  y_range(x_start_, x_end_, &lo, &hi);
  if (!(hi > lo)) return out;
  out.in_contact = true;
  for (size_t i = 0; i + 1 < roll_kinks_.size(); ++i) {
    double slo = 0.0, shi = 0.0;
    y_range(roll_kinks_[i], roll_kinks_[i + 1], &slo, &shi);
    slo = std::max(slo, lo);
    shi = std::min(shi, hi);
    if (shi > slo) add(slo, shi);
  }
  return out;
}

SeparationIntegrals TransmissionErrorModel::CalcIntegrals(double theta) const {
  GEARDYN_THROW_UNLESS(std::isfinite(theta),
                       "CalcIntegrals: theta = " << theta << " is not finite");
  const double p = lines_.zone().transverse_base_pitch;
  const double wrapped = WrapMeshPhase(theta);
  const double phase = wrapped / kTwoPi;  // x_j = (phase + j) p_bt, as ContactLineModel
  const bool per_tooth = separation_.has_tooth_errors();
  std::int64_t cycle = 0;  // m = ⌊θ/2π⌋ mod P, consistent with the wrapped phase
  double runout = 0.0;
  if (per_tooth) {
    const auto period = static_cast<double>(period_meshes());
    double m = std::fmod(std::round((theta - wrapped) / kTwoPi), period);
    if (m < 0.0) m += period;
    cycle = static_cast<std::int64_t>(m);
    runout = separation_.RunoutSeparation(kTwoPi * m + wrapped);
  }
  const double reach = b_ * std::abs(tan_);  // a line spans x_j ± b|tan β_b|
  const auto j_min = static_cast<long>(std::floor((x_start_ - reach) / p - phase)) - 1;
  const auto j_max = static_cast<long>(std::ceil((x_end_ + reach) / p - phase)) + 1;
  SeparationIntegrals sums;
  for (long j = j_min; j <= j_max; ++j) {
    const LineIntegrals g = CalcLineIntegrals((phase + static_cast<double>(j)) * p);
    if (!g.in_contact) continue;
    ++sums.num_lines;
    sums.stiffness += g.stiffness;
    sums.first_moment += g.first_moment;
    sums.k_e += g.k_e;
    sums.k_sigma_e += g.k_sigma_e;
    if (per_tooth) {
      // Line j belongs to mesh cycle n = m − j (tooth_modifications.hpp); uniform on the line.
      const double e = separation_.ToothPairSeparation(cycle - j) + runout;
      sums.k_e += e * g.stiffness;
      sums.k_sigma_e += e * g.first_moment;
    }
  }
  return sums;
}

void TransmissionErrorModel::CalcChannels(double theta, Eigen::Ref<VectorX> out) const {
  GEARDYN_CHECK_SIZE(out.size(), kNumSeparationChannels, "CalcChannels: out");
  const SeparationIntegrals s = CalcIntegrals(theta);
  out[kSeparationKeChannel] = s.k_e;
  out[kSeparationKSigmaEChannel] = s.k_sigma_e;
}

Vector2 TransmissionErrorModel::CalcTransmissionError(double theta) const {
  const SeparationIntegrals s = CalcIntegrals(theta);
  const ContactLineIntegrals c = lines_.CalcIntegrals(theta);
  Matrix2 K2;  // spec 01 §3: K2 = [[∫k, −∫kσ], [−∫kσ, ∫kσ²]]
  K2 << c.stiffness, -c.first_moment, -c.first_moment, c.second_moment;
  return CalcTransmissionErrorPair(K2, s.k_e, s.k_sigma_e);
}

std::vector<double> TransmissionErrorModel::LineBreakpoints() const {
  const double reach = b_ * tan_;
  const double p = lines_.zone().transverse_base_pitch;
  std::vector<double> breaks;
  for (double c : roll_kinks_) {
    for (double x : {c - reach, c + reach}) breaks.push_back(kTwoPi * x / p);
  }
  std::sort(breaks.begin(), breaks.end());
  std::vector<double> merged;
  for (double t : breaks) {
    if (merged.empty() || t - merged.back() > kBreakpointMerge) merged.push_back(t);
  }
  return merged;
}

// ---------------------------------------------------------------- coefficient builders

TableCoefficient MakeSeparationTableCoefficient(const TransmissionErrorModel& model,
                                                int samples_per_mesh) {
  const std::int64_t total = TotalSamples(model, samples_per_mesh);
  MatrixX samples(kNumSeparationChannels, total);
  for (std::int64_t s = 0; s < total; ++s) {
    model.CalcChannels(kTwoPi * static_cast<double>(s) / samples_per_mesh, samples.col(s));
  }
  return TableCoefficient(std::move(samples), model.period_meshes());
}

namespace {

/// The exact Fourier coefficients of the separation channels over the hunting period (see the
/// header's "Structure over θ"): built once per model, evaluated per harmonic m.
class SeparationHarmonicsEvaluator {
 public:
  explicit SeparationHarmonicsEvaluator(const TransmissionErrorModel& model)
      : sep_(model.separation()),
        period_(model.period_meshes()),
        cos_b_(std::cos(model.contact_lines().zone().base_helix_angle)),
        pieces_(BuildLinePieces(model)),
        has_pitch_(!sep_.pinion_flank_lags().empty() || !sep_.gear_flank_lags().empty()) {
    // Runout terms: A cos(θ r/P + φ) with r = P/z multiplies the mesh-periodic (∫k, ∫kσ), whose
    // harmonic h is ĝ_K(h)/2π (Poisson): it adds (A/2)[e^{iφ} K̂((m − r)/P) + e^{−iφ} K̂((m +
    // r)/P)].
    const ToothErrors& e = sep_.errors();
    if (e.pinion_runout > 0.0) {
      runouts_.push_back(
          {-cos_b_ * e.pinion_runout, e.pinion_runout_phase, period_ / e.pinion_teeth});
    }
    if (e.gear_runout > 0.0) {
      runouts_.push_back({cos_b_ * e.gear_runout, e.gear_runout_phase, period_ / e.gear_teeth});
    }
  }

  /// c_m of (∫ke [N], ∫kσe [N·m]), m ≥ 0.
  Eigen::Matrix<Complex, kNumSeparationChannels, 1> operator()(std::int64_t m) const {
    Eigen::Matrix<Complex, kNumSeparationChannels, 1> c =
        Eigen::Matrix<Complex, kNumSeparationChannels, 1>::Zero();
    const auto P = static_cast<double>(period_);
    const bool mesh_harmonic = m % period_ == 0;
    // Â_m = cos β_b Σ_{n<P} (F_1[n mod z_1] − F_2[n mod z_2]) e^{−2πimn/P}
    Complex pitch(0.0, 0.0);
    if (has_pitch_) {
      pitch = cos_b_ * (LagSequenceDft(sep_.pinion_flank_lags(), period_, m) -
                        LagSequenceDft(sep_.gear_flank_lags(), period_, m));
    }
    if (mesh_harmonic || pitch != Complex(0.0, 0.0)) {
      const LineTransform g = CalcLineTransform(pieces_, static_cast<double>(m) / P);
      if (mesh_harmonic) c += g.tail<2>() / kTwoPi;  // flank modifications (period 2π)
      c += g.head<2>() * pitch / (kTwoPi * P);       // pitch deviations (period 2πP)
    }
    for (const Runout& r : runouts_) {
      for (int side : {1, -1}) {
        const std::int64_t num = m - side * r.shift;
        if (num % period_ != 0) continue;
        const double h = static_cast<double>(num / period_);  // mesh harmonic of (K, K·h)
        const LineTransform g = CalcLineTransform(pieces_, h);
        c += 0.5 * r.amplitude * std::polar(1.0, side * r.phase) * g.head<2>() / kTwoPi;
      }
    }
    return c;
  }

 private:
  struct Runout {
    double amplitude;    // A [m]
    double phase;        // φ [rad]
    std::int64_t shift;  // r = P/z
  };
  const UnloadedSeparation& sep_;
  std::int64_t period_;
  double cos_b_;
  std::vector<LinePiece> pieces_;
  bool has_pitch_;
  std::vector<Runout> runouts_;
};

}  // namespace

FourierCoefficient MakeSeparationFourierCoefficient(const TransmissionErrorModel& model,
                                                    int num_terms) {
  GEARDYN_THROW_UNLESS(num_terms >= 0, "num_terms: must be >= 0, got " << num_terms);
  const SeparationHarmonicsEvaluator coefficient(model);
  const VectorX mean = coefficient(0).real();
  MatrixXc harmonics(kNumSeparationChannels, num_terms);
  for (int m = 1; m <= num_terms; ++m) harmonics.col(m - 1) = coefficient(m);
  return FourierCoefficient(mean, std::move(harmonics), model.period_meshes());
}

MatrixXc CalcSeparationHarmonics(const TransmissionErrorModel& model,
                                 const std::vector<std::int64_t>& harmonics) {
  for (std::int64_t m : harmonics) {
    GEARDYN_THROW_UNLESS(m >= 0, "harmonics: must be >= 0, got " << m);
  }
  const SeparationHarmonicsEvaluator coefficient(model);
  MatrixXc out(kNumSeparationChannels, static_cast<Eigen::Index>(harmonics.size()));
  for (size_t i = 0; i < harmonics.size(); ++i) {
    out.col(static_cast<Eigen::Index>(i)) = coefficient(harmonics[i]);
  }
  return out;
}

TransmissionErrorSidebands MakeRunoutSidebands(const UnloadedSeparation& separation) {
  const ToothErrors& e = separation.errors();
  TransmissionErrorSidebands out;
  if (!(e.pinion_runout > 0.0) && !(e.gear_runout > 0.0)) return out;
  out.period_meshes = separation.period_meshes();
  const double cos_b = std::cos(separation.zone().base_helix_angle);
  std::vector<std::complex<double>> c;
  const auto add = [&](int teeth, double runout, double phase, double sign, const char* field) {
    if (!(runout > 0.0)) return;
    GEARDYN_THROW_UNLESS(teeth >= 2, field << ": a runout line on a gear of " << teeth
                                           << " tooth is a mesh order; use the table form");
    out.harmonics.push_back(out.period_meshes / teeth);
    c.push_back(std::polar(0.5 * sign * cos_b * runout, phase));
  };
  add(e.pinion_teeth, e.pinion_runout, e.pinion_runout_phase, -1.0, "errors.pinion_teeth");
  add(e.gear_teeth, e.gear_runout, e.gear_runout_phase, 1.0, "errors.gear_teeth");
  out.coefficients = MatrixXc::Zero(2, static_cast<Eigen::Index>(c.size()));
  for (size_t i = 0; i < c.size(); ++i) out.coefficients(0, static_cast<Eigen::Index>(i)) = c[i];
  return out;
}

TableCoefficient MakeTransmissionErrorTableCoefficient(const TransmissionErrorModel& model,
                                                       int samples_per_mesh) {
  const std::int64_t total = TotalSamples(model, samples_per_mesh);
  MatrixX samples(kNumTransmissionErrorChannels, total);
  for (std::int64_t s = 0; s < total; ++s) {
    // Element-wise: assigning the fixed 2-vector to a dynamic column trips a GCC 12
    // -Wstringop-overread false positive in Eigen's packet store.
    const Vector2 epsilon =
        model.CalcTransmissionError(kTwoPi * static_cast<double>(s) / samples_per_mesh);
    samples(kTransmissionErrorEtaChannel, s) = epsilon[0];
    samples(kTransmissionErrorZetaChannel, s) = epsilon[1];
  }
  return TableCoefficient(std::move(samples), model.period_meshes());
}

FourierCoefficient MakeTransmissionErrorFourierCoefficient(const TransmissionErrorModel& model,
                                                           int num_terms, int samples_per_mesh) {
  const std::int64_t total = TotalSamples(model, samples_per_mesh);
  GEARDYN_THROW_UNLESS(num_terms >= 0 && 2 * static_cast<std::int64_t>(num_terms) <= total,
                       "num_terms: must be in [0, S/2] for S = samples_per_mesh x period_meshes = "
                           << total << " samples, got " << num_terms);
  return ToFourier(MakeTransmissionErrorTableCoefficient(model, samples_per_mesh), num_terms);
}

}  // namespace geardyn
