#include "geardyn/models/scene/scene_reader.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <string>
#include <vector>

#include "geardyn/common/units.hpp"
#include "support/expect_throws.hpp"

namespace geardyn {
namespace {

// A valid spur pair; every bad-input case below edits one thing in it. The comments on the table
// headers make each line unique, so a case can name the line it expects by its text.
constexpr std::string_view kBase = R"(title = "test pair"

[[gear]]  # pinion
name = "pinion"
teeth = 20
normal_module = 0.002
face_width = 0.02
mass = 0.5
inertia = 1e-4

[[gear]]  # wheel
name = "wheel"
teeth = 40
normal_module = 0.002
face_width = 0.02
mass = 2.0
inertia = 1.6e-3

[[mesh]]  # pinion-wheel
pinion = "pinion"
gear = "wheel"

[[bearing]]  # b1
name = "b1"
body = "pinion"
stiffness = [1e9, 1e9, 1e9, 1e7, 1e7, 0]

[[load]]  # brake
name = "brake"
body = "wheel"
torque = 100.0

[operating_point]
speed_rpm = 3000
torque = 50
)";

constexpr const char* kSource = "t.toml";

// `text` with the first occurrence of `from` replaced by `to` (which must exist).
std::string Replace(std::string_view text, std::string_view from, std::string_view to) {
  std::string s(text);
  const std::size_t pos = s.find(from);
  if (pos == std::string::npos) {
    ADD_FAILURE() << "test setup: '" << from << "' not found";
    return s;
  }
  return s.replace(pos, from.size(), to);
}

// 1-based line of the first occurrence of `needle` in `text` (0 if `needle` is empty).
int LineOf(std::string_view text, std::string_view needle) {
  if (needle.empty()) return 0;
  const std::size_t pos = text.find(needle);
  if (pos == std::string_view::npos) {
    ADD_FAILURE() << "test setup: line '" << needle << "' not found";
    return -1;
  }
  return 1 +
         static_cast<int>(std::count(text.begin(), text.begin() + static_cast<long>(pos), '\n'));
}

// The base pair made helical: pinion right-handed, wheel left-handed, 15°.
std::string Helical() {
  std::string s = Replace(kBase, "name = \"pinion\"\n",
                          "name = \"pinion\"\nhelix_angle_deg = 15.0\nhand = \"right\"\n");
  return Replace(s, "name = \"wheel\"\n",
                 "name = \"wheel\"\nhelix_angle_deg = 15.0\nhand = \"left\"\n");
}

// A third gear meshing with both others: three external gears in a triangle cannot turn.
std::string Triangle() {
  std::string s = Replace(kBase, "[[mesh]]  # pinion-wheel", R"([[gear]]  # idler
name = "idler"
teeth = 30
normal_module = 0.002
face_width = 0.02
mass = 1.0
inertia = 5e-4

[[mesh]]  # pinion-idler
pinion = "pinion"
gear = "idler"

[[mesh]]  # idler-wheel
pinion = "idler"
gear = "wheel"

[[mesh]]  # pinion-wheel)");
  return s;
}

struct BadCase {
  std::string name;                    // test name suffix
  std::string text;                    // the scene
  std::vector<std::string> overrides;  // --set
  std::string line_of;                 // the expected line contains this ("" = no line)
  std::string regex;                   // what() must match; "{line}" stands for that line
};

std::ostream& operator<<(std::ostream& os, const BadCase& c) { return os << c.name; }

// Bad mesh-model keys (mesh_model.hpp): `extra` is inserted at the end of the [[mesh]] table, so
// sub-tables ([mesh.modifications], ...) written there belong to the mesh.
void AddMeshModelCases(const std::string& base, const std::string& helical,
                       std::vector<BadCase>* cases) {
  const std::string mesh_end = "gear = \"wheel\"\n";
  const auto mesh = [&](const std::string& extra) {
    return Replace(base, mesh_end, mesh_end + extra);
  };
  const auto add = [&](std::string name, std::string text, std::string line_of, std::string regex,
                       std::vector<std::string> overrides = {}) {
    cases->push_back({std::move(name), std::move(text), std::move(overrides), std::move(line_of),
                      std::move(regex)});
  };
  std::string twenty = "[";  // 20 pitch deviations, one of them non-zero: not closed
  for (int i = 0; i < 20; ++i) twenty += i == 0 ? "2e-6" : ", 0";
  twenty += "]";
  // --- [[mesh]] keys ---
  add("MeshUnknownModel", mesh("model = \"coupling4\"\n"), "model = \"coupling4\"",
      R"(^t\.toml:{line}: mesh\.pinion-wheel\.model: unknown model 'coupling4'; models: )"
      R"(blankenship_singh, coupling_4dof, lti, torsional, slices$)");
  add("MeshMisspeltModel", mesh("model = \"torsinal\"\n"), "model = \"torsinal\"",
      R"(^t\.toml:{line}: mesh\.pinion-wheel\.model: unknown model 'torsinal' \(did you mean )"
      R"('torsional'\?\); models: )");
  add("MeshSlicesWithoutSliceModel", mesh("slices = 10\n"), "slices = 10",
      R"(^t\.toml:{line}: mesh\.pinion-wheel\.slices: only used by model = "slices" \(this )"
      R"(mesh's model is "blankenship_singh"\)$)");
  add("MeshZeroSlices", mesh("model = \"slices\"\nslices = 0\n"), "slices = 0",
      R"(^t\.toml:{line}: mesh\.pinion-wheel\.slices: must be >= 1, got 0$)");
  add("MeshSlicesAsFloat", mesh("model = \"slices\"\nslices = 10.0\n"), "slices = 10.0",
      R"(^t\.toml:{line}: mesh\.pinion-wheel\.slices: must be an integer, got 10 \(a float\)$)");
  add("MeshDampingAndRatio", mesh("damping_ratio = 0.05\ndamping = 200\n"), "damping = 200",
      R"(^t\.toml:{line}: mesh\.pinion-wheel\.damping: give either damping_ratio or damping)");
  add("MeshNegativeDampingRatio", mesh("damping_ratio = -0.1\n"), "damping_ratio = -0.1",
      R"(^t\.toml:{line}: mesh\.pinion-wheel\.damping_ratio: must be >= 0, got -0\.1$)");
  add("MeshStiffnessPerLengthInWrongUnits", mesh("stiffness_per_length = 14\n"),
      "stiffness_per_length = 14",
      R"(^t\.toml:{line}: mesh\.pinion-wheel\.stiffness_per_length: 14 N/m\^2 is implausibly small)");
  add("MeshUnknownCoefficientForm", mesh("coefficient_form = \"fourrier\"\n"), "fourrier",
      R"(^t\.toml:{line}: mesh\.pinion-wheel\.coefficient_form: unknown form 'fourrier' \(did you )"
      R"(mean 'fourier'\?\); forms: auto, piecewise_constant, fourier, table$)");
  add("MeshPiecewiseConstantHelical",
      Replace(helical, mesh_end, mesh_end + "coefficient_form = \"piecewise_constant\"\n"),
      "coefficient_form",
      R"(^t\.toml:{line}: mesh\.pinion-wheel\.coefficient_form: "piecewise_constant" needs a spur )");
  add("MeshFourierTermsWithTableForm", mesh("coefficient_form = \"table\"\nfourier_terms = 10\n"),
      "fourier_terms = 10",
      R"(^t\.toml:{line}: mesh\.pinion-wheel\.fourier_terms: only used with coefficient_form )"
      R"("fourier" or "auto" \(coefficient_form = "table"\)$)");
  add("MeshFourierToleranceAboveOne", mesh("fourier_tolerance = 1.5\n"), "fourier_tolerance",
      R"(^t\.toml:{line}: mesh\.pinion-wheel\.fourier_tolerance: must be > 0 and < 1, got 1\.5$)");
  add("MeshFourierTermsTooManyForTransmissionError",
      mesh("coefficient_form = \"fourier\"\nfourier_terms = 200\nmodifications = { lead_crowning "
           "= 5e-6 }\n"),
      "fourier_terms = 200",
      R"(^t\.toml:{line}: mesh\.pinion-wheel\.fourier_terms: must be below table_samples/2 = 128 )");
  // --- [mesh.modifications] ---
  add("MeshReliefWithoutLength", mesh("[mesh.modifications]\npinion_tip_relief = 2e-5\n"),
      "pinion_tip_relief = 2e-5",
      R"(^t\.toml:{line}: mesh\.pinion-wheel\.modifications\.pinion_tip_relief: needs )"
      R"(pinion_tip_relief_length too)");
  add("MeshReliefLengthWithoutAmount",
      mesh("[mesh.modifications]\ngear_root_relief_length = 1e-3\n"), "gear_root_relief_length",
      R"(^t\.toml:{line}: mesh\.pinion-wheel\.modifications\.gear_root_relief_length: given )"
      R"(without the relief amount gear_root_relief$)");
  add("MeshReliefLongerThanPath",
      mesh("[mesh.modifications]\ngear_tip_relief = 1e-5\ngear_tip_relief_length = 0.05\n"),
      "gear_tip_relief_length = 0.05",
      R"(^t\.toml:{line}: mesh\.pinion-wheel\.modifications\.gear_tip_relief_length: must be at )"
      R"(most the length of the path of contact g_alpha = 0\.00[0-9]+ m, got 0\.05$)");
  add("MeshCrowningInMicrometres", mesh("[mesh.modifications]\nlead_crowning = 5\n"),
      "lead_crowning = 5",
      R"(^t\.toml:{line}: mesh\.pinion-wheel\.modifications\.lead_crowning: must be at most )"
      R"(0\.001 m in magnitude \(deviations are in metres)");
  add("MeshUnknownModificationKey", mesh("[mesh.modifications]\nlead_crown = 5e-6\n"),
      "lead_crown = 5e-6",
      R"(^t\.toml:{line}: mesh\.pinion-wheel\.modifications\.lead_crown: unknown key \(did you )"
      R"(mean 'lead_crowning'\?\)$)");
  add("MeshUnknownReliefShape", mesh("[mesh.modifications]\nrelief_shape = \"round\"\n"), "round",
      R"(^t\.toml:{line}: mesh\.pinion-wheel\.modifications\.relief_shape: unknown shape 'round')");
  add("MeshModificationsNotATable", mesh("modifications = 5\n"), "modifications = 5",
      R"(^t\.toml:{line}: mesh\.pinion-wheel\.modifications: must be a table, got 5 \(an integer\)$)");
  // --- [mesh.errors] ---
  add("MeshPitchDeviationsWrongLength",
      mesh("[mesh.errors]\npinion_pitch_deviations = [1e-6, -1e-6, 0]\n"), "[1e-6, -1e-6, 0]",
      R"(^t\.toml:{line}: mesh\.pinion-wheel\.errors\.pinion_pitch_deviations: must have one entry )"
      R"(per tooth of the pinion 'pinion': 20 entries \(z = 20\), got 3$)");
  add("MeshPitchDeviationsNotClosed",
      mesh("[mesh.errors]\ngear_pitch_deviations = " + twenty + "\n"), "gear_pitch_deviations",
      R"(^t\.toml:{line}: mesh\.pinion-wheel\.errors\.gear_pitch_deviations: must have one entry )"
      R"(per tooth of the gear 'wheel': 40 entries \(z = 40\), got 20$)");
  add("MeshPinionPitchDeviationsNotClosed",
      mesh("[mesh.errors]\npinion_pitch_deviations = " + twenty + "\n"), "pinion_pitch_deviations",
      R"(^t\.toml:{line}: mesh\.pinion-wheel\.errors\.pinion_pitch_deviations: the single pitch )"
      R"(deviations of a closed gear sum to zero, got 2e-06 m \(subtract the mean 1e-07 m)");
  add("MeshRunoutPhaseWithoutRunout", mesh("[mesh.errors]\ngear_runout_phase_deg = 30\n"),
      "gear_runout_phase_deg",
      R"(^t\.toml:{line}: mesh\.pinion-wheel\.errors\.gear_runout_phase_deg: given without the )"
      R"(runout gear_runout$)");
  add("MeshNegativeRunout", mesh("[mesh.errors]\npinion_runout = -1e-5\n"), "pinion_runout",
      R"(^t\.toml:{line}: mesh\.pinion-wheel\.errors\.pinion_runout: must be >= 0, got -1e-05$)");
  // --- [mesh.parameters] ---
  const std::string params = "[mesh.parameters]  # user data\n";
  add("MeshParametersWithSlices",
      mesh("model = \"slices\"\n" + params + "form = \"table\"\nstiffness = [4e8]\n"),
      params.substr(0, 17),
      R"(^t\.toml:{line}: mesh\.pinion-wheel\.parameters: user parameters cannot make model = )"
      R"("slices" \(the slices need the contact lines\))");
  add("MeshParametersWithStiffnessPerLength",
      mesh("stiffness_per_length = 2e10\n" + params + "form = \"table\"\nstiffness = [4e8]\n"),
      "stiffness_per_length",
      R"(^t\.toml:{line}: mesh\.pinion-wheel\.stiffness_per_length: not used with )"
      R"(\[mesh\.parameters\] \(user data replaces the contact-line model)");
  add("MeshParametersMissingStiffness", mesh(params + "form = \"table\"\n"), params.substr(0, 17),
      R"(^t\.toml:{line}: mesh\.pinion-wheel\.parameters\.stiffness: missing \(required: mesh )"
      R"(stiffness K \[N/m\] over one mesh cycle\)$)");
  add("MeshParametersUnknownForm", mesh(params + "form = \"tabel\"\nstiffness = [4e8]\n"), "tabel",
      R"(^t\.toml:{line}: mesh\.pinion-wheel\.parameters\.form: unknown form 'tabel' \(did you )"
      R"(mean 'table'\?\); forms: table, fourier$)");
  add("MeshParametersLengthMismatch",
      mesh(params + "form = \"table\"\nstiffness = [3e8, 4e8]\nmu = [0.4]\n"), "mu = [0.4]",
      R"(^t\.toml:{line}: mesh\.pinion-wheel\.parameters\.mu: has 1 entries but stiffness has 2 )");
  add("MeshParametersNegativeStiffness",
      mesh(params + "form = \"table\"\nstiffness = [3e8, -1e8]\n"), "stiffness = [3e8, -1e8]",
      R"(^t\.toml:{line}: mesh\.pinion-wheel\.parameters\.stiffness: sample 1: K = -1e\+08 N/m )"
      R"(must be >= 0$)");
  add("MeshParametersMuBelowKappaSquared",
      mesh(params + "form = \"table\"\nstiffness = [4e8, 4e8]\nload_centre = [0, 0.008]\n"
                    "mu = [0.5, 0.5]\n"),
      "mu = [0.5, 0.5]",
      R"(^t\.toml:{line}: mesh\.pinion-wheel\.parameters\.mu: sample 1: mu = 0\.5 is below )"
      R"(kappa\^2 = \(h/b\)\^2 = 0\.64[0-9]* \(K2 would not be positive semi-definite)");
  add("MeshParametersLoadCentreInMillimetres",
      mesh(params + "form = \"table\"\nstiffness = [4e8, 4e8]\nload_centre = [0, 3]\n"),
      "load_centre = [0, 3]",
      R"(^t\.toml:{line}: mesh\.pinion-wheel\.parameters\.load_centre: sample 1: h = 3 m lies )"
      R"(outside the zone of action \(\|h\| <= 0\.02 m; lengths are in metres\)$)");
  add("MeshParametersEvenFourierLength",
      mesh(params + "form = \"fourier\"\nstiffness = [4e8, 1e7]\n"), "stiffness = [4e8, 1e7]",
      R"(^t\.toml:{line}: mesh\.pinion-wheel\.parameters\.stiffness: a Fourier series \[c0, a1, )"
      R"(b1, \.\.\., aN, bN\] has an odd number of entries, got 2$)");
  add("MeshParametersFourierNegativeSomewhere",
      mesh(params + "form = \"fourier\"\nstiffness = [4e8, 5e8, 0]\n"), "stiffness = [4e8, 5e8, 0]",
      R"(^t\.toml:{line}: mesh\.pinion-wheel\.parameters\.stiffness: at check point [0-9]+ of 64 )"
      R"(\(theta = [0-9.e+-]+ rad\): K = -[0-9.e+-]+ N/m; the series must be >= 0 )");
  // --- overrides ---
  add("OverrideUnknownModel", base, "",
      R"(^t\.toml: --set mesh\.pinion-wheel\.model=bs6: mesh\.pinion-wheel\.model: unknown model )"
      R"('bs6')",
      {"mesh.pinion-wheel.model=bs6"});
  add("OverrideUnknownModificationKey", base, "",
      R"(^t\.toml: --set mesh\.pinion-wheel\.modifications\.crowning=5e-6: )"
      R"(mesh\.pinion-wheel\.modifications\.crowning: unknown key)",
      {"mesh.pinion-wheel.modifications.crowning=5e-6"});
}

std::vector<BadCase> BadCases() {
  const std::string base(kBase);
  const std::string helical = Helical();
  std::vector<BadCase> c;
  // --- gear fields -------------------------------------------------------------------------
  c.push_back({"MissingTeeth",
               Replace(base, "teeth = 40\n", ""),
               {},
               "[[gear]]  # wheel",
               R"(^t\.toml:{line}: gear\.wheel\.teeth: missing \(required: number of teeth)"});
  c.push_back({"NegativeTeeth",
               Replace(base, "teeth = 40", "teeth = -5"),
               {},
               "teeth = -5",
               R"(^t\.toml:{line}: gear\.wheel\.teeth: must be a positive integer, got -5$)"});
  c.push_back({"ZeroTeeth",
               Replace(base, "teeth = 20", "teeth = 0"),
               {},
               "teeth = 0",
               R"(^t\.toml:{line}: gear\.pinion\.teeth: must be a positive integer, got 0$)"});
  c.push_back(
      {"TeethAsFloat",
       Replace(base, "teeth = 20", "teeth = 20.0"),
       {},
       "teeth = 20.0",
       R"(^t\.toml:{line}: gear\.pinion\.teeth: must be a positive integer, got 20 \(a float\)$)"});
  c.push_back(
      {"TeethAsString",
       Replace(base, "teeth = 20", "teeth = \"20\""),
       {},
       "teeth = \"20\"",
       R"(^t\.toml:{line}: gear\.pinion\.teeth: must be a positive integer, got string "20"$)"});
  c.push_back({"TeethHuge",
               Replace(base, "teeth = 20", "teeth = 3000000000"),
               {},
               "3000000000",
               R"(^t\.toml:{line}: gear\.pinion\.teeth: must be at most 10000, got 3000000000$)"});
  c.push_back({"ModuleNan",
               Replace(base, "normal_module = 0.002", "normal_module = nan"),
               {},
               "normal_module = nan",
               R"(^t\.toml:{line}: gear\.pinion\.normal_module: must be finite, got nan$)"});
  c.push_back({"ModuleInf",
               Replace(base, "normal_module = 0.002", "normal_module = +inf"),
               {},
               "normal_module = +inf",
               R"(^t\.toml:{line}: gear\.pinion\.normal_module: must be finite, got inf$)"});
  c.push_back(
      {"ModuleInMillimetres",
       Replace(base, "normal_module = 0.002", "normal_module = 2"),
       {},
       "normal_module = 2\n",
       R"(^t\.toml:{line}: gear\.pinion\.normal_module: must be at most 0\.1 m \(lengths are in metres)"});
  c.push_back(
      {"ModuleAsString",
       Replace(base, "normal_module = 0.002", "normal_module = \"2mm\""),
       {},
       "2mm",
       R"(^t\.toml:{line}: gear\.pinion\.normal_module: must be a number, got string "2mm"$)"});
  c.push_back({"NegativeFaceWidth",
               Replace(base, "face_width = 0.02", "face_width = -0.02"),
               {},
               "face_width = -0.02",
               R"(^t\.toml:{line}: gear\.pinion\.face_width: must be > 0, got -0\.02$)"});
  c.push_back({"NegativeMass",
               Replace(base, "mass = 0.5", "mass = -0.5"),
               {},
               "mass = -0.5",
               R"(^t\.toml:{line}: gear\.pinion\.mass: must be > 0, got -0\.5$)"});
  c.push_back({"ZeroInertia",
               Replace(base, "inertia = 1e-4", "inertia = 0.0"),
               {},
               "inertia = 0.0",
               R"(^t\.toml:{line}: gear\.pinion\.inertia: must be > 0, got 0$)"});
  c.push_back({"TransverseInertiaTooSmall",
               Replace(base, "inertia = 1e-4", "inertia = 1e-4\ntransverse_inertia = 4e-5"),
               {},
               "transverse_inertia",
               R"(^t\.toml:{line}: gear\.pinion\.transverse_inertia: must be at least inertia/2)"});
  c.push_back(
      {"PressureAngleOutOfRange",
       Replace(base, "teeth = 20", "teeth = 20\nnormal_pressure_angle_deg = 60"),
       {},
       "normal_pressure_angle_deg = 60",
       R"(^t\.toml:{line}: gear\.pinion\.normal_pressure_angle_deg: must be in \(0, 45\) degrees, got 60$)"});
  c.push_back(
      {"NegativeHelix",
       Replace(helical, "helix_angle_deg = 15.0", "helix_angle_deg = -15.0"),
       {},
       "helix_angle_deg = -15.0",
       R"(^t\.toml:{line}: gear\.pinion\.helix_angle_deg: must be >= 0 \(give the direction with hand)"});
  c.push_back(
      {"HandMissingForHelical",
       Replace(helical, "hand = \"left\"\n", ""),
       {},
       "[[gear]]  # wheel",
       R"(^t\.toml:{line}: gear\.wheel\.hand: missing \(required: "right" or "left" for a helical gear)"});
  c.push_back({"HandGivenForSpur",
               Replace(base, "teeth = 40", "teeth = 40\nhand = \"left\""),
               {},
               "hand = \"left\"",
               R"(^t\.toml:{line}: gear\.wheel\.hand: must not be given for a spur gear)"});
  c.push_back(
      {"HandMisspelt",
       Replace(helical, "hand = \"left\"", "hand = \"lefft\""),
       {},
       "hand = \"lefft\"",
       R"(^t\.toml:{line}: gear\.wheel\.hand: must be "right" or "left", got "lefft" \(did you mean 'left'\?\)$)"});
  c.push_back(
      {"InternalNotBool",
       Replace(base, "teeth = 40", "teeth = 40\ninternal = \"yes\""),
       {},
       "internal = \"yes\"",
       R"(^t\.toml:{line}: gear\.wheel\.internal: must be a boolean \(true or false\), got string "yes"$)"});
  c.push_back({"MissingGearName",
               Replace(base, "name = \"wheel\"\n", ""),
               {},
               "[[gear]]  # wheel",
               R"(^t\.toml:{line}: gear\[1\]\.name: missing \(required: a unique name)"});
  c.push_back({"EmptyGearName",
               Replace(base, "name = \"wheel\"", "name = \"\""),
               {},
               "name = \"\"",
               R"(^t\.toml:{line}: gear\[1\]\.name: '' is not a valid name)"});
  c.push_back({"GearNameWithDot",
               Replace(base, "name = \"wheel\"", "name = \"wh.eel\""),
               {},
               "name = \"wh.eel\"",
               R"(^t\.toml:{line}: gear\[1\]\.name: 'wh\.eel' is not a valid name)"});
  c.push_back(
      {"DuplicateGearName",
       Replace(base, "name = \"wheel\"", "name = \"pinion\""),
       {},
       "name = \"pinion\"\nteeth = 40",
       R"(^t\.toml:{line}: gear\[1\]\.name: duplicate gear name 'pinion' \(first defined at line 3\)$)"});
  // --- unknown keys and tables at every level ------------------------------------------------
  c.push_back({"UnknownTopLevelKey",
               Replace(base, "title = \"test pair\"", "titel = \"test pair\""),
               {},
               "titel",
               R"(^t\.toml:{line}: titel: unknown key \(did you mean 'title'\?\)$)"});
  c.push_back({"UnknownTopLevelTable",
               base + "\n[gears]\nteeth = 3\n",
               {},
               "[gears]",
               R"(^t\.toml:{line}: gears: unknown key \(did you mean 'gear'\?\)$)"});
  c.push_back({"UnknownGearKey",
               Replace(base, "teeth = 40", "teeth = 40\nteth = 40"),
               {},
               "teth = 40",
               R"(^t\.toml:{line}: gear\.wheel\.teth: unknown key \(did you mean 'teeth'\?\)$)"});
  c.push_back(
      {"UnknownKeyWithoutSuggestion",
       Replace(base, "teeth = 40", "teeth = 40\ncolour = 3"),
       {},
       "colour = 3",
       R"(^t\.toml:{line}: gear\.wheel\.colour: unknown key; allowed keys: name, teeth, )"});
  c.push_back(
      {"UnknownMeshKey",
       Replace(base, "gear = \"wheel\"", "gear = \"wheel\"\ncentre_distance = 0.06"),
       {},
       "centre_distance",
       R"(^t\.toml:{line}: mesh\.pinion-wheel\.centre_distance: unknown key \(did you mean 'center_distance'\?\)$)"});
  c.push_back(
      {"UnknownBearingKey",
       Replace(base, "body = \"pinion\"", "body = \"pinion\"\nstifness = 1"),
       {},
       "stifness",
       R"(^t\.toml:{line}: bearing\.b1\.stifness: unknown key \(did you mean 'stiffness'\?\)$)"});
  c.push_back({"UnknownLoadKey",
               Replace(base, "torque = 100.0", "torque = 100.0\ntorq = 1"),
               {},
               "torq = 1",
               R"(^t\.toml:{line}: load\.brake\.torq: unknown key \(did you mean 'torque'\?\)$)"});
  c.push_back(
      {"UnknownOperatingPointKey",
       Replace(base, "speed_rpm = 3000", "speed = 3000"),
       {},
       "speed = 3000",
       R"(^t\.toml:{line}: operating_point\.speed: unknown key \(did you mean 'speed_rpm'\?\)$)"});
  c.push_back(
      {"GearAsPlainTable",
       "title = \"x\"\n\n[gear]  # plain\nname = \"pinion\"\n",
       {},
       "[gear]  # plain",
       R"(^t\.toml:{line}: gear: must be an array of tables \(\[\[gear\]\]\), got a table$)"});
  c.push_back(
      {"NoGears",
       "title = \"x\"\n",
       {},
       "",
       R"(^t\.toml: gear: the scene has no gear \(at least one \[\[gear\]\] is required\)$)"});
  c.push_back({"TitleNotString",
               Replace(base, "title = \"test pair\"", "title = 3"),
               {},
               "title = 3",
               R"(^t\.toml:{line}: title: must be a string, got 3 \(an integer\)$)"});
  // --- meshes --------------------------------------------------------------------------------
  c.push_back(
      {"MeshUnknownGear",
       Replace(base, "gear = \"wheel\"", "gear = \"wheeel\""),
       {},
       "gear = \"wheeel\"",
       R"(^t\.toml:{line}: mesh\.pinion-wheeel\.gear: no gear named 'wheeel' \(did you mean 'wheel'\?\); gears: pinion, wheel$)"});
  c.push_back({"MeshGearIsPinion",
               Replace(base, "gear = \"wheel\"", "gear = \"pinion\""),
               {},
               "gear = \"pinion\"",
               R"(^t\.toml:{line}: mesh\.pinion-pinion\.gear: a gear cannot mesh with itself)"});
  c.push_back({"MeshMissingPinion",
               Replace(base, "pinion = \"pinion\"\n", ""),
               {},
               "[[mesh]]",
               R"(^t\.toml:{line}: mesh\[0\]\.pinion: missing)"});
  c.push_back(
      {"ModuleMismatch",
       Replace(base, "teeth = 40\nnormal_module = 0.002", "teeth = 40\nnormal_module = 0.0025"),
       {},
       "[[mesh]]",
       R"(^t\.toml:{line}: mesh\.pinion-wheel: normal_module differs: pinion 'pinion' has 0\.002 m but gear 'wheel' has 0\.0025 m)"});
  c.push_back(
      {"PressureAngleMismatch",
       Replace(base, "teeth = 40", "teeth = 40\nnormal_pressure_angle_deg = 25"),
       {},
       "[[mesh]]",
       R"(^t\.toml:{line}: mesh\.pinion-wheel: normal_pressure_angle_deg differs: .* 20 deg .* 25 deg)"});
  c.push_back({"HelixAngleMismatch",
               Replace(helical, "helix_angle_deg = 15.0\nhand = \"left\"",
                       "helix_angle_deg = 12.0\nhand = \"left\""),
               {},
               "[[mesh]]",
               R"(^t\.toml:{line}: mesh\.pinion-wheel: helix_angle_deg differs)"});
  c.push_back(
      {"SameHandExternalHelical",
       Replace(helical, "hand = \"left\"", "hand = \"right\""),
       {},
       "[[mesh]]",
       R"(^t\.toml:{line}: mesh\.pinion-wheel: external helical gears need opposite hands, but pinion 'pinion' and gear 'wheel' are both right-handed$)"});
  c.push_back(
      {"InternalPinion",
       Replace(base, "teeth = 20", "teeth = 20\ninternal = true"),
       {},
       "pinion = \"pinion\"",
       R"(^t\.toml:{line}: mesh\.pinion-wheel\.pinion: 'pinion' is an internal gear; the pinion of a mesh must be external)"});
  c.push_back(
      {"InternalMeshOppositeHands",
       Replace(helical, "teeth = 40", "teeth = 60\ninternal = true"),
       {},
       "[[mesh]]",
       R"(^t\.toml:{line}: mesh\.pinion-wheel: an internal helical mesh needs equal hands, but pinion 'pinion' is right-handed and ring 'wheel' is not$)"});
  c.push_back(
      {"DuplicateMeshPair",
       Replace(base, "[[bearing]]",
               "[[mesh]]  # again\nname = \"again\"\npinion = \"wheel\"\ngear = "
               "\"pinion\"\n\n[[bearing]]"),
       {},
       "[[mesh]]  # again",
       R"(^t\.toml:{line}: mesh\.again: gears 'wheel' and 'pinion' already mesh in mesh 'pinion-wheel'$)"});
  c.push_back(
      {"NegativeCenterDistance",
       Replace(base, "gear = \"wheel\"", "gear = \"wheel\"\ncenter_distance = -0.06"),
       {},
       "center_distance",
       R"(^t\.toml:{line}: mesh\.pinion-wheel\.center_distance: must be > 0, got -0\.06$)"});
  c.push_back({"KinematicallyLockedTriangle",
               Triangle(),
               {},
               "[[mesh]]  # pinion-wheel",
               R"(^t\.toml:{line}: mesh\.pinion-wheel: kinematically locked loop)"});
  // Geometry (CalcGearPairGeometry) errors, reported at the mesh.
  c.push_back({"ContactRatioBelowOne",
               Replace(Replace(base, "teeth = 20", "teeth = 20\naddendum_coefficient = 0.35"),
                       "teeth = 40", "teeth = 40\naddendum_coefficient = 0.35"),
               {},
               "[[mesh]]",
               R"(^t\.toml:{line}: mesh\.pinion-wheel: transverse_contact_ratio: .*below 1)"});
  c.push_back({"ImpossibleCenterDistance",
               Replace(base, "gear = \"wheel\"", "gear = \"wheel\"\ncenter_distance = 0.05"),
               {},
               "center_distance = 0.05",
               R"(^t\.toml:{line}: mesh\.pinion-wheel: center_distance: )"});
  // 70 mm is past a_max = sqrt((T1E + T2A)² + (r_b1 + r_b2)²) = 63.95 mm: the tips no longer
  // overlap along the line of action (formerly "transverse_contact_ratio: -1.9 is below 1").
  c.push_back(
      {"CenterDistanceBeyondPathOfContact",
       Replace(base, "gear = \"wheel\"", "gear = \"wheel\"\ncenter_distance = 0.07"),
       {},
       "center_distance = 0.07",
       R"(^t\.toml:{line}: mesh\.pinion-wheel: center_distance: 70 mm exceeds the largest centre distance with a positive path of contact, 63\.94[0-9]* mm, by 6\.05[0-9]* mm \(the tips no longer overlap along the line of action: g_α = -11\.3[0-9]* mm\)$)"});
  // --- bearings ------------------------------------------------------------------------------
  c.push_back(
      {"BearingFiveStiffnessEntries",
       Replace(base, "[1e9, 1e9, 1e9, 1e7, 1e7, 0]", "[1e9, 1e9, 1e9, 1e7, 1e7]"),
       {},
       "stiffness = ",
       R"(^t\.toml:{line}: bearing\.b1\.stiffness: must have 6 entries \(diagonal\) or 6 rows of 6 \(full matrix\), got 5 entries$)"});
  c.push_back(
      {"BearingNegativeDiagonal",
       Replace(base, "[1e9, 1e9, 1e9, 1e7, 1e7, 0]", "[1e9, -1e9, 1e9, 1e7, 1e7, 0]"),
       {},
       "stiffness = ",
       R"(^t\.toml:{line}: bearing\.b1\.stiffness: diagonal entry 1 \(y\) must be >= 0, got -1e\+09$)"});
  c.push_back(
      {"BearingAsymmetric",
       Replace(base, "stiffness = [1e9, 1e9, 1e9, 1e7, 1e7, 0]", R"(stiffness = [
  [1e9, 0, 0, 0, 1e6, 0],
  [0, 1e9, 0, 0, 0, 0],
  [0, 0, 1e9, 0, 0, 0],
  [0, 0, 0, 1e7, 0, 0],
  [2e6, 0, 0, 0, 1e7, 0],  # row 4
  [0, 0, 0, 0, 0, 0],
])"),
       {},
       "# row 4",
       R"(^t\.toml:{line}: bearing\.b1\.stiffness: not symmetric: \[0\]\[4\] \(x,ry\) = 1e\+06 but \[4\]\[0\] = 2e\+06$)"});
  c.push_back(
      {"BearingNotPsd",
       Replace(base, "stiffness = [1e9, 1e9, 1e9, 1e7, 1e7, 0]", R"(stiffness = [
  [1e9, 0, 0, 0, 1e9, 0],
  [0, 1e9, 0, 0, 0, 0],
  [0, 0, 1e9, 0, 0, 0],
  [0, 0, 0, 1e7, 0, 0],
  [1e9, 0, 0, 0, 1e7, 0],
  [0, 0, 0, 0, 0, 0],
])"),
       {},
       "stiffness = [\n",
       R"(^t\.toml:{line}: bearing\.b1\.stiffness: not positive semi-definite: the diagonally scaled matrix has eigenvalue -9)"});
  c.push_back(
      {"BearingShortRow",
       Replace(base, "stiffness = [1e9, 1e9, 1e9, 1e7, 1e7, 0]", R"(stiffness = [
  [1e9, 0, 0, 0, 0, 0],
  [0, 1e9, 0, 0, 0],  # short
  [0, 0, 1e9, 0, 0, 0],
  [0, 0, 0, 1e7, 0, 0],
  [0, 0, 0, 0, 1e7, 0],
  [0, 0, 0, 0, 0, 0],
])"),
       {},
       "# short",
       R"(^t\.toml:{line}: bearing\.b1\.stiffness: row 1 \(y\) must have 6 entries, got 5$)"});
  c.push_back(
      {"BearingDampingNan",
       Replace(base, "body = \"pinion\"", "body = \"pinion\"\ndamping = [1, 1, 1, 1, 1, nan]"),
       {},
       "damping",
       R"(^t\.toml:{line}: bearing\.b1\.damping: entry 5 \(rz\) must be finite, got nan$)"});
  c.push_back(
      {"BearingUnknownBody",
       Replace(base, "body = \"pinion\"", "body = \"pinon\""),
       {},
       "body = \"pinon\"",
       R"(^t\.toml:{line}: bearing\.b1\.body: no gear named 'pinon' \(did you mean 'pinion'\?\))"});
  c.push_back({"BearingOtherIsBody",
               Replace(base, "body = \"pinion\"", "body = \"pinion\"\nother = \"pinion\""),
               {},
               "other = ",
               R"(^t\.toml:{line}: bearing\.b1\.other: must differ from body)"});
  c.push_back({"BearingMissingStiffness",
               Replace(base, "stiffness = [1e9, 1e9, 1e9, 1e7, 1e7, 0]\n", ""),
               {},
               "[[bearing]]",
               R"(^t\.toml:{line}: bearing\.b1\.stiffness: missing)"});
  // --- loads and operating point -------------------------------------------------------------
  c.push_back({"LoadMissingTorque",
               Replace(base, "torque = 100.0\n", ""),
               {},
               "[[load]]",
               R"(^t\.toml:{line}: load\.brake\.torque: missing)"});
  c.push_back({"LoadTorqueInf",
               Replace(base, "torque = 100.0", "torque = -inf"),
               {},
               "torque = -inf",
               R"(^t\.toml:{line}: load\.brake\.torque: must be finite, got -inf$)"});
  c.push_back({"OperatingPointMissing",
               Replace(base, "[operating_point]\nspeed_rpm = 3000\ntorque = 50\n", ""),
               {},
               "",
               R"(^t\.toml: operating_point: missing \(required: an \[operating_point\] table)"});
  c.push_back({"OperatingPointMissingSpeed",
               Replace(base, "speed_rpm = 3000\n", ""),
               {},
               "[operating_point]",
               R"(^t\.toml:{line}: operating_point\.speed_rpm: missing)"});
  c.push_back({"OperatingPointNegativeSpeed",
               Replace(base, "speed_rpm = 3000", "speed_rpm = -100"),
               {},
               "speed_rpm = -100",
               R"(^t\.toml:{line}: operating_point\.speed_rpm: must be >= 0, got -100$)"});
  c.push_back({"OperatingPointUnknownBody",
               Replace(base, "speed_rpm = 3000", "speed_rpm = 3000\nbody = \"motor\""),
               {},
               "body = \"motor\"",
               R"(^t\.toml:{line}: operating_point\.body: no gear named 'motor')"});
  // --- TOML syntax ---------------------------------------------------------------------------
  c.push_back({"TomlSyntaxError",
               Replace(base, "teeth = 40", "teeth = = 40"),
               {},
               "teeth = = 40",
               R"(^t\.toml:{line}: TOML syntax error: )"});
  c.push_back({"TomlDuplicateKey",
               Replace(base, "teeth = 40", "teeth = 40\nteeth = 41"),
               {},
               "teeth = 41",
               R"(^t\.toml:{line}: TOML syntax error: )"});
  // --- overrides -----------------------------------------------------------------------------
  c.push_back(
      {"OverrideWithoutEquals",
       base,
       {"gear.pinion.teeth"},
       "",
       R"(^t\.toml: --set gear\.pinion\.teeth: malformed override: expected PATH=VALUE \(no '='\)$)"});
  c.push_back({"OverrideEmptyPath",
               base,
               {" = 3"},
               "",
               R"(^t\.toml: --set  = 3: malformed override: empty path)"});
  c.push_back(
      {"OverrideEmptySegment",
       base,
       {"gear..teeth=3"},
       "",
       R"(^t\.toml: --set gear\.\.teeth=3: gear\.\.teeth: malformed override: empty path segment)"});
  c.push_back(
      {"OverrideUnknownElement",
       base,
       {"gear.pinon.teeth=23"},
       "",
       R"(^t\.toml: --set gear\.pinon\.teeth=23: gear\.pinon: no element of 'gear' is named 'pinon' \(did you mean 'pinion'\?\))"});
  c.push_back(
      {"OverrideIndexOutOfRange",
       base,
       {"gear.5.teeth=23"},
       "",
       R"(^t\.toml: --set gear\.5\.teeth=23: gear\.5: no element 5 \('gear' has 2 elements)"});
  c.push_back(
      {"OverrideThroughNonTable",
       base,
       {"title.x=1"},
       "",
       R"(^t\.toml: --set title\.x=1: title\.x: cannot descend into 'title': it is string "test pair", not a table$)"});
  c.push_back(
      {"OverrideThroughValueDeeper",
       base,
       {"gear.pinion.teeth.x.y=1"},
       "",
       R"(^t\.toml: --set gear\.pinion\.teeth\.x\.y=1: gear\.pinion\.teeth\.x: cannot descend into 'gear\.pinion\.teeth': it is 20 \(an integer\), not a table$)"});
  c.push_back(
      {"OverrideBadValue",
       base,
       {"gear.pinion.teeth=0"},
       "",
       R"(^t\.toml: --set gear\.pinion\.teeth=0: gear\.pinion\.teeth: must be a positive integer, got 0$)"});
  c.push_back({"OverrideAddsUnknownKey",
               base,
               {"gear.pinion.colour=red"},
               "",
               R"(^t\.toml: --set gear\.pinion\.colour=red: gear\.pinion\.colour: unknown key)"});
  c.push_back(
      {"OverrideBareStringWhereNumber",
       base,
       {"operating_point.torque=lots"},
       "",
       R"(^t\.toml: --set operating_point\.torque=lots: operating_point\.torque: must be a number, got string "lots"$)"});
  c.push_back({"OverrideLaterOneReported",
               base,
               {"gear.0.teeth=21", "gear.1.mass=-1"},
               "",
               R"(^t\.toml: --set gear\.1\.mass=-1: gear\.wheel\.mass: must be > 0, got -1$)"});
  AddMeshModelCases(base, helical, &c);
  return c;
}

