// Reading [mesh.modifications] (flank modifications) and [mesh.errors] (tooth-to-tooth errors).
#include <algorithm>
#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "geardyn/common/units.hpp"
#include "scene/mesh_model_reader.hpp"
#include "scene/suggestions.hpp"

namespace geardyn::internal {
namespace {

/// Relative closure tolerance of Σ f_p, the same as UnloadedSeparation's.
/// 1e-6 of Σ|f_p|: entries rounded to 7 significant digits (a mean-free list printed with %.6e)
/// leave |Σ f_p| ≤ 5e-7 Σ|f_p| and must pass (1e-9 rejected them with advice that rounding undoes);
/// the residual only changes the pitch of tooth 0 by that much. A list that does not close is off
/// by a sizeable fraction of Σ|f_p|.
constexpr double kClosureTol = 1e-6;

// A deviation-like amount [m]: at most kMaxDeviation in magnitude, ≥ 0 unless `is_signed`.
void CheckDeviation(const Fields& f, std::string_view key, const Number& n, bool is_signed) {
  if (!is_signed) f.NonNegative(key, n);
  if (std::abs(n.value) > kMaxDeviation) {
    f.context().Fail(n.node, f.Key(key),
                     "must be at most " + FormatNumber(kMaxDeviation) +
                         " m in magnitude (deviations are in metres: 20 um is 2e-05), got " +
                         FormatNumber(n.value));
  }
}

ReliefShape ReadShape(const Fields& f) {
  const std::optional<std::string> name = f.OptString("relief_shape");
  if (!name || *name == "linear") return ReliefShape::kLinear;
  if (*name == "parabolic") return ReliefShape::kParabolic;
  const std::vector<std::string> names = {"linear", "parabolic"};
  f.Fail("relief_shape", "unknown shape '" + *name + "'" + DidYouMean(*name, names) +
                             "; shapes: " + JoinNames(names));
}

// One relief band: `key` (amount) and `key`_length, both or neither.
ProfileRelief ReadRelief(const Fields& f, const std::string& key, ReliefShape shape,
                         double path_length) {
  const std::string length_key = key + "_length";
  const std::optional<Number> amount = f.OptNumber(key);
  const std::optional<Number> length = f.OptNumber(length_key);
  if (amount && !length) {
    f.Fail(key,
           "needs " + length_key + " too (the extent of the relief along the path of contact, m)");
  }
  if (length && !amount) f.Fail(length_key, "given without the relief amount " + key);
  if (!amount) return {};
  CheckDeviation(f, key, *amount, false);
  f.Positive(length_key, *length);
  if (length->value > path_length) {
    f.Fail(length_key, "must be at most the length of the path of contact g_alpha = " +
                           FormatNumber(path_length) + " m, got " + FormatNumber(length->value));
  }
  return {amount->value, length->value, shape};
}

// Single pitch deviations of one member: z entries, each a deviation, summing to zero.
std::vector<double> ReadPitchDeviations(const Fields& f, const std::string& key,
                                        const GearDef& member, const char* role) {
  const std::optional<std::vector<Number>> entries = f.OptNumberArray(key);
  if (!entries) return {};
  const int z = member.blank.teeth;
  if (static_cast<int>(entries->size()) != z) {
    f.Fail(key, "must have one entry per tooth of the " + std::string(role) + " '" + member.name +
                    "': " + std::to_string(z) + " entries (z = " + std::to_string(z) + "), got " +
                    std::to_string(entries->size()));
  }
  std::vector<double> values;
  double sum = 0.0, sum_abs = 0.0;
  for (std::size_t i = 0; i < entries->size(); ++i) {
    const Number& e = (*entries)[i];
    if (std::abs(e.value) > kMaxDeviation) {
      f.context().Fail(e.node, f.Key(key),
                       "entry " + std::to_string(i) + " must be at most " +
                           FormatNumber(kMaxDeviation) +
                           " m in magnitude (deviations are in metres: 5 um is 5e-06), got " +
                           FormatNumber(e.value));
    }
    values.push_back(e.value);
    sum += e.value;
    sum_abs += std::abs(e.value);
  }
  if (std::abs(sum) > kClosureTol * sum_abs) {
    f.Fail(key, "the single pitch deviations of a closed gear sum to zero, got " +
                    FormatNumber(sum) + " m (subtract the mean " + FormatNumber(sum / z) +
                    " m from each entry)");
  }
  return values;
}

// A runout (eccentricity, ≥ 0) and its phase in degrees; the phase needs the runout.
void ReadRunout(const Fields& f, const std::string& key, double* runout, double* phase) {
  const std::string phase_key = key + "_phase_deg";
  const std::optional<Number> r = f.OptNumber(key);
  const std::optional<Number> p = f.OptNumber(phase_key);
  if (p && !r) f.Fail(phase_key, "given without the runout " + key);
  if (r) {
    CheckDeviation(f, key, *r, false);
    *runout = r->value;
  }
  if (p) *phase = DegToRad(p->value);
}

}  // namespace

bool HasUnloadedSeparation(const ToothModifications& m, const ToothErrors& e) {
  const auto any = [](const std::vector<double>& v) {
    return std::any_of(v.begin(), v.end(), [](double x) { return x != 0.0; });
  };
  return m.pinion_tip_relief.is_active() || m.gear_tip_relief.is_active() ||
         m.pinion_root_relief.is_active() || m.gear_root_relief.is_active() ||
         m.lead_crowning != 0.0 || m.lead_slope != 0.0 || any(e.pinion_pitch_deviations) ||
         any(e.gear_pitch_deviations) || e.pinion_runout != 0.0 || e.gear_runout != 0.0;
}

ToothModifications ReadToothModifications(const Fields& f, const GearPairGeometry& geometry) {
  f.CheckKnown({"pinion_tip_relief", "pinion_tip_relief_length", "gear_tip_relief",
                "gear_tip_relief_length", "pinion_root_relief", "pinion_root_relief_length",
                "gear_root_relief", "gear_root_relief_length", "relief_shape", "lead_crowning",
                "lead_slope"});
  const ReliefShape shape = ReadShape(f);
  const double g_alpha = geometry.line_of_action_length;
  ToothModifications m;
  m.pinion_tip_relief = ReadRelief(f, "pinion_tip_relief", shape, g_alpha);
  m.gear_tip_relief = ReadRelief(f, "gear_tip_relief", shape, g_alpha);
  m.pinion_root_relief = ReadRelief(f, "pinion_root_relief", shape, g_alpha);
  m.gear_root_relief = ReadRelief(f, "gear_root_relief", shape, g_alpha);
  if (const std::optional<Number> c = f.OptNumber("lead_crowning")) {
    CheckDeviation(f, "lead_crowning", *c, false);
    m.lead_crowning = c->value;
  }
  if (const std::optional<Number> s = f.OptNumber("lead_slope")) {
    CheckDeviation(f, "lead_slope", *s, true);
    m.lead_slope = s->value;
  }
  return m;
}

ToothErrors ReadToothErrors(const Fields& f, const GearDef& pinion, const GearDef& gear) {
  f.CheckKnown({"pinion_pitch_deviations", "gear_pitch_deviations", "pinion_runout",
                "pinion_runout_phase_deg", "gear_runout", "gear_runout_phase_deg"});
  ToothErrors e;
  e.pinion_teeth = pinion.blank.teeth;
  e.gear_teeth = gear.blank.teeth;
  if (gear.blank.kind == GearKind::kRack) {
    // The pinion's errors repeat every z_1 mesh cycles (lcm(z_1, 1)); the rack's never repeat.
    e.gear_teeth = 1;
    for (const char* key : {"gear_pitch_deviations", "gear_runout", "gear_runout_phase_deg"}) {
      if (f.Find(key) != nullptr) {
        f.Fail(key, "'" + gear.name +
                        "' is a rack: its errors do not repeat over a mesh period (no runout, "
                        "pitch deviations along its length are not modelled); give the "
                        "pinion's");
      }
    }
  }
  e.pinion_pitch_deviations = ReadPitchDeviations(f, "pinion_pitch_deviations", pinion, "pinion");
  e.gear_pitch_deviations = ReadPitchDeviations(f, "gear_pitch_deviations", gear, "gear");
  ReadRunout(f, "pinion_runout", &e.pinion_runout, &e.pinion_runout_phase);
  ReadRunout(f, "gear_runout", &e.gear_runout, &e.gear_runout_phase);
  return e;
}

}  // namespace geardyn::internal
