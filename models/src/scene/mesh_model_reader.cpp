// Reading the mesh model of one [[mesh]] table: level, stiffness source, damping, coefficient
// options, and the sub-tables (tooth_data_reader.cpp, mesh_parameters_reader.cpp).
#include "scene/mesh_model_reader.hpp"

#include <array>
#include <cmath>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "scene/suggestions.hpp"

namespace geardyn::internal {
namespace {

constexpr int kMaxSlices = 10000;
constexpr int kMaxFourierTerms = 1 << 16;
constexpr int kMaxTableSamples = 1 << 20;
/// Below this a stiffness per unit length is a probable N/(mm·µm) value (1 N/(mm·µm) = 1e9 N/m²;
/// steel pairs have about 2e10 N/m², plastics a few 1e8 N/m²).
constexpr double kMinStiffnessPerLength = 1e6;

constexpr std::array<MeshModelLevel, 8> kLevels = {
    MeshModelLevel::kBlankenshipSingh, MeshModelLevel::kBsProjected, MeshModelLevel::kFiveDof,
    MeshModelLevel::kCoupling4Dof,     MeshModelLevel::kMeanLti,     MeshModelLevel::kTorsional,
    MeshModelLevel::kNonlinearSlices,  MeshModelLevel::kContact};

struct FormName {
  std::string_view name;
  MeshCoefficientForm form;
};
constexpr std::array<FormName, 4> kForms = {
    {{"auto", MeshCoefficientForm::kAuto},
     {"piecewise_constant", MeshCoefficientForm::kPiecewiseConstant},
     {"fourier", MeshCoefficientForm::kFourier},
     {"table", MeshCoefficientForm::kTable}}};

MeshModelLevel ReadLevel(const Fields& f) {
  const std::optional<std::string> name = f.OptString("model");
  if (!name) return MeshModelLevel::kBlankenshipSingh;
  if (const std::optional<MeshModelLevel> level = ParseMeshModelLevel(*name)) return *level;
  std::vector<std::string> names;
  for (const MeshModelLevel level : kLevels) names.emplace_back(ToString(level));
  f.Fail("model", "unknown model '" + *name + "'" + DidYouMean(*name, names) +
                      "; models: " + JoinNames(names));
}

std::string_view FormNameOf(MeshCoefficientForm form) {
  for (const FormName& f : kForms) {
    if (f.form == form) return f.name;
  }
  return "auto";
}

MeshCoefficientForm ReadForm(const Fields& f, const GearDef& pinion) {
  const std::optional<std::string> name = f.OptString("coefficient_form");
  if (!name) return MeshCoefficientForm::kAuto;
  std::vector<std::string_view> names;
  for (const FormName& form : kForms) {
    if (form.name == *name) {
      if (form.form == MeshCoefficientForm::kPiecewiseConstant && pinion.helix_angle != 0.0) {
        f.Fail("coefficient_form",
               "\"piecewise_constant\" needs a spur pair (helical contact lines give smooth "
               "coefficients); use \"auto\", \"fourier\" or \"table\"");
      }
      return form.form;
    }
    names.push_back(form.name);
  }
  f.Fail("coefficient_form", "unknown form '" + *name + "'" + DidYouMean(*name, names) +
                                 "; forms: " + JoinNames(names));
}

// Reads the damping: a ratio or a coefficient, not both.
MeshDamping ReadDamping(const Fields& f) {
  const std::optional<Number> ratio = f.OptNumber("damping_ratio");
  const std::optional<Number> coefficient = f.OptNumber("damping");
  if (ratio && coefficient) {
    f.Fail("damping", "give either damping_ratio or damping (the coefficient), not both");
  }
  if (ratio) {
    f.NonNegative("damping_ratio", *ratio);
    return MeshDamping::FromRatio(ratio->value);
  }
  if (coefficient) {
    f.NonNegative("damping", *coefficient);
    return MeshDamping::FromCoefficient(coefficient->value);
  }
  return MeshDamping::None();
}

// Keys of the contact-line levels that the tooth-contact model does not use (it has its own law,
// damping and flank geometry: [mesh.contact]).
constexpr std::array<std::string_view, 10> kNotContactKeys = {
    "stiffness_per_length", "damping_ratio", "damping", "coefficient_form", "fourier_terms",
    "fourier_tolerance",    "table_samples", "slices",  "parameters",       "errors"};

// Keys that configure the contact-line model, rejected next to [mesh.parameters].
constexpr std::array<std::string_view, 8> kContactLineKeys = {
    "stiffness_per_length", "coefficient_form", "fourier_terms", "fourier_tolerance",
    "table_samples",        "slices",           "modifications", "errors"};

}  // namespace

MeshModelDef ReadMeshModel(const Fields& f, const GearDef& pinion, const GearDef& gear,
                           const GearPairGeometry& geometry) {
  MeshModelDef def;
  def.level = ReadLevel(f);
  if (def.level == MeshModelLevel::kContact) {
    for (const std::string_view key : kNotContactKeys) {
      if (f.Find(key) != nullptr) {
        f.Fail(key,
               "not used by model = \"contact\" (the tooth contact takes its law, damping and "
               "flanks from [mesh.contact] and [mesh.modifications]; remove it or choose another "
               "model)");
      }
    }
  }
  if (const toml::table* t = f.OptTable("contact")) {
    def.contact = ReadContactMesh(Fields(f.context(), *t, f.Key("contact")), geometry);
  }
  const bool slices = def.level == MeshModelLevel::kNonlinearSlices;
  const std::string model_text =
      std::string("this mesh's model is \"") + ToString(def.level) + "\"";
  MeshCoreOptions& options = def.core_options;
  options.level = def.level;
  if (const std::optional<int> n = f.OptInt("slices", 1, kMaxSlices)) {
    if (!slices) f.Fail("slices", "only used by model = \"slices\" (" + model_text + ")");
    options.num_slices = *n;
  }
  if (const std::optional<Number> k = f.OptNumber("stiffness_per_length")) {
    f.Positive("stiffness_per_length", *k);
    if (k->value < kMinStiffnessPerLength) {
      f.Fail("stiffness_per_length",
             FormatNumber(k->value) + " N/m^2 is implausibly small (at least " +
                 FormatNumber(kMinStiffnessPerLength) +
                 "; units are N/m^2: 1 N/(mm um) = 1e9 N/m^2, steel pairs about 2e10)");
    }
    def.stiffness_per_length = k->value;
  }
  def.damping = ReadDamping(f);

  const MeshCoefficientForm form = ReadForm(f, pinion);
  const bool fourier_used =
      form == MeshCoefficientForm::kAuto || form == MeshCoefficientForm::kFourier;
  const std::string form_text = "coefficient_form = \"" + std::string(FormNameOf(form)) + "\"";
  const std::optional<int> terms = f.OptInt("fourier_terms", 0, kMaxFourierTerms);
  if (terms && !fourier_used) {
    f.Fail("fourier_terms",
           "only used with coefficient_form \"fourier\" or \"auto\" (" + form_text + ")");
  }
  const std::optional<Number> tolerance = f.OptNumber("fourier_tolerance");
  if (tolerance) {
    if (!fourier_used) {
      f.Fail("fourier_tolerance",
             "only used with coefficient_form \"fourier\" or \"auto\" (" + form_text + ")");
    }
    if (slices) {
      f.Fail("fourier_tolerance",
             "not used by model = \"slices\" (its Fourier form keeps fourier_terms harmonics of "
             "table_samples samples)");
    }
    if (!(tolerance->value > 0.0 && tolerance->value < 1.0)) {
      f.Fail("fourier_tolerance", "must be > 0 and < 1, got " + FormatNumber(tolerance->value));
    }
  }
  const std::optional<int> given_samples = f.OptInt("table_samples", 1, kMaxTableSamples);
  const int samples = given_samples.value_or(options.coefficient.num_samples);
  def.fourier_keys_given = terms.has_value() || tolerance.has_value();
  def.table_samples_given = given_samples.has_value();
  options.coefficient.form = form;
  options.coefficient.num_terms = terms.value_or(0);
  if (tolerance) options.coefficient.rel_tol = tolerance->value;
  options.coefficient.num_samples = samples;
  options.slices.form = form;
  options.slices.num_samples = samples;
  options.slices.num_terms = terms.value_or(0);
  if (slices && terms && *terms > samples / 2) {
    f.Fail("fourier_terms", "must be at most table_samples/2 = " + std::to_string(samples / 2) +
                                " for model = \"slices\" (the series of table_samples samples), "
                                "got " +
                                std::to_string(*terms));
  }

  if (const toml::table* t = f.OptTable("modifications")) {
    def.modifications =
        ReadToothModifications(Fields(f.context(), *t, f.Key("modifications")), geometry);
  }
  def.errors.pinion_teeth = pinion.blank.teeth;
  def.errors.gear_teeth = gear.blank.kind == GearKind::kRack ? 1 : gear.blank.teeth;
  if (const toml::table* t = f.OptTable("errors")) {
    def.errors = ReadToothErrors(Fields(f.context(), *t, f.Key("errors")), pinion, gear);
  }
  if (form == MeshCoefficientForm::kFourier && terms && 2 * *terms >= samples &&
      HasUnloadedSeparation(def.modifications, def.errors)) {
    f.Fail("fourier_terms",
           "must be below table_samples/2 = " + FormatNumber(0.5 * samples) +
               " with tooth modifications or errors (the transmission error's series comes from "
               "table_samples samples per mesh cycle), got " +
               std::to_string(*terms));
  }

  if (const toml::table* t = f.OptTable("parameters")) {
    if (slices) {
      f.Fail("parameters",
             "user parameters cannot make model = \"slices\" (the slices need the contact "
             "lines); remove [mesh.parameters] or choose a linear model");
    }
    for (const std::string_view key : kContactLineKeys) {
      if (f.Find(key) != nullptr) {
        f.Fail(key,
               "not used with [mesh.parameters] (user data replaces the contact-line "
               "model; give te_eta/te_zeta there for a transmission error)");
      }
    }
    const double beta_b = geometry.base_helix_angle;
    const double sigma_width = geometry.line_of_action_length * std::abs(std::sin(beta_b)) +
                               geometry.face_width * std::cos(beta_b);
    def.parameters = ReadUserMeshParameters(Fields(f.context(), *t, f.Key("parameters")),
                                            0.5 * geometry.face_width, sigma_width);
  }
  return def;
}

}  // namespace geardyn::internal
