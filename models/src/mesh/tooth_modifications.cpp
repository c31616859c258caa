/// @file
/// @brief The unloaded separation e: flank modifications and tooth-to-tooth errors (spec 01 §3).
#include "geardyn/models/mesh/tooth_modifications.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>

#include "geardyn/common/check.hpp"
#include "geardyn/common/units.hpp"
#include "zone_of_action_checks.hpp"

namespace geardyn {
namespace {

/// Relative closure tolerance of Σ f_p: round-off of the sum of z values of similar size.
/// 1e-6 of Σ|f_p|: entries rounded to 7 significant digits (a mean-free list printed with %.6e)
/// leave |Σ f_p| ≤ 5e-7 Σ|f_p| and must pass (1e-9 rejected them with advice that rounding undoes);
/// the residual only changes the pitch of tooth 0 by that much. A list that does not close is off
/// by a sizeable fraction of Σ|f_p|.
constexpr double kClosureTol = 1e-6;
/// Largest hunting period accepted [mesh cycles] (tables index samples with int).
constexpr std::int64_t kMaxPeriodMeshes = std::int64_t{1} << 31;

void CheckRelief(const ProfileRelief& relief, const std::string& name, double path_length) {
  GEARDYN_THROW_UNLESS(std::isfinite(relief.amount) && relief.amount >= 0.0,
                       name << ".amount: must be finite and >= 0 [m], got " << relief.amount);
  GEARDYN_THROW_UNLESS(std::isfinite(relief.length) && relief.length >= 0.0,
                       name << ".length: must be finite and >= 0 [m], got " << relief.length);
  GEARDYN_THROW_UNLESS(relief.amount == 0.0 || relief.length > 0.0,
                       name << ".length: must be > 0 for a relief amount of " << relief.amount
                            << " m, got " << relief.length);
  GEARDYN_THROW_UNLESS(relief.length <= path_length,
                       name << ".length: " << relief.length
                            << " m is longer than the path of contact g_alpha = " << path_length
                            << " m");
  GEARDYN_THROW_UNLESS(
      relief.shape == ReliefShape::kLinear || relief.shape == ReliefShape::kParabolic,
      name << ".shape: unknown relief shape " << static_cast<int>(relief.shape));
}

/// C·u or C·u² with u = depth/L for depth > 0 (0 outside the band).
double ReliefValue(const ProfileRelief& relief, double depth) {
  if (!relief.is_active() || depth <= 0.0) return 0.0;
  const double u = depth / relief.length;
  return relief.shape == ReliefShape::kLinear ? relief.amount * u : relief.amount * u * u;
}

/// Flank lags F[i] = Σ_{k=1..i} f[k] relative to their mean, after the size and closure checks.
std::vector<double> FlankLags(const std::vector<double>& deviations, int teeth,
                              const std::string& name) {
  if (deviations.empty()) return {};
  GEARDYN_THROW_UNLESS(static_cast<long>(deviations.size()) == teeth,
                       name << ": has " << deviations.size() << " entries but the member has "
                            << teeth << " teeth (one single pitch deviation per tooth)");
  double sum = 0.0, sum_abs = 0.0;
  for (size_t i = 0; i < deviations.size(); ++i) {
    GEARDYN_THROW_UNLESS(std::isfinite(deviations[i]),
                         name << "[" << i << "] = " << deviations[i] << " is not finite");
    sum += deviations[i];
    sum_abs += std::abs(deviations[i]);
  }
  GEARDYN_THROW_UNLESS(std::abs(sum) <= kClosureTol * sum_abs,
                       name << ": the single pitch deviations of a closed gear sum to zero, got "
                            << sum << " m (subtract the mean " << sum / teeth
                            << " m from every entry)");
  std::vector<double> lags(deviations.size(), 0.0);
  for (size_t i = 1; i < deviations.size(); ++i) lags[i] = lags[i - 1] + deviations[i];
  const double mean = std::accumulate(lags.begin(), lags.end(), 0.0) / teeth;
  for (double& f : lags) f -= mean;
  return lags;
}

int PositiveMod(std::int64_t n, int z) {
  const std::int64_t r = n % z;
  return static_cast<int>(r < 0 ? r + z : r);
}

}  // namespace

UnloadedSeparation::UnloadedSeparation(const ZoneOfAction& zone,
                                       const ToothModifications& modifications,
                                       const ToothErrors& errors)
    : zone_(zone), modifications_(modifications), errors_(errors) {
  internal::CheckZoneGeometry(zone);
  // The same expressions as ContactLineModel, so that both agree to the last bit on the ends.
  x_start_ = -0.5 * zone.length - zone.pitch_point_offset;
  x_end_ = x_start_ + zone.length;
  b_ = 0.5 * zone.face_width;
  cos_ = std::cos(zone.base_helix_angle);

  const ToothModifications& m = modifications;
  CheckRelief(m.pinion_tip_relief, "modifications.pinion_tip_relief", zone.length);
  CheckRelief(m.gear_tip_relief, "modifications.gear_tip_relief", zone.length);
  CheckRelief(m.pinion_root_relief, "modifications.pinion_root_relief", zone.length);
  CheckRelief(m.gear_root_relief, "modifications.gear_root_relief", zone.length);
  GEARDYN_THROW_UNLESS(
      std::isfinite(m.lead_crowning) && m.lead_crowning >= 0.0,
      "modifications.lead_crowning: must be finite and >= 0 [m], got " << m.lead_crowning);
  GEARDYN_THROW_UNLESS(std::isfinite(m.lead_slope),
                       "modifications.lead_slope: must be finite [m], got " << m.lead_slope);

  // Inner ends of the relief bands: the kinks of e_profile (strictly inside the path).
  auto add_kink = [&](const ProfileRelief& r, double x) {
    if (r.is_active() && x > x_start_ && x < x_end_) profile_kinks_.push_back(x);
  };
  add_kink(m.pinion_tip_relief, x_end_ - m.pinion_tip_relief.length);
  add_kink(m.gear_root_relief, x_end_ - m.gear_root_relief.length);
  add_kink(m.gear_tip_relief, x_start_ + m.gear_tip_relief.length);
  add_kink(m.pinion_root_relief, x_start_ + m.pinion_root_relief.length);
  std::sort(profile_kinks_.begin(), profile_kinks_.end());
  profile_kinks_.erase(std::unique(profile_kinks_.begin(), profile_kinks_.end()),
                       profile_kinks_.end());

  const ToothErrors& e = errors;
  GEARDYN_THROW_UNLESS(
      std::isfinite(e.pinion_runout) && e.pinion_runout >= 0.0,
      "errors.pinion_runout: must be finite and >= 0 [m], got " << e.pinion_runout);
  GEARDYN_THROW_UNLESS(std::isfinite(e.gear_runout) && e.gear_runout >= 0.0,
                       "errors.gear_runout: must be finite and >= 0 [m], got " << e.gear_runout);
  GEARDYN_THROW_UNLESS(
      std::isfinite(e.pinion_runout_phase),
      "errors.pinion_runout_phase: must be finite [rad], got " << e.pinion_runout_phase);
  GEARDYN_THROW_UNLESS(
      std::isfinite(e.gear_runout_phase),
      "errors.gear_runout_phase: must be finite [rad], got " << e.gear_runout_phase);
  const bool any_pitch =
      std::any_of(e.pinion_pitch_deviations.begin(), e.pinion_pitch_deviations.end(),
                  [](double f) { return f != 0.0; }) ||
      std::any_of(e.gear_pitch_deviations.begin(), e.gear_pitch_deviations.end(),
                  [](double f) { return f != 0.0; });
  has_tooth_errors_ = any_pitch || e.pinion_runout > 0.0 || e.gear_runout > 0.0;
  const bool needs_teeth =
      has_tooth_errors_ || !e.pinion_pitch_deviations.empty() || !e.gear_pitch_deviations.empty();
  if (needs_teeth) {
    GEARDYN_THROW_UNLESS(e.pinion_teeth >= 1,
                         "errors.pinion_teeth: must be >= 1 when tooth-to-tooth errors are "
                         "given, got "
                             << e.pinion_teeth);
    GEARDYN_THROW_UNLESS(
        e.gear_teeth >= 1,
        "errors.gear_teeth: must be >= 1 when tooth-to-tooth errors are given, got "
            << e.gear_teeth);
  }
  pinion_lags_ =
      FlankLags(e.pinion_pitch_deviations, e.pinion_teeth, "errors.pinion_pitch_deviations");
  gear_lags_ = FlankLags(e.gear_pitch_deviations, e.gear_teeth, "errors.gear_pitch_deviations");
  if (has_tooth_errors_) {
    period_meshes_ = std::lcm(std::int64_t{e.pinion_teeth}, std::int64_t{e.gear_teeth});
    GEARDYN_THROW_UNLESS(period_meshes_ <= kMaxPeriodMeshes,
                         "errors: the hunting period lcm(pinion_teeth, gear_teeth) = "
                             << period_meshes_ << " mesh cycles exceeds " << kMaxPeriodMeshes);
  }
}

bool UnloadedSeparation::has_flank_modifications() const {
  const ToothModifications& m = modifications_;
  return m.pinion_tip_relief.is_active() || m.gear_tip_relief.is_active() ||
         m.pinion_root_relief.is_active() || m.gear_root_relief.is_active() ||
         m.lead_crowning != 0.0 || m.lead_slope != 0.0;
}

double UnloadedSeparation::ProfileSeparation(double roll) const {
  const ToothModifications& m = modifications_;
  // Depth into each band, measured from its inner end toward the path end it touches.
  return ReliefValue(m.pinion_tip_relief, roll - (x_end_ - m.pinion_tip_relief.length)) +
         ReliefValue(m.gear_root_relief, roll - (x_end_ - m.gear_root_relief.length)) +
         ReliefValue(m.gear_tip_relief, (x_start_ + m.gear_tip_relief.length) - roll) +
         ReliefValue(m.pinion_root_relief, (x_start_ + m.pinion_root_relief.length) - roll);
}

double UnloadedSeparation::LeadSeparation(double face) const {
  const double u = face / b_;
  return modifications_.lead_crowning * u * u + 0.5 * modifications_.lead_slope * u;
}

double UnloadedSeparation::ToothPairSeparation(std::int64_t cycle) const {
  double lag = 0.0;
  if (!pinion_lags_.empty()) lag += pinion_lags_[PinionTooth(cycle)];
  if (!gear_lags_.empty()) lag -= gear_lags_[GearTooth(cycle)];
  return cos_ * lag;
}

double UnloadedSeparation::RunoutSeparation(double theta) const {
  const ToothErrors& e = errors_;
  double d = 0.0;
  if (e.pinion_runout > 0.0) {
    d -= e.pinion_runout * std::cos(theta / e.pinion_teeth + e.pinion_runout_phase);
  }
  if (e.gear_runout > 0.0) {
    d += e.gear_runout * std::cos(theta / e.gear_teeth + e.gear_runout_phase);
  }
  return cos_ * d;
}

double UnloadedSeparation::Separation(double roll, double face, std::int64_t cycle,
                                      double theta) const {
  return ProfileSeparation(roll) + LeadSeparation(face) + ToothPairSeparation(cycle) +
         RunoutSeparation(theta);
}

int UnloadedSeparation::PinionTooth(std::int64_t cycle) const {
  GEARDYN_THROW_UNLESS(errors_.pinion_teeth >= 1,
                       "errors.pinion_teeth: must be >= 1, got " << errors_.pinion_teeth);
  return PositiveMod(cycle, errors_.pinion_teeth);
}

int UnloadedSeparation::GearTooth(std::int64_t cycle) const {
  GEARDYN_THROW_UNLESS(errors_.gear_teeth >= 1,
                       "errors.gear_teeth: must be >= 1, got " << errors_.gear_teeth);
  return PositiveMod(cycle, errors_.gear_teeth);
}

}  // namespace geardyn