class SceneReaderBadInputTest : public ::testing::TestWithParam<BadCase> {};

TEST_P(SceneReaderBadInputTest, ReportsFileLineKeyAndReason) {
  const BadCase& c = GetParam();
  const int line = LineOf(c.text, c.line_of);
  const std::string regex =
      std::regex_replace(c.regex, std::regex(R"(\{line\})"), std::to_string(line));
  try {
    (void)ParseScene(c.text, kSource, c.overrides);
    ADD_FAILURE() << "no SceneError; expected " << regex;
  } catch (const SceneError& e) {
    EXPECT_THAT(std::string(e.what()), ::testing::ContainsRegex(regex));
    EXPECT_EQ(e.line(), line) << e.what();
    EXPECT_EQ(e.source(), kSource);
  }
}

INSTANTIATE_TEST_SUITE_P(Cases, SceneReaderBadInputTest, ::testing::ValuesIn(BadCases()),
                         [](const ::testing::TestParamInfo<BadCase>& param_info) {
                           return param_info.param.name;
                         });

TEST(SceneReaderTest, BadCaseTableIsLargeAndNamesAreUnique) {
  const std::vector<BadCase> cases = BadCases();
  EXPECT_GE(cases.size(), 30u);
  std::set<std::string> names;
  for (const BadCase& c : cases) EXPECT_TRUE(names.insert(c.name).second) << c.name;
}

