/// @file
/// @brief Closed-form contact-line sums (spec 01 §4.1) and exact θ-coefficients built from them.
#include "geardyn/models/mesh/contact_lines.hpp"

#include <Eigen/LU>
#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <limits>
#include <sstream>
#include <utility>

#include "geardyn/common/check.hpp"
#include "geardyn/common/units.hpp"
#include "geardyn/models/gear/gear_geometry.hpp"
#include "polynomial_fourier_moments.hpp"
#include "zone_of_action_checks.hpp"

namespace geardyn {
namespace {

using Complex = std::complex<double>;
constexpr double kTwoPi = 2.0 * kPi;
/// Breakpoints closer than this [rad] are one breakpoint (coincident events up to round-off,
/// e.g. integer ε_α or ε_β); a merged sliver changes a Fourier coefficient by < 1e-12 relative.
constexpr double kBreakpointMerge = 1e-12;

void CheckProfileVectors(const std::vector<double>& knots, size_t num_values,
                         const char* values_name, const std::vector<double>& values) {
  GEARDYN_THROW_UNLESS(knots.size() >= 2,
                       "profile knots: needs at least 2 knots, got " << knots.size());
  GEARDYN_THROW_UNLESS(values.size() == num_values, "profile "
                                                        << values_name << ": has " << values.size()
                                                        << " entries, expected " << num_values
                                                        << " for " << knots.size() << " knots");
  for (size_t i = 0; i < knots.size(); ++i) {
    GEARDYN_THROW_UNLESS(std::isfinite(knots[i]),
                         "profile knots[" << i << "] = " << knots[i] << " is not finite");
    if (i > 0) {
      GEARDYN_THROW_UNLESS(knots[i] > knots[i - 1],
                           "profile knots: must be strictly increasing, but knots["
                               << i << "] = " << knots[i] << " follows knots[" << i - 1
                               << "] = " << knots[i - 1]);
    }
  }
  for (size_t i = 0; i < values.size(); ++i) {
    GEARDYN_THROW_UNLESS(std::isfinite(values[i]) && values[i] >= 0.0,
                         "profile " << values_name << "[" << i << "] = " << values[i]
                                    << " must be finite and >= 0 [N/m^2]");
  }
}

/// θ reduced to [0, 2π).
double WrapMeshPhase(double theta) {
  double t = std::fmod(theta, kTwoPi);
  if (t < 0.0) t += kTwoPi;
  if (t >= kTwoPi) t = 0.0;
  return t;
}

// ----------------------------------------------------------- exact piecewise-polynomial series

constexpr int kPolyNodes = 5;  // degree ≤ 4 in θ between breakpoints

/// One piece [θ_mid − w, θ_mid + w] of the channels, q_c(τ) = Σ_r alpha(c, r) τ^r, θ = mid + w τ.
struct PolyPiece {
  double mid = 0.0;
  double half_width = 0.0;
  Eigen::Matrix<double, kNumMeshChannels, kPolyNodes> alpha;
};

/// Pieces between consecutive breakpoints (cyclically), each fitted exactly.
std::vector<PolyPiece> BuildPieces(const ContactLineModel& model) {
  std::vector<double> breaks = model.Breakpoints();
  if (breaks.empty()) breaks.push_back(0.0);
  const internal::ChebyshevFit<kPolyNodes>& fit = internal::GetChebyshevFit<kPolyNodes>();
  std::vector<PolyPiece> pieces;
  pieces.reserve(breaks.size());
  Eigen::Matrix<double, kNumMeshChannels, kPolyNodes> values;
  VectorX channels(kNumMeshChannels);
  for (size_t k = 0; k < breaks.size(); ++k) {
    const double a = breaks[k];
    const double b = k + 1 < breaks.size() ? breaks[k + 1] : breaks[0] + kTwoPi;
    PolyPiece piece;
    piece.mid = 0.5 * (a + b);
    piece.half_width = 0.5 * (b - a);
    for (int i = 0; i < kPolyNodes; ++i) {
      model.CalcChannels(piece.mid + piece.half_width * fit.nodes[i], channels);
      values.col(i) = channels;
    }
    // values = alpha · Vᵀ  ⇒  alpha = values · V⁻ᵀ.
    piece.alpha = values * fit.inverse_vandermonde.transpose();
    pieces.push_back(piece);
  }
  return pieces;
}

/// c_n = (1/2π) ∫_0^{2π} f e^{−inθ} dθ of all channels, exact for the fitted pieces.
Eigen::Matrix<Complex, kNumMeshChannels, 1> PieceSeriesCoefficient(
    const std::vector<PolyPiece>& pieces, int n) {
  Eigen::Matrix<Complex, kNumMeshChannels, 1> sum =
      Eigen::Matrix<Complex, kNumMeshChannels, 1>::Zero();
  for (const PolyPiece& piece : pieces) {
    // ∫ q(τ) e^{−in(mid + wτ)} w dτ = w e^{−in·mid} Σ_r α_r M_r(n w).
    internal::AddPieceTransform<kPolyNodes>(piece.alpha, piece.mid, piece.half_width,
                                            static_cast<double>(n), &sum);
  }
  return sum / kTwoPi;
}

/// (1/2π) ∫ (f_c − mean_c)² dθ per channel: 5-point Gauss–Legendre per piece (exact, degree 8).
VectorX PieceVariation(const std::vector<PolyPiece>& pieces, const VectorX& mean) {
  static const std::array<double, 5> x = {0.0, -0.5384693101056831, 0.5384693101056831,
                                          -0.9061798459386640, 0.9061798459386640};
  static const std::array<double, 5> w = {0.5688888888888889, 0.4786286704993665,
                                          0.4786286704993665, 0.2369268850561891,
                                          0.2369268850561891};
  VectorX variation = VectorX::Zero(kNumMeshChannels);
  for (const PolyPiece& piece : pieces) {
    for (int i = 0; i < 5; ++i) {
      for (int c = 0; c < kNumMeshChannels; ++c) {
        double q = 0.0;
        for (int r = kPolyNodes - 1; r >= 0; --r) q = q * x[i] + piece.alpha(c, r);
        const double d = q - mean[c];
        variation[c] += w[i] * piece.half_width * d * d;
      }
    }
  }
  return variation / kTwoPi;
}

VectorX PieceMean(const std::vector<PolyPiece>& pieces) {
  return PieceSeriesCoefficient(pieces, 0).real();
}

/// Per-channel scale for "constant to round-off": K̄·b^c (c = 0, 1, 2).
bool PiecesAreConstant(const ContactLineModel& model, const std::vector<PolyPiece>& pieces,
                       const VectorX& mean) {
  const VectorX variation = PieceVariation(pieces, mean);
  double scale = std::abs(mean[kMeshStiffnessChannel]);
  for (int c = 0; c < kNumMeshChannels; ++c) {
    if (std::sqrt(variation[c]) > 1e-13 * scale) return false;
    scale *= model.half_face_width();
  }
  return true;
}

}  // namespace

// ---------------------------------------------------------------- zone of action

double ZoneOfAction::overlap_ratio() const {
  return face_width * std::abs(std::tan(base_helix_angle)) / transverse_base_pitch;
}

ZoneOfAction MakeZoneOfAction(const GearPairGeometry& geometry, int drive_sign) {
  GEARDYN_THROW_UNLESS(drive_sign == 1 || drive_sign == -1,
                       "drive_sign: must be +1 or -1, got " << drive_sign);
  ZoneOfAction zone;
  zone.length = geometry.line_of_action_length;
  zone.face_width = geometry.face_width;
  zone.transverse_base_pitch = geometry.transverse_base_pitch;
  double hand = 0.0;
  if (geometry.pinion.hand == HelixHand::kRight) hand = 1.0;
  if (geometry.pinion.hand == HelixHand::kLeft) hand = -1.0;
  if (geometry.spec.pinion_hand == HelixHand::kRight && hand == 0.0) hand = 1.0;
  if (geometry.spec.pinion_hand == HelixHand::kLeft && hand == 0.0) hand = -1.0;
  GEARDYN_THROW_UNLESS(hand != 0.0 || geometry.base_helix_angle == 0.0,
                       "geometry.pinion.hand: a helical pair (base_helix_angle = "
                           << geometry.base_helix_angle << ") needs a helix hand");
  zone.base_helix_angle = -static_cast<double>(drive_sign) * hand * geometry.base_helix_angle;
  zone.drive_sign = drive_sign;
  // Approach length: from the start of contact (driven gear's tip on the line of action) to the
  // pitch point C; T2A = √(r_a2² − r_b2²), T2C = r_b2 tan α_wt.
  const double ra = geometry.gear.tip_radius;
  const double rb = geometry.gear.base_radius;
  const double t2a = std::sqrt(std::max(0.0, ra * ra - rb * rb));
  const double t2c = rb * std::tan(geometry.operating_pressure_angle);
  // A rack has no T2: the approach is T1C − T1A on the pinion's roll lengths (the same length).
  double approach = geometry.rack ? geometry.pitch_point_from_pinion_tangent -
                                        geometry.path_start_from_pinion_tangent
                    : geometry.internal ? t2c - t2a
                                        : t2a - t2c;
  approach = std::clamp(approach, 0.0, zone.length);
  zone.pitch_point_offset = approach - 0.5 * zone.length;
  return zone;
}

// ---------------------------------------------------------------- stiffness profile

StiffnessProfile StiffnessProfile::Constant(double k) {
  GEARDYN_THROW_UNLESS(std::isfinite(k) && k >= 0.0,
                       "profile k: must be finite and >= 0 [N/m^2], got " << k);
  StiffnessProfile p;
  p.start_values_ = {k};
  p.end_values_ = {k};
  return p;
}

StiffnessProfile StiffnessProfile::PiecewiseConstant(std::vector<double> knots,
                                                     std::vector<double> values) {
  CheckProfileVectors(knots, knots.size() - 1, "values", values);
  std::vector<double> end = values;
  return Segments(std::move(knots), std::move(values), std::move(end));
}

StiffnessProfile StiffnessProfile::PiecewiseLinear(std::vector<double> knots,
                                                   std::vector<double> values) {
  CheckProfileVectors(knots, knots.size(), "values", values);
  std::vector<double> start(values.begin(), values.end() - 1);
  std::vector<double> end(values.begin() + 1, values.end());
  return Segments(std::move(knots), std::move(start), std::move(end));
}

StiffnessProfile StiffnessProfile::Segments(std::vector<double> knots,
                                            std::vector<double> start_values,
                                            std::vector<double> end_values) {
  GEARDYN_THROW_UNLESS(!knots.empty(), "profile knots: needs at least 2 knots, got 0");
  CheckProfileVectors(knots, knots.size() - 1, "start_values", start_values);
  CheckProfileVectors(knots, knots.size() - 1, "end_values", end_values);
  StiffnessProfile p;
  p.knots_ = std::move(knots);
  p.start_values_ = std::move(start_values);
  p.end_values_ = std::move(end_values);
  return p;
}

double StiffnessProfile::ValueAt(double roll) const {
  if (is_constant()) return start_values_[0];
  const auto it = std::upper_bound(knots_.begin(), knots_.end(), roll);
  int i = static_cast<int>(it - knots_.begin()) - 1;
  i = std::clamp(i, 0, num_segments() - 1);
  const double r0 = knots_[i], r1 = knots_[i + 1];
  return start_values_[i] + (end_values_[i] - start_values_[i]) * (roll - r0) / (r1 - r0);
}

bool StiffnessProfile::is_piecewise_constant() const {
  for (int i = 0; i < num_segments(); ++i) {
    if (start_values_[i] != end_values_[i]) return false;
  }
  return true;
}

// ---------------------------------------------------------------- model

MeshParameters MeshParametersFromChannels(double stiffness, double first_moment,
                                          double second_moment, double half_face_width) {
  GEARDYN_THROW_UNLESS(half_face_width > 0.0,
                       "half_face_width: must be > 0 [m], got " << half_face_width);
  MeshParameters p;
  p.stiffness = stiffness;
  if (stiffness > 0.0) {
    p.load_centre = first_moment / stiffness;
    p.kappa = p.load_centre / half_face_width;
    p.mu = second_moment / (stiffness * half_face_width * half_face_width);
  }
  return p;
}

ContactLineModel::ContactLineModel(const ZoneOfAction& zone, StiffnessProfile profile)
    : zone_(zone), profile_(std::move(profile)) {
  internal::CheckZoneGeometry(zone);
  GEARDYN_THROW_UNLESS(zone.drive_sign == 1 || zone.drive_sign == -1,
                       "zone.drive_sign: must be +1 or -1, got " << zone.drive_sign);
  const double total = zone.transverse_contact_ratio() + zone.overlap_ratio();
  GEARDYN_THROW_UNLESS(total >= 1.0 - 1e-12,
                       "zone: total contact ratio eps_alpha + eps_beta = "
                           << total << " is below 1 (contact would be lost; eps_alpha = "
                           << zone.transverse_contact_ratio()
                           << ", eps_beta = " << zone.overlap_ratio() << ")");
  b_ = 0.5 * zone.face_width;
  tan_ = std::tan(zone.base_helix_angle);
  cos_ = std::cos(zone.base_helix_angle);
  sin_ = std::sin(zone.base_helix_angle);
  sign_ = static_cast<double>(zone.drive_sign);
  x_start_ = -0.5 * zone.length - zone.pitch_point_offset;
  x_end_ = x_start_ + zone.length;

  if (profile_.is_constant()) {
    const double k = profile_.start_values()[0];
    segments_.push_back(Segment{x_start_, x_end_, k, k});
  } else {
    const std::vector<double>& knots = profile_.knots();
    const double slack = 1e-9 * zone.length;
    GEARDYN_THROW_UNLESS(knots.front() <= slack && knots.back() >= zone.length - slack,
                         "profile: its knots cover [" << knots.front() << ", " << knots.back()
                                                      << "] m of roll distance but the zone of "
                                                         "action needs [0, "
                                                      << zone.length << "] m");
    for (int i = 0; i < profile_.num_segments(); ++i) {
      // Clip to [0, g_α]; the end segments extend linearly over round-off short of the ends.
      const double lo = (i == 0) ? 0.0 : std::max(knots[i], 0.0);
      const double hi =
          (i == profile_.num_segments() - 1) ? zone.length : std::min(knots[i + 1], zone.length);
      if (hi <= lo) continue;
      const double k0 = profile_.start_values()[i];
      const double k1 = profile_.end_values()[i];
      const double slope = (k1 - k0) / (knots[i + 1] - knots[i]);
      segments_.push_back(Segment{x_start_ + lo, x_start_ + hi, k0 + slope * (lo - knots[i]),
                                  k0 + slope * (hi - knots[i])});
    }
    GEARDYN_DEMAND(!segments_.empty());
  }
}

void ContactLineModel::AddLine(double x_line, double y_min, double y_max,
                               ContactLineIntegrals* sums) const {
  // Adds ∫ over σ ∈ [σa, σb] with k linear from ka to kb (closed forms, exact):
  //   ∫k = Δ(ka + kb)/2, ∫kσ = Δ[ka(2σa + σb) + kb(σa + 2σb)]/6,
  //   ∫kσ² = Δ[ka(3σa² + 2σaσb + σb²) + kb(σa² + 2σaσb + 3σb²)]/12.
  auto add = [&](double ya, double yb, double ka, double kb) {
    const double sa = sign_ * (ya / cos_ - x_line * sin_);  // σ = s(y/cos β_b − x_j sin β_b)
    const double sb = sign_ * (yb / cos_ - x_line * sin_);
    const double d = (yb - ya) / cos_;  // dℓ = dy/cos β_b
    sums->length += d;
    sums->stiffness += 0.5 * d * (ka + kb);
    sums->first_moment += d / 6.0 * (ka * (2.0 * sa + sb) + kb * (sa + 2.0 * sb));
    sums->second_moment += d / 12.0 *
                           (ka * (3.0 * sa * sa + 2.0 * sa * sb + sb * sb) +
                            kb * (sa * sa + 2.0 * sa * sb + 3.0 * sb * sb));
  };
  if (tan_ == 0.0) {
    // Spur: the whole face at roll x_line, if x_s ≤ x_line < x_e (right-continuous in θ).
    if (x_line < x_start_ || x_line >= x_end_) return;
    const double ya = std::max(-b_, y_min), yb = std::min(b_, y_max);
    if (!(yb > ya)) return;
    for (const Segment& s : segments_) {
      if (x_line < s.x_end || &s == &segments_.back()) {
        const double k = s.KAt(x_line);
        add(ya, yb, k, k);
        ++sums->num_lines;
        return;
      }
    }
    return;
  }
  // Helical: x = x_line − y tan β_b; the y-range where x ∈ [xa, xb] is [(x_line − xb)/t,
  // (x_line − xa)/t] (swapped for t < 0), clipped to the face [−b, b].
  auto y_range = [&](double xa, double xb, double* lo, double* hi) {
    const double y1 = (x_line - xb) / tan_;
    const double y2 = (x_line - xa) / tan_;
    *lo = std::max(std::max(-b_, y_min), std::min(y1, y2));
    *hi = std::min(std::min(b_, y_max), std::max(y1, y2));
  };
  double lo = 0.0, hi = 0.0;
  y_range(x_start_, x_end_, &lo, &hi);
  if (!(hi > lo)) return;
  ++sums->num_lines;
  if (segments_.size() == 1) {
    const Segment& s = segments_.front();
    add(lo, hi, s.KAt(x_line - lo * tan_), s.KAt(x_line - hi * tan_));
    return;
  }
  for (const Segment& s : segments_) {
    double slo = 0.0, shi = 0.0;
    y_range(s.x_begin, s.x_end, &slo, &shi);
    slo = std::max(slo, lo);
    shi = std::min(shi, hi);
    if (shi > slo) add(slo, shi, s.KAt(x_line - slo * tan_), s.KAt(x_line - shi * tan_));
  }
}

void ContactLineModel::LinesNear(double theta, double* phase, long* j_min, long* j_max) const {
  GEARDYN_THROW_UNLESS(std::isfinite(theta),
                       "CalcIntegrals: theta = " << theta << " is not finite");
  const double p = zone_.transverse_base_pitch;
  *phase = WrapMeshPhase(theta) / kTwoPi;    // x_j = (phase + j) p_bt
  const double reach = b_ * std::abs(tan_);  // a line spans x_j ± b|tan β_b|
  *j_min = static_cast<long>(std::floor((x_start_ - reach) / p - *phase)) - 1;
  *j_max = static_cast<long>(std::ceil((x_end_ + reach) / p - *phase)) + 1;
}

ContactLineIntegrals ContactLineModel::CalcIntegrals(double theta) const {
  double phase = 0.0;
  long j_min = 0, j_max = 0;
  LinesNear(theta, &phase, &j_min, &j_max);
  const double p = zone_.transverse_base_pitch;
  ContactLineIntegrals sums;
  for (long j = j_min; j <= j_max; ++j) {
    AddLine((phase + static_cast<double>(j)) * p, -b_, b_, &sums);
  }
  return sums;
}

ContactLineIntegrals ContactLineModel::CalcIntegrals(double theta, double sigma_min,
                                                     double sigma_max) const {
  GEARDYN_THROW_UNLESS(
      std::isfinite(sigma_min) && std::isfinite(sigma_max),
      "CalcIntegrals: sigma band [" << sigma_min << ", " << sigma_max << "] m is not finite");
  double phase = 0.0;
  long j_min = 0, j_max = 0;
  LinesNear(theta, &phase, &j_min, &j_max);
  const double p = zone_.transverse_base_pitch;
  // On line x_j: σ = s(y/cos β_b − x_j sin β_b) ⇔ y = cos β_b (s σ + x_j sin β_b); s σ ranges
  // over [σ_min, σ_max] (s = +1) or [−σ_max, −σ_min] (s = −1).
  const double t_lo = sign_ > 0.0 ? sigma_min : -sigma_max;
  const double t_hi = sign_ > 0.0 ? sigma_max : -sigma_min;
  ContactLineIntegrals sums;
  for (long j = j_min; j <= j_max; ++j) {
    const double x_line = (phase + static_cast<double>(j)) * p;
    AddLine(x_line, cos_ * (t_lo + x_line * sin_), cos_ * (t_hi + x_line * sin_), &sums);
  }
  return sums;
}

Vector2 ContactLineModel::SigmaRange() const {
  double lo = std::numeric_limits<double>::infinity();
  double hi = -lo;
  for (double x : {x_start_, x_end_}) {
    for (double y : {-b_, b_}) {
      const double sigma = sign_ * (-x * sin_ + y * cos_);
      lo = std::min(lo, sigma);
      hi = std::max(hi, sigma);
    }
  }
  return Vector2(lo, hi);
}

MeshParameters ContactLineModel::CalcMeshParameters(double theta) const {
  const ContactLineIntegrals s = CalcIntegrals(theta);
  return MeshParametersFromChannels(s.stiffness, s.first_moment, s.second_moment, b_);
}

void ContactLineModel::CalcChannels(double theta, Eigen::Ref<VectorX> out) const {
  GEARDYN_CHECK_SIZE(out.size(), kNumMeshChannels, "CalcChannels: out");
  const ContactLineIntegrals s = CalcIntegrals(theta);
  out[kMeshStiffnessChannel] = s.stiffness;
  out[kMeshFirstMomentChannel] = s.first_moment;
  out[kMeshSecondMomentChannel] = s.second_moment;
}

std::vector<double> ContactLineModel::Breakpoints() const {
  std::vector<double> events = {x_start_, x_end_};
  for (size_t i = 1; i < segments_.size(); ++i) events.push_back(segments_[i].x_begin);
  const double reach = b_ * tan_;
  std::vector<double> breaks;
  for (double c : events) {
    for (double x : {c - reach, c + reach}) {
      // x_j(θ) = (θ/2π + j) p_bt = x  ⇒  θ = 2π frac(x/p_bt).
      const double u = x / zone_.transverse_base_pitch;
      double t = kTwoPi * (u - std::floor(u));
      if (t >= kTwoPi - kBreakpointMerge) t = 0.0;
      breaks.push_back(t);
    }
  }
  std::sort(breaks.begin(), breaks.end());
  std::vector<double> merged;
  for (double t : breaks) {
    if (merged.empty() || t - merged.back() > kBreakpointMerge) merged.push_back(t);
  }
  // The last one may sit within the merge distance of the first one + 2π.
  if (merged.size() > 1 && merged.front() + kTwoPi - merged.back() <= kBreakpointMerge) {
    merged.pop_back();
  }
  return merged;
}

// ---------------------------------------------------------------- coefficient builders

PiecewiseConstantCoefficient MakePiecewiseConstantMeshCoefficient(const ContactLineModel& model) {
  GEARDYN_THROW_UNLESS(model.is_piecewise_constant(),
                       "model: the mesh parameters are piecewise constant only for a spur zone "
                       "(zone.base_helix_angle = "
                           << model.zone().base_helix_angle
                           << ") with a piecewise-constant stiffness profile");
  std::vector<double> breaks = model.Breakpoints();
  if (breaks.empty()) breaks.push_back(0.0);
  std::vector<double> starts;
  std::vector<VectorX> columns;
  VectorX value(kNumMeshChannels);
  for (size_t k = 0; k < breaks.size(); ++k) {
    const double a = breaks[k];
    const double b = k + 1 < breaks.size() ? breaks[k + 1] : breaks[0] + kTwoPi;
    model.CalcChannels(0.5 * (a + b), value);  // the value on the open interval
    const double scale = std::max(std::abs(value[0]), 1e-300);
    if (!columns.empty()) {
      // Merge with the previous interval when equal to round-off (channel c scaled by K b^c).
      bool same = true;
      double s = scale;
      for (int c = 0; c < kNumMeshChannels; ++c) {
        same = same && std::abs(value[c] - columns.back()[c]) <= 1e-13 * s;
        s *= model.half_face_width();
      }
      if (same) continue;
    }
    starts.push_back(a);
    columns.push_back(value);
  }
  // The last interval wraps into the first: merge them when equal.
  if (columns.size() > 1) {
    bool same = true;
    double s = std::max(std::abs(columns.front()[0]), 1e-300);
    for (int c = 0; c < kNumMeshChannels; ++c) {
      same = same && std::abs(columns.front()[c] - columns.back()[c]) <= 1e-13 * s;
      s *= model.half_face_width();
    }
    if (same) {
      starts.erase(starts.begin());
      columns.erase(columns.begin());
    }
  }
  VectorX bp(static_cast<Eigen::Index>(starts.size()));
  MatrixX values(kNumMeshChannels, static_cast<Eigen::Index>(starts.size()));
  for (size_t k = 0; k < starts.size(); ++k) {
    bp[static_cast<Eigen::Index>(k)] = starts[k];
    values.col(static_cast<Eigen::Index>(k)) = columns[k];
  }
  return PiecewiseConstantCoefficient(std::move(bp), std::move(values));
}

FourierCoefficient MakeFourierMeshCoefficient(const ContactLineModel& model, int num_terms) {
  GEARDYN_THROW_UNLESS(num_terms >= 0, "num_terms: must be >= 0, got " << num_terms);
  const std::vector<PolyPiece> pieces = BuildPieces(model);
  MatrixXc harmonics(kNumMeshChannels, num_terms);
  for (int n = 1; n <= num_terms; ++n) harmonics.col(n - 1) = PieceSeriesCoefficient(pieces, n);
  return FourierCoefficient(PieceMean(pieces), std::move(harmonics));
}

FourierFit MakeFourierMeshCoefficientWithTolerance(const ContactLineModel& model, double rel_tol,
                                                   int max_terms) {
  GEARDYN_THROW_UNLESS(std::isfinite(rel_tol) && rel_tol > 0.0,
                       "rel_tol: must be finite and > 0, got " << rel_tol);
  GEARDYN_THROW_UNLESS(max_terms >= 0, "max_terms: must be >= 0, got " << max_terms);
  const std::vector<PolyPiece> pieces = BuildPieces(model);
  const VectorX mean = PieceMean(pieces);
  const VectorX variation = PieceVariation(pieces, mean);
  // Channels whose variation is round-off (relative 1e-13 of K̄ b^c) count as constant.
  VectorX floor_energy(kNumMeshChannels);
  double scale = std::abs(mean[kMeshStiffnessChannel]);
  for (int c = 0; c < kNumMeshChannels; ++c) {
    floor_energy[c] = 1e-26 * scale * scale;
    scale *= model.half_face_width();
  }
  std::array<long double, kNumMeshChannels> partial{};
  auto error_now = [&]() {
    double e = 0.0;
    for (int c = 0; c < kNumMeshChannels; ++c) {
      if (variation[c] <= floor_energy[c]) continue;
      const long double tail = std::max(0.0L, static_cast<long double>(variation[c]) - partial[c]);
      e = std::max(e, static_cast<double>(std::sqrt(tail / variation[c])));
    }
    return e;
  };
  std::vector<Eigen::Matrix<Complex, kNumMeshChannels, 1>> columns;
  double error = error_now();
  while (error > rel_tol && static_cast<int>(columns.size()) < max_terms) {
    columns.push_back(PieceSeriesCoefficient(pieces, static_cast<int>(columns.size()) + 1));
    for (int c = 0; c < kNumMeshChannels; ++c) {
      partial[c] += 2.0L * static_cast<long double>(std::norm(columns.back()[c]));
    }
    error = error_now();
  }
  const int n_terms = static_cast<int>(columns.size());
  MatrixXc harmonics(kNumMeshChannels, n_terms);
  for (int n = 0; n < n_terms; ++n) harmonics.col(n) = columns[n];
  return FourierFit{FourierCoefficient(mean, std::move(harmonics)), n_terms, error,
                    error <= rel_tol};
}

TableCoefficient MakeTableMeshCoefficient(const ContactLineModel& model, int num_samples) {
  GEARDYN_THROW_UNLESS(num_samples >= 1, "num_samples: must be >= 1, got " << num_samples);
  MatrixX samples(kNumMeshChannels, num_samples);
  for (int s = 0; s < num_samples; ++s) {
    model.CalcChannels(kTwoPi * s / num_samples, samples.col(s));
  }
  return TableCoefficient(std::move(samples));
}

bool MeshCoefficientOptions::IsValid(std::string* why) const {
  std::ostringstream msg;
  if (num_terms < 0) {
    msg << "num_terms: must be >= 0, got " << num_terms;
  } else if (!(std::isfinite(rel_tol) && rel_tol > 0.0)) {
    msg << "rel_tol: must be finite and > 0, got " << rel_tol;
  } else if (max_terms < 0) {
    msg << "max_terms: must be >= 0, got " << max_terms;
  } else if (num_samples < 1) {
    msg << "num_samples: must be >= 1, got " << num_samples;
  } else {
    return true;
  }
  if (why != nullptr) *why = msg.str();
  return false;
}

Coefficient MakeMeshCoefficient(const ContactLineModel& model,
                                const MeshCoefficientOptions& options) {
  std::string why;
  GEARDYN_THROW_UNLESS(options.IsValid(&why), why);
  switch (options.form) {
    case MeshCoefficientForm::kPiecewiseConstant:
      return MakePiecewiseConstantMeshCoefficient(model);
    case MeshCoefficientForm::kTable:
      return MakeTableMeshCoefficient(model, options.num_samples);
    case MeshCoefficientForm::kFourier:
      if (options.num_terms > 0) return MakeFourierMeshCoefficient(model, options.num_terms);
      return MakeFourierMeshCoefficientWithTolerance(model, options.rel_tol, options.max_terms)
          .fourier;
    case MeshCoefficientForm::kAuto: {
      const std::vector<PolyPiece> pieces = BuildPieces(model);
      const VectorX mean = PieceMean(pieces);
      if (PiecesAreConstant(model, pieces, mean)) return ConstantCoefficient(mean);
      if (model.is_piecewise_constant()) return MakePiecewiseConstantMeshCoefficient(model);
      if (options.num_terms > 0) return MakeFourierMeshCoefficient(model, options.num_terms);
      return MakeFourierMeshCoefficientWithTolerance(model, options.rel_tol, options.max_terms)
          .fourier;
    }
  }
  GEARDYN_DEMAND(false);
  return ConstantCoefficient(VectorX::Zero(kNumMeshChannels));
}

}  // namespace geardyn
