// Reading the optional top-level [damping] table: system modal or Rayleigh damping.
#include "scene/section_readers.hpp"
#include "scene/toml_fields.hpp"

namespace geardyn::internal {
namespace {

// ζ ∈ [0, 1) under `key` (`subject` names an entry of a list).
void CheckRatio(const Fields& f, std::string_view key, const Number& n,
                const std::string& subject = {}) {
  if (!(n.value >= 0.0 && n.value < 1.0)) {
    f.context().Fail(n.node, f.Key(key),
                     subject + "must be a damping ratio in [0, 1), got " + FormatNumber(n.value));
  }
}

}  // namespace

SystemDamping ReadSystemDamping(const ErrorContext& ctx, const toml::table& root) {
  SystemDamping d;
  const toml::node* n = root.get("damping");
  if (n == nullptr) return d;
  const toml::table* t = n->as_table();
  if (t == nullptr) ctx.Fail(n, "damping", "must be a table ([damping]), got " + Describe(*n));
  const Fields f(ctx, *t, "damping");
  f.CheckKnown({"modal_ratio", "modal_ratios", "rayleigh_alpha", "rayleigh_beta"});
  if (auto zeta = f.OptNumber("modal_ratio")) {
    CheckRatio(f, "modal_ratio", *zeta);
    d.modal_ratio = zeta->value;
  }
  if (auto list = f.OptNumberArray("modal_ratios")) {
    if (list->empty()) f.Fail("modal_ratios", "must list at least one damping ratio");
    for (std::size_t r = 0; r < list->size(); ++r) {
      CheckRatio(f, "modal_ratios", (*list)[r], "entry " + std::to_string(r) + " ");
      d.modal_ratios.push_back((*list)[r].value);
    }
  }
  if (auto alpha = f.OptNumber("rayleigh_alpha")) {
    f.NonNegative("rayleigh_alpha", *alpha);
    d.rayleigh_alpha = alpha->value;
  }
  if (auto beta = f.OptNumber("rayleigh_beta")) {
    f.NonNegative("rayleigh_beta", *beta);
    d.rayleigh_beta = beta->value;
  }
  const bool rayleigh = f.Find("rayleigh_alpha") != nullptr || f.Find("rayleigh_beta") != nullptr;
  if (rayleigh && d.has_modal()) {
    f.Fail(f.Find("rayleigh_alpha") != nullptr ? "rayleigh_alpha" : "rayleigh_beta",
           "give either modal damping (modal_ratio, modal_ratios) or Rayleigh damping "
           "(rayleigh_alpha, rayleigh_beta), not both");
  }
  return d;
}

}  // namespace geardyn::internal