// --- SceneError ---------------------------------------------------------------------------------

TEST(SceneErrorTest, FormatsSourceLineKeyReason) {
  const SceneError e("rig.toml", 12, "gear.wheel.teeth", "must be a positive integer, got -5");
  EXPECT_STREQ(e.what(), "rig.toml:12: gear.wheel.teeth: must be a positive integer, got -5");
  EXPECT_EQ(e.source(), "rig.toml");
  EXPECT_EQ(e.line(), 12);
  EXPECT_EQ(e.key(), "gear.wheel.teeth");
  EXPECT_EQ(e.reason(), "must be a positive integer, got -5");
  EXPECT_TRUE(e.override_spec().empty());
  const InvalidInput& base = e;  // catchable as the library's bad-input type
  EXPECT_STREQ(base.what(), e.what());
}

TEST(SceneErrorTest, FormatsOverrideAndMissingParts) {
  EXPECT_STREQ(SceneError("rig.toml", 0, "gear.pinion.teeth", "bad", "gear.pinion.teeth=0").what(),
               "rig.toml: --set gear.pinion.teeth=0: gear.pinion.teeth: bad");
  EXPECT_STREQ(SceneError("rig.toml", 0, "", "cannot open").what(), "rig.toml: cannot open");
  EXPECT_STREQ(SceneError("rig.toml", 3, "", "TOML syntax error: x").what(),
               "rig.toml:3: TOML syntax error: x");
}

