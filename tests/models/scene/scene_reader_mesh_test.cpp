// Scene reader, [[mesh]] tables and their mesh-model keys (model, [mesh.modifications],
// [mesh.errors], [mesh.parameters]): each bad input is reported as FILE:LINE: KEY: REASON.
#include <gtest/gtest.h>

#include <string>
#include <utility>
#include <vector>

#include "scene_reader_cases.hpp"

namespace geardyn {
namespace {

using test::BadCase;
using test::kBase;
using test::Replace;
using test::Triangle;

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
      R"(blankenship_singh, bs_projected, five_dof, coupling_4dof, lti, torsional, slices, )"
      R"(contact$)");
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

std::vector<BadCase> MeshCases() {
  const std::string base(kBase);
  const std::string helical = test::Helical();
  std::vector<BadCase> c;
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
  AddMeshModelCases(base, helical, &c);
  return c;
}

class SceneReaderMeshInputTest : public ::testing::TestWithParam<BadCase> {};

TEST_P(SceneReaderMeshInputTest, ReportsFileLineKeyAndReason) {
  test::ExpectSceneError(GetParam());
}

INSTANTIATE_TEST_SUITE_P(Cases, SceneReaderMeshInputTest, ::testing::ValuesIn(MeshCases()),
                         test::CaseName);

TEST(SceneReaderTest, MeshCasesTableNamesAreUnique) {
  const std::vector<BadCase> cases = MeshCases();
  EXPECT_GE(cases.size(), 30u);
  test::ExpectUniqueNames(cases);
}

}  // namespace
}  // namespace geardyn
