// Reading the [oscillator] table: the dimensionless oscillator of Kahraman & Singh (1990) and
// Blankenship & Kahraman (1995) (docs/scene-format.md "Oscillator scenes").
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "scene/section_readers.hpp"
#include "scene/suggestions.hpp"
#include "scene/toml_fields.hpp"

namespace geardyn::internal {

OscillatorDef ReadOscillator(const ErrorContext& ctx, const toml::table& t) {
  const Fields f(ctx, t, "oscillator");
  f.CheckKnown({"zeta", "alpha", "mean_force", "alternating_force", "force_phase_deg", "backlash",
                "back_contact", "model", "frequency_ratio"});
  OscillatorDef def;
  def.line = ctx.Line(&t);
  if (auto zeta = f.OptNumber("zeta")) {
    f.NonNegative("zeta", *zeta);
    def.zeta = zeta->value;
  }
  if (auto alpha = f.OptNumber("alpha")) {
    if (!(std::abs(alpha->value) < 1.0)) {
      f.Fail("alpha",
             "the parametric stiffness amplitude must satisfy |alpha| < 1 (the stiffness "
             "1 + alpha cos stays positive), got " +
                 FormatNumber(alpha->value));
    }
    def.alpha = alpha->value;
  }
  if (auto fm = f.OptNumber("mean_force")) def.mean_force = fm->value;
  if (auto fa = f.OptNumber("alternating_force")) def.alternating_force = fa->value;
  if (auto phase = f.OptNumber("force_phase_deg")) {
    def.force_phase = phase->value * std::numbers::pi / 180.0;
  }
  if (auto ratio = f.OptNumber("frequency_ratio")) {
    f.Positive("frequency_ratio", *ratio);
    def.frequency_ratio = ratio->value;
  }
  if (auto backlash = f.OptBool("backlash")) def.backlash = *backlash;
  if (auto back = f.OptBool("back_contact")) {
    if (!def.backlash && !*back) {
      f.Fail("back_contact",
             "back_contact = false needs backlash = true (without backlash the "
             "oscillator is linear and has no flanks)");
    }
    def.back_contact = *back;
  }
  def.model = def.backlash ? OscillatorModel::kSlices : OscillatorModel::kTorsional;
  if (auto name = f.OptString("model")) {
    const std::vector<std::string> names = {"slices", "torsional", "lti"};
    if (*name == "slices") {
      def.model = OscillatorModel::kSlices;
    } else if (*name == "torsional") {
      def.model = OscillatorModel::kTorsional;
    } else if (*name == "lti") {
      def.model = OscillatorModel::kLti;
    } else {
      f.Fail("model", "unknown model '" + *name + "'" + DidYouMean(*name, names) +
                          "; models: " + JoinNames(names));
    }
    if (def.model == OscillatorModel::kSlices && !def.backlash) {
      f.Fail("model",
             "\"slices\" is the clearance model, but the oscillator has backlash = false "
             "(use \"torsional\" or \"lti\", or backlash = true)");
    }
  }
  return def;
}

}  // namespace geardyn::internal