TEST(SceneErrorTest, OverrideErrorCarriesTheOverride) {
  try {
    (void)ParseScene(kBase, kSource, {"gear.pinion.teeth=0"});
    FAIL() << "no SceneError";
  } catch (const SceneError& e) {
    EXPECT_EQ(e.line(), 0);
    EXPECT_EQ(e.override_spec(), "gear.pinion.teeth=0");
    EXPECT_EQ(e.key(), "gear.pinion.teeth");
    EXPECT_EQ(e.reason(), "must be a positive integer, got 0");
  }
}

// --- LoadScene: files and built-ins ---------------------------------------------------------

TEST(LoadSceneTest, UnreadableFileNamesTheFile) {
  EXPECT_THROWS_MESSAGE(LoadScene("/nonexistent/dir/rig.toml"), SceneError,
                        R"(^/nonexistent/dir/rig\.toml: cannot open the scene file)");
  const std::string dir = std::filesystem::temp_directory_path().string();
  EXPECT_THROWS_MESSAGE(LoadScene(dir), SceneError, "is a directory");
}

TEST(LoadSceneTest, UnknownBuiltinListsTheNames) {
  EXPECT_THROWS_MESSAGE(
      LoadScene("builtin:helical-pear"), SceneError,
      R"(^builtin:helical-pear: no built-in scene named 'helical-pear' \(did you )"
      R"(mean 'helical-pair'\?\); built-in scenes: geared-shafts, helical-pair, )");
}

TEST(LoadSceneTest, ReadsAFileAndNamesItInErrors) {
  const std::filesystem::path path =
      std::filesystem::temp_directory_path() / "geardyn_scene_reader_test_rig.toml";
  {
    std::ofstream out(path);
    out << kBase;
  }
  const Scene scene = LoadScene(path.string());
  EXPECT_EQ(scene.source, path.string());
  EXPECT_EQ(scene.title, "test pair");
  EXPECT_THROWS_MESSAGE(
      LoadScene(path.string(), {"gear.wheel.teeth=-5"}), SceneError,
      "^" + std::regex_replace(path.string(), std::regex(R"([.^$|()\[\]{}*+?\\])"), R"(\$&)") +
          R"(: --set gear\.wheel\.teeth=-5: gear\.wheel\.teeth: must be a )"
          R"(positive integer, got -5$)");
  std::filesystem::remove(path);
}

TEST(LoadSceneTest, BuiltinErrorsNameTheBuiltin) {
  EXPECT_THROWS_MESSAGE(
      LoadScene("builtin:helical-pair", {"gear.pinion.teeth=0"}), SceneError,
      R"(^builtin:helical-pair: --set gear\.pinion\.teeth=0: gear\.pinion\.teeth: )"
      R"(must be a positive integer, got 0$)");
}

// --- Valid input: values, defaults, unit conversions ----------------------------------------

// Relative tolerance for values that go through one unit conversion.
constexpr double kConvTol = 1e-14;

TEST(ParseSceneTest, ReadsTheBasePairWithDefaultsAndSiUnits) {
  const Scene s = ParseScene(kBase, kSource);
  EXPECT_EQ(s.source, kSource);
  EXPECT_EQ(s.title, "test pair");
  ASSERT_EQ(s.gears.size(), 2u);
  const GearDef& p = s.gear("pinion");
  EXPECT_EQ(p.blank.teeth, 20);
  EXPECT_EQ(p.blank.kind, GearKind::kExternal);
  EXPECT_DOUBLE_EQ(p.normal_module, 0.002);
  EXPECT_NEAR(p.normal_pressure_angle, 20.0 * std::acos(-1.0) / 180.0, kConvTol);  // default 20°
  EXPECT_EQ(p.helix_angle, 0.0);
  EXPECT_EQ(p.hand, HelixHand::kNone);
  EXPECT_DOUBLE_EQ(p.blank.face_width, 0.02);
  EXPECT_EQ(p.blank.profile_shift, 0.0);
  EXPECT_EQ(p.blank.addendum_coefficient, 1.0);
  EXPECT_EQ(p.blank.dedendum_coefficient, 1.25);
  EXPECT_EQ(p.blank.root_radius_coefficient, 0.38);
  EXPECT_FALSE(p.blank.tip_diameter.has_value());
  EXPECT_FALSE(p.blank.web_thickness.has_value());
  EXPECT_FALSE(p.blank.rim_thickness.has_value());
  EXPECT_EQ(p.mass, 0.5);
  EXPECT_EQ(p.inertia, 1e-4);
  EXPECT_EQ(p.key, "gear.pinion");
  EXPECT_FALSE(p.transverse_inertia.has_value());
  EXPECT_EQ(s.gear("wheel").mass, 2.0);  // 2.0 written as a float, also fine as int below

  ASSERT_EQ(s.meshes.size(), 1u);
  const MeshDef& m = s.meshes[0];
  EXPECT_EQ(m.name, "pinion-wheel");  // default name
  EXPECT_EQ(m.pinion, "pinion");
  EXPECT_EQ(m.gear, "wheel");
  EXPECT_EQ(m.geometry.pinion.teeth, 20);
  EXPECT_EQ(m.geometry.gear.teeth, 40);
  EXPECT_NEAR(m.geometry.center_distance, 0.002 * (20 + 40) / 2.0, 1e-12);  // zero backlash
  EXPECT_FALSE(m.geometry.spec.center_distance.has_value());

  ASSERT_EQ(s.bearings.size(), 1u);
  const BearingDef& b = s.bearings[0];
  EXPECT_EQ(b.name, "b1");
  EXPECT_EQ(b.body, "pinion");
  EXPECT_TRUE(b.other.empty());
  Matrix6 k = Matrix6::Zero();
  k.diagonal() << 1e9, 1e9, 1e9, 1e7, 1e7, 0.0;
  EXPECT_EQ(b.stiffness, k);
  EXPECT_EQ(b.damping, Matrix6::Zero());

  ASSERT_EQ(s.loads.size(), 1u);
  EXPECT_EQ(s.loads[0].name, "brake");
  EXPECT_EQ(s.loads[0].body, "wheel");
  EXPECT_EQ(s.loads[0].torque, 100.0);

  EXPECT_EQ(s.operating_point.body, "pinion");  // default: the first mesh's pinion
  EXPECT_NEAR(s.operating_point.speed, 3000.0 * 2.0 * std::acos(-1.0) / 60.0, 1e-12);
  EXPECT_EQ(s.operating_point.torque, 50.0);
}

TEST(ParseSceneTest, ConvertsDegreesAndRpm) {
  const std::string text =
      Replace(Replace(Helical(), "helix_angle_deg = 15.0\nhand = \"right\"",
                      "helix_angle_deg = 15.0\nhand = \"right\"\nnormal_pressure_angle_deg = 25"),
              "helix_angle_deg = 15.0\nhand = \"left\"",
              "helix_angle_deg = 15.0\nhand = \"left\"\nnormal_pressure_angle_deg = 25.0");
  const Scene s = ParseScene(text, kSource, {"operating_point.speed_rpm=60"});
  const double pi = std::acos(-1.0);
  EXPECT_NEAR(s.gear("pinion").normal_pressure_angle, 25.0 * pi / 180.0, kConvTol);
  EXPECT_NEAR(s.gear("pinion").helix_angle, 15.0 * pi / 180.0, kConvTol);
  EXPECT_EQ(s.gear("pinion").hand, HelixHand::kRight);
  EXPECT_EQ(s.gear("wheel").hand, HelixHand::kLeft);
  EXPECT_NEAR(s.operating_point.speed, 2.0 * pi, kConvTol);  // 60 rpm = 1 rev/s
  EXPECT_EQ(s.meshes[0].geometry.spec.pinion_hand, HelixHand::kRight);
}

TEST(ParseSceneTest, ReadsAllOptionalGearKeys) {
  const std::string text = Replace(kBase, "teeth = 40\n", R"(teeth = 40
profile_shift = -0.1
addendum_coefficient = 1.0
dedendum_coefficient = 1.3
root_radius_coefficient = 0.3
tip_diameter = 0.0836
web_thickness = 0.008
rim_thickness = 0.01
transverse_inertia = 9e-4
)");
  const Scene s = ParseScene(text, kSource);
  const GearDef& w = s.gear("wheel");
  EXPECT_EQ(w.blank.profile_shift, -0.1);
  EXPECT_EQ(w.blank.dedendum_coefficient, 1.3);
  EXPECT_EQ(w.blank.root_radius_coefficient, 0.3);
  EXPECT_EQ(w.blank.tip_diameter, 0.0836);
  EXPECT_EQ(w.blank.web_thickness, 0.008);
  EXPECT_EQ(w.blank.rim_thickness, 0.01);
  EXPECT_EQ(w.transverse_inertia, 9e-4);
  EXPECT_EQ(s.meshes[0].geometry.spec.gear.tip_diameter, 0.0836);
}

TEST(ParseSceneTest, IntegersAreAcceptedForFloats) {
  const Scene s = ParseScene(Replace(kBase, "mass = 2.0", "mass = 2"), kSource);
  EXPECT_EQ(s.gear("wheel").mass, 2.0);
}

TEST(ParseSceneTest, ReadsFullSymmetricMatricesAndDefaultNames) {
  const std::string text = Replace(Replace(kBase, "name = \"b1\"\n", ""),
                                   "stiffness = [1e9, 1e9, 1e9, 1e7, 1e7, 0]", R"(other = "wheel"
stiffness = [
  [1e9, 0, 0, 0, 2e7, 0],
  [0, 1e9, 0, -2e7, 0, 0],
  [0, 0, 5e8, 0, 0, 0],
  [0, -2e7, 0, 1e6, 0, 0],
  [2e7, 0, 0, 0, 1e6, 0],
  [0, 0, 0, 0, 0, 0],
]
damping = [100, 100, 50, 1, 1, 0]
)");
  const Scene s = ParseScene(text, kSource);
  const BearingDef& b = s.bearings[0];
  EXPECT_EQ(b.name, "bearing0");
  EXPECT_EQ(b.other, "wheel");
  EXPECT_EQ(b.stiffness(0, 4), 2e7);
  EXPECT_EQ(b.stiffness(4, 0), 2e7);
  EXPECT_EQ(b.stiffness(1, 3), -2e7);
  EXPECT_EQ(b.stiffness(2, 2), 5e8);
  EXPECT_EQ(b.stiffness(5, 5), 0.0);
  EXPECT_EQ(b.damping(2, 2), 50.0);
  EXPECT_EQ(b.damping(0, 1), 0.0);
  // A default-named bearing is addressable by its default name.
  const Scene t = ParseScene(text, kSource, {"bearing.bearing0.damping=[1, 2, 3, 4, 5, 6]"});
  EXPECT_EQ(t.bearings[0].damping(5, 5), 6.0);
}

TEST(ParseSceneTest, ExplicitCenterDistanceReachesTheGeometry) {
  const Scene s = ParseScene(kBase, kSource, {"mesh.pinion-wheel.center_distance=0.0601"});
  ASSERT_TRUE(s.meshes[0].geometry.spec.center_distance.has_value());
  EXPECT_EQ(*s.meshes[0].geometry.spec.center_distance, 0.0601);
  EXPECT_NEAR(s.meshes[0].geometry.center_distance, 0.0601, 1e-15);
}

TEST(ParseSceneTest, InternalHelicalMeshKeepsTheDirection) {
  const std::string text = Replace(Replace(Helical(), "teeth = 40", "teeth = 60\ninternal = true"),
                                   "hand = \"left\"", "hand = \"right\"");
  const Scene s = ParseScene(text, kSource);
  EXPECT_EQ(s.gear("wheel").blank.kind, GearKind::kInternal);
  EXPECT_TRUE(s.meshes[0].geometry.internal);
  EXPECT_EQ(s.meshes[0].geometry.gear.hand, HelixHand::kRight);
  const double w = s.operating_point.speed;
  EXPECT_NEAR(s.GearSpeed("wheel"), w * 20.0 / 60.0, 1e-12 * w);  // same sign: internal mesh
}

TEST(ParseSceneTest, AcceptsInlineArraysOfTables) {
  const std::string text = R"(gear = [
  { name = "a", teeth = 30, normal_module = 0.001, face_width = 0.01, mass = 0.1, inertia = 1e-5 },
  { name = "b", teeth = 31, normal_module = 0.001, face_width = 0.01, mass = 0.1, inertia = 1e-5 },
]
mesh = [{ pinion = "a", gear = "b" }]
operating_point = { speed_rpm = 600, torque = 1 }
)";
  const Scene s = ParseScene(text, kSource);
  EXPECT_EQ(s.gears.size(), 2u);
  EXPECT_EQ(s.meshes[0].name, "a-b");
  EXPECT_NEAR(s.MeshFrequencyHz(s.meshes[0]), 600.0 / 60.0 * 30.0, 1e-9);
  // Inline tables carry lines too.
  EXPECT_THROWS_MESSAGE(ParseScene(Replace(text, "teeth = 31", "teeth = -31"), kSource), SceneError,
                        R"(^t\.toml:3: gear\.b\.teeth: must be a positive integer, got -31$)");
}

// --- Overrides ----------------------------------------------------------------------------------

TEST(OverrideTest, ChangesValuesByNameAndIndex) {
  const Scene s =
      ParseScene(kBase, kSource,
                 {"gear.pinion.teeth=23", "gear.1.mass=3.5", "operating_point.torque=200",
                  "title=\"x\"", "load.brake.torque = -7"});
  EXPECT_EQ(s.gear("pinion").blank.teeth, 23);
  EXPECT_EQ(s.meshes[0].geometry.pinion.teeth, 23);
  EXPECT_EQ(s.gear("wheel").mass, 3.5);
  EXPECT_EQ(s.operating_point.torque, 200.0);
  EXPECT_EQ(s.title, "x");
  EXPECT_EQ(s.loads[0].torque, -7.0);
}

TEST(OverrideTest, BareWordsAreStringsAndTomlValuesKeepTheirType) {
  const Scene s = ParseScene(Helical(), kSource, {"gear.0.hand=left", "gear.wheel.hand=right"});
  EXPECT_EQ(s.gear("pinion").hand, HelixHand::kLeft);
  EXPECT_EQ(s.gear("wheel").hand, HelixHand::kRight);
  EXPECT_THROWS_MESSAGE(ParseScene(kBase, kSource, {"gear.pinion.teeth=23.0"}), SceneError,
                        R"(got 23 \(a float\)$)");
  EXPECT_THROWS_MESSAGE(ParseScene(kBase, kSource, {"gear.pinion.teeth=\"23\""}), SceneError,
                        R"(got string "23"$)");
}

TEST(OverrideTest, AddsKeysAndTables) {
  const Scene s = ParseScene(kBase, kSource,
                             {"gear.wheel.transverse_inertia=1e-3", "operating_point.body=wheel"});
  EXPECT_EQ(s.gear("wheel").transverse_inertia, 1e-3);
  EXPECT_EQ(s.operating_point.body, "wheel");
  // A whole missing table is created on the way.
  const std::string no_op =
      Replace(kBase, "[operating_point]\nspeed_rpm = 3000\ntorque = 50\n", "");
  const Scene t =
      ParseScene(no_op, kSource, {"operating_point.speed_rpm=1000", "operating_point.torque=5"});
  EXPECT_NEAR(t.operating_point.speed, 1000.0 * 2.0 * std::acos(-1.0) / 60.0, 1e-12);
  EXPECT_THROWS_MESSAGE(ParseScene(no_op, kSource, {"operating_point.torque=5"}), SceneError,
                        R"(^t\.toml: --set operating_point\.torque=5: operating_point\.speed_rpm: )"
                        R"(missing)");
}

TEST(OverrideTest, ArrayElementsAndLaterOverridesWin) {
  const Scene s = ParseScene(
      kBase, kSource,
      {"bearing.b1.stiffness.5=3e4", "operating_point.torque=1", "operating_point.torque=2"});
  EXPECT_EQ(s.bearings[0].stiffness(5, 5), 3e4);
  EXPECT_EQ(s.bearings[0].stiffness(0, 0), 1e9);
  EXPECT_EQ(s.operating_point.torque, 2.0);
}

TEST(OverrideTest, OverrideErrorsWinOverLaterFileErrors) {
  // The override's value is wrong; the file is fine: the error names the override, not a line.
  EXPECT_THROWS_MESSAGE(
      ParseScene(kBase, kSource, {"gear.wheel.normal_module=inf"}), SceneError,
      R"(^t\.toml: --set gear\.wheel\.normal_module=inf: gear\.wheel\.normal_module: )"
      R"(must be finite, got inf$)");
}

TEST(OverrideTest, ReplacesAWholeElement) {
  const Scene s =
      ParseScene(kBase, kSource, {R"(load.0={name="drag", body="pinion", torque=3.0})"});
  ASSERT_EQ(s.loads.size(), 1u);
  EXPECT_EQ(s.loads[0].name, "drag");
  EXPECT_EQ(s.loads[0].body, "pinion");
}

}  // namespace
}  // namespace geardyn
