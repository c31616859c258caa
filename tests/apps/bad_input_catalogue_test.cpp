// The bad-input catalogue of the geardyn command (issue 16): every row is one bad input — a
// scene with one thing changed, or one bad command-line option — run in-process through the
// command that reads it. Each must (a) exit with code 2, (b) name the file (scene rows: the
// scene's file name with its line) and the field (the TOML key path, or the CLI flag), and
// (c) give the reason ("must be > 0", "unknown key", "must be finite", …). Never a crash, a NaN
// in the output or a silent default. docs/bad-input.md lists the rows with their counts; set
// GEARDYN_BAD_INPUT_TABLE=FILE to write this file's rows as that document's table.
//
// Independent truth: the scene format's documented bounds (docs/scene-format.md) and the
// commands' documented option ranges (`geardyn CMD --help`), not the messages printed today.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "support/cli_run.hpp"
#include "support/scene_text.hpp"

namespace geardyn {
namespace {

using test::CliRun;
using test::Replace;
using test::RunGeardyn;

// A valid spur pair (support/scene_text.hpp) with a bearing on each gear, a brake, the operating
// point and modal damping: every scene row changes one thing in it.
const std::string kBase = test::SpurPairScene("bad-input base", R"([[bearing]]  # b1
name = "b1"
body = "pinion"
stiffness = [1e9, 1e9, 1e9, 1e7, 1e7, 0]

[[bearing]]  # b2
name = "b2"
body = "wheel"
stiffness = [1e9, 1e9, 1e9, 1e7, 1e7, 0]

[[load]]  # brake
name = "brake"
body = "wheel"
torque = 100.0

[operating_point]
speed_rpm = 3000
torque = 50

[damping]
modal_ratio = 0.02
)");

// The base made helical (15°, right-handed pinion, left-handed wheel).
std::string Helical() {
  std::string s = Replace(kBase, "name = \"pinion\"\n",
                          "name = \"pinion\"\nhelix_angle_deg = 15.0\nhand = \"right\"\n");
  return Replace(s, "name = \"wheel\"\n",
                 "name = \"wheel\"\nhelix_angle_deg = 15.0\nhand = \"left\"\n");
}

// The base's mesh table with `lines` added after its last line.
std::string WithMeshLines(const std::string& lines) {
  return Replace(kBase, "gear = \"wheel\"\n", "gear = \"wheel\"\n" + lines);
}

// The commands that read a scene, with the options each needs to get as far as reading it (the
// reader is shared; the rows rotate through them).
const std::map<std::string, std::vector<std::string>>& CommandArgs() {
  static const std::map<std::string, std::vector<std::string>> args = {
      {"info", {}},
      {"mesh", {}},
      {"modes", {}},
      {"floquet", {}},
      {"hb", {"--mesh-frequency", "1000"}},
      {"simulate", {"--max-periods", "5"}},
      {"stability-chart",
       {"--x", "operating_point.speed_rpm=1000:3000:2", "--y", "operating_point.torque=10:50:2"}},
      {"compare", {"--analyses", "modes"}},
  };
  return args;
}

struct BadInput {
  std::string name;                   // unique; the scene file is <name>.toml
  std::string category;               // docs/bad-input.md groups the rows by it
  std::string scene;                  // scene text ("" = the row's args name the scene)
  std::vector<std::string> args;      // command and options; "{scene}" = the written file
  std::vector<std::string> expected;  // substrings of the error: the field, then the reason
  bool scene_error = false;           // a scene-reader error: FILE:LINE: KEY: REASON
};

void PrintTo(const BadInput& c, std::ostream* os) { *os << c.name; }

// A scene row: `command` (with its CommandArgs) reads `scene`.
BadInput SceneRow(std::string name, std::string category, std::string scene, std::string command,
                  std::vector<std::string> expected) {
  std::vector<std::string> args = {command, "{scene}"};
  const std::vector<std::string>& extra = CommandArgs().at(command);
  args.insert(args.end(), extra.begin(), extra.end());
  return {std::move(name), std::move(category), std::move(scene),
          std::move(args), std::move(expected), true};
}

// A CLI row on a built-in scene or on the base scene ("{scene}").
BadInput FlagRow(std::string name, std::string category, std::vector<std::string> args,
                 std::vector<std::string> expected) {
  const bool uses_base = std::find(args.begin(), args.end(), std::string("{scene}")) != args.end();
  return {std::move(name), std::move(category), uses_base ? kBase : "",
          std::move(args), std::move(expected), false};
}

std::vector<BadInput> SceneRows() {
  const std::string b = kBase;
  const std::string helical = Helical();
  std::vector<BadInput> c;
  // --- [[gear]] -----------------------------------------------------------------------------
  c.push_back(SceneRow("GearMissingTeeth", "gear", Replace(b, "teeth = 40\n", ""), "info",
                       {"gear.wheel.teeth", "missing"}));
  c.push_back(SceneRow("GearNegativeTeeth", "gear", Replace(b, "teeth = 40", "teeth = -5"), "modes",
                       {"gear.wheel.teeth", "must be a positive integer", "-5"}));
  c.push_back(SceneRow("GearZeroTeeth", "gear", Replace(b, "teeth = 20", "teeth = 0"), "hb",
                       {"gear.pinion.teeth", "must be a positive integer", "got 0"}));
  c.push_back(SceneRow("GearTeethFloat", "gear", Replace(b, "teeth = 20", "teeth = 20.5"),
                       "floquet", {"gear.pinion.teeth", "must be a positive integer"}));
  c.push_back(SceneRow("GearTeethString", "gear", Replace(b, "teeth = 20", "teeth = \"20\""),
                       "simulate", {"gear.pinion.teeth", "got string"}));
  c.push_back(SceneRow("GearTeethHuge", "gear", Replace(b, "teeth = 20", "teeth = 3000000000"),
                       "mesh", {"gear.pinion.teeth", "must be at most 10000"}));
  c.push_back(SceneRow("GearModuleNan", "gear",
                       Replace(b, "normal_module = 0.002", "normal_module = nan"),
                       "stability-chart", {"gear.pinion.normal_module", "finite", "nan"}));
  c.push_back(SceneRow("GearModuleInf", "gear",
                       Replace(b, "normal_module = 0.002", "normal_module = -inf"), "compare",
                       {"gear.pinion.normal_module", "finite", "inf"}));
  c.push_back(SceneRow("GearModuleInMillimetres", "gear",
                       Replace(b, "normal_module = 0.002", "normal_module = 2"), "info",
                       {"gear.pinion.normal_module", "at most 0.1", "metres"}));
  c.push_back(SceneRow("GearModuleTiny", "gear",
                       Replace(Replace(b, "normal_module = 0.002", "normal_module = 1e-9"),
                               "normal_module = 0.002", "normal_module = 1e-9"),
                       "modes", {"normal_module", "at least 1e-05 m", "1e-09"}));
  c.push_back(SceneRow("GearModulesDiffer", "gear",
                       Replace(b, "normal_module = 0.002", "normal_module = 0.0025"), "hb",
                       {"mesh.pinion-wheel", "normal_module differs", "0.0025"}));
  c.push_back(SceneRow("GearModuleString", "gear",
                       Replace(b, "normal_module = 0.002", "normal_module = \"2mm\""), "hb",
                       {"gear.pinion.normal_module", "must be a number", "2mm"}));
  c.push_back(SceneRow("GearNegativeFaceWidth", "gear",
                       Replace(b, "face_width = 0.02", "face_width = -0.02"), "floquet",
                       {"gear.pinion.face_width", "must be > 0"}));
  c.push_back(SceneRow("GearFaceWidthInMillimetres", "gear",
                       Replace(b, "face_width = 0.02", "face_width = 20"), "mesh",
                       {"gear.pinion.face_width", "at most 2 m", "metres"}));
  c.push_back(SceneRow("GearNegativeMass", "gear", Replace(b, "mass = 0.5", "mass = -0.5"), "modes",
                       {"gear.pinion.mass", "must be > 0"}));
  c.push_back(SceneRow("GearMassNan", "gear", Replace(b, "mass = 2.0", "mass = nan"), "simulate",
                       {"gear.wheel.mass", "finite"}));
  c.push_back(SceneRow("GearZeroInertia", "gear", Replace(b, "inertia = 1e-4", "inertia = 0.0"),
                       "floquet", {"gear.pinion.inertia", "must be > 0"}));
  c.push_back(SceneRow("GearInertiaInf", "gear", Replace(b, "inertia = 1.6e-3", "inertia = inf"),
                       "hb", {"gear.wheel.inertia", "finite"}));
  c.push_back(SceneRow("GearTransverseInertiaTooSmall", "gear",
                       Replace(b, "inertia = 1e-4", "inertia = 1e-4\ntransverse_inertia = 4e-5"),
                       "modes", {"gear.pinion.transverse_inertia", "at least inertia/2"}));
  c.push_back(SceneRow("GearPressureAngle60", "gear",
                       Replace(b, "teeth = 20", "teeth = 20\nnormal_pressure_angle_deg = 60"),
                       "info", {"gear.pinion.normal_pressure_angle_deg", "must be in (0, 45)"}));
  c.push_back(SceneRow("GearHelixAbove45", "gear",
                       Replace(helical, "helix_angle_deg = 15.0", "helix_angle_deg = 60.0"),
                       "floquet", {"gear.pinion.helix_angle_deg", "45"}));
  c.push_back(SceneRow("GearNegativeHelix", "gear",
                       Replace(helical, "helix_angle_deg = 15.0", "helix_angle_deg = -15.0"), "hb",
                       {"gear.pinion.helix_angle_deg", "must be >= 0"}));
  c.push_back(SceneRow("GearHandMissing", "gear", Replace(helical, "hand = \"left\"\n", ""),
                       "modes", {"gear.wheel.hand", "missing"}));
  c.push_back(SceneRow("GearHandOnSpur", "gear",
                       Replace(b, "teeth = 40", "teeth = 40\nhand = \"left\""), "simulate",
                       {"gear.wheel.hand", "must not be given for a spur gear"}));
  c.push_back(SceneRow("GearHandMisspelt", "gear",
                       Replace(helical, "hand = \"left\"", "hand = \"lefty\""), "info",
                       {"gear.wheel.hand", "lefty"}));
  c.push_back(SceneRow("GearSameHands", "gear",
                       Replace(helical, "hand = \"left\"", "hand = \"right\""), "modes",
                       {"hand", "opposite"}));
  c.push_back(SceneRow("GearProfileShiftNan", "gear",
                       Replace(b, "teeth = 20", "teeth = 20\nprofile_shift = nan"), "floquet",
                       {"gear.pinion.profile_shift", "finite"}));
  c.push_back(SceneRow("GearZeroAddendum", "gear",
                       Replace(b, "teeth = 20", "teeth = 20\naddendum_coefficient = 0"), "mesh",
                       {"gear.pinion.addendum_coefficient", "> 0"}));
  c.push_back(SceneRow("GearNegativeTipDiameter", "gear",
                       Replace(b, "teeth = 20", "teeth = 20\ntip_diameter = -0.044"), "info",
                       {"gear.pinion.tip_diameter", "> 0"}));
  c.push_back(SceneRow("GearTipDiameterInMillimetres", "gear",
                       Replace(b, "teeth = 20", "teeth = 20\ntip_diameter = 44"), "modes",
                       {"mesh.pinion-wheel", "pinion.tip_diameter", "comes to a point"}));
  c.push_back(SceneRow("GearUnknownKey", "gear", Replace(b, "teeth = 40", "teeth = 40\nteth = 4"),
                       "hb", {"gear.wheel.teth", "unknown key"}));
  c.push_back(SceneRow("GearDuplicateName", "gear",
                       Replace(b, "name = \"wheel\"", "name = \"pinion\""), "info",
                       {"gear", "pinion", "duplicate"}));
  c.push_back(SceneRow("GearInternalNotBoolean", "gear",
                       Replace(b, "teeth = 40", "teeth = 40\ninternal = \"yes\""), "simulate",
                       {"gear.wheel.internal", "boolean"}));
  c.push_back(SceneRow("GearNegativeWebThickness", "gear",
                       Replace(b, "teeth = 40", "teeth = 40\nweb_thickness = -0.005"), "mesh",
                       {"gear.wheel.web_thickness", "> 0"}));
  c.push_back(SceneRow("GearNameNotString", "gear", Replace(b, "name = \"wheel\"", "name = 7"),
                       "info", {"gear", "name", "string"}));
  // --- [[mesh]] -----------------------------------------------------------------------------
  c.push_back(SceneRow("MeshUnknownGear", "mesh",
                       Replace(b, "gear = \"wheel\"\n", "gear = \"whee1\"\n"), "modes",
                       {"gear", "whee1"}));
  c.push_back(SceneRow("MeshMissingPinion", "mesh", Replace(b, "pinion = \"pinion\"\n", ""),
                       "floquet", {"pinion", "missing"}));
  c.push_back(SceneRow("MeshPinionEqualsGear", "mesh",
                       Replace(b, "gear = \"wheel\"\n", "gear = \"pinion\"\n"), "info",
                       {"mesh", "pinion"}));
  c.push_back(SceneRow("MeshCentreDistanceTooSmall", "mesh",
                       WithMeshLines("center_distance = 0.055\n"), "hb",
                       {"mesh.pinion-wheel", "center_distance", "not above r_b1 + r_b2"}));
  c.push_back(SceneRow("MeshCentreDistanceNegativeBacklash", "mesh",
                       WithMeshLines("center_distance = 0.0595\n"), "floquet",
                       {"mesh.pinion-wheel", "center_distance", "negative backlash"}));
  c.push_back(SceneRow(
      "MeshCentreDistanceInMillimetres", "mesh", WithMeshLines("center_distance = 60\n"), "info",
      {"mesh.pinion-wheel", "center_distance", "exceeds the largest centre distance"}));
  c.push_back(SceneRow("MeshCentreDistanceNegative", "mesh",
                       WithMeshLines("center_distance = -0.06\n"), "modes",
                       {"mesh.pinion-wheel.center_distance", "> 0"}));
  c.push_back(SceneRow("MeshContactRatioBelowOne", "mesh",
                       Replace(Replace(b, "teeth = 20", "teeth = 20\ntip_diameter = 0.0412"),
                               "teeth = 40", "teeth = 40\ntip_diameter = 0.0812"),
                       "floquet", {"mesh.pinion-wheel", "transverse_contact_ratio", "below 1"}));
  c.push_back(SceneRow("MeshUnknownModel", "mesh", WithMeshLines("model = \"fancy\"\n"), "simulate",
                       {"mesh.pinion-wheel.model", "fancy"}));
  c.push_back(SceneRow("MeshSlicesWithoutSliceModel", "mesh", WithMeshLines("slices = 10\n"), "hb",
                       {"mesh.pinion-wheel.slices", "slices"}));
  c.push_back(SceneRow("MeshZeroSlices", "mesh", WithMeshLines("model = \"slices\"\nslices = 0\n"),
                       "mesh", {"mesh.pinion-wheel.slices", "got 0"}));
  c.push_back(SceneRow("MeshNegativeStiffness", "mesh",
                       WithMeshLines("stiffness_per_length = -1e10\n"), "modes",
                       {"mesh.pinion-wheel.stiffness_per_length", "> 0"}));
  c.push_back(SceneRow("MeshStiffnessNan", "mesh", WithMeshLines("stiffness_per_length = nan\n"),
                       "floquet", {"mesh.pinion-wheel.stiffness_per_length", "finite"}));
  c.push_back(SceneRow("MeshNegativeDampingRatio", "mesh", WithMeshLines("damping_ratio = -0.05\n"),
                       "hb", {"mesh.pinion-wheel.damping_ratio", ">= 0"}));
  c.push_back(SceneRow("MeshDampingAndRatio", "mesh",
                       WithMeshLines("damping_ratio = 0.05\ndamping = 100.0\n"), "simulate",
                       {"mesh.pinion-wheel.damping", "damping_ratio"}));
  c.push_back(SceneRow("MeshUnknownCoefficientForm", "mesh",
                       WithMeshLines("coefficient_form = \"wavelet\"\n"), "floquet",
                       {"mesh.pinion-wheel.coefficient_form", "wavelet"}));
  c.push_back(SceneRow("MeshFourierToleranceAboveOne", "mesh",
                       WithMeshLines("fourier_tolerance = 2.0\n"), "modes",
                       {"mesh.pinion-wheel.fourier_tolerance", "got 2"}));
  c.push_back(SceneRow("MeshZeroTableSamples", "mesh", WithMeshLines("table_samples = 0\n"), "mesh",
                       {"mesh.pinion-wheel.table_samples", "got 0"}));
  c.push_back(SceneRow("MeshNegativeTipRelief", "mesh",
                       WithMeshLines("[mesh.modifications]\npinion_tip_relief = -1e-5\n"
                                     "pinion_tip_relief_length = 0.002\n"),
                       "info", {"mesh.pinion-wheel.modifications.pinion_tip_relief", ">= 0"}));
  c.push_back(SceneRow(
      "MeshReliefWithoutLength", "mesh",
      WithMeshLines("[mesh.modifications]\npinion_tip_relief = 1e-5\n"), "hb",
      {"mesh.pinion-wheel.modifications.pinion_tip_relief", "needs pinion_tip_relief_length"}));
  c.push_back(SceneRow("MeshReliefInMillimetres", "mesh",
                       WithMeshLines("[mesh.modifications]\nlead_crowning = 0.01\n"), "modes",
                       {"mesh.pinion-wheel.modifications.lead_crowning", "0.001"}));
  c.push_back(SceneRow("MeshPitchDeviationsCount", "mesh",
                       WithMeshLines("[mesh.errors]\npinion_pitch_deviations = [1e-6, 2e-6]\n"),
                       "mesh", {"mesh.pinion-wheel.errors.pinion_pitch_deviations", "20"}));
  c.push_back(SceneRow("MeshRunoutTooLarge", "mesh",
                       WithMeshLines("[mesh.errors]\ngear_runout = 0.01\n"), "hb",
                       {"mesh.pinion-wheel.errors.gear_runout", "0.001"}));
  c.push_back(SceneRow("MeshRunoutPhaseAlone", "mesh",
                       WithMeshLines("[mesh.errors]\ngear_runout_phase_deg = 30\n"), "info",
                       {"mesh.pinion-wheel.errors.gear_runout_phase_deg", "gear_runout"}));
  c.push_back(SceneRow("MeshParametersUnknownForm", "mesh",
                       WithMeshLines("[mesh.parameters]\nform = \"spline\"\n"
                                     "stiffness = [1e8, 2e8]\n"),
                       "floquet", {"mesh.pinion-wheel.parameters.form", "spline"}));
  c.push_back(SceneRow("MeshParametersNegativeStiffness", "mesh",
                       WithMeshLines("[mesh.parameters]\nform = \"table\"\n"
                                     "stiffness = [1e8, -2e8]\n"),
                       "modes", {"mesh.pinion-wheel.parameters.stiffness", ">= 0"}));
  c.push_back(SceneRow("MeshParametersStiffnessNotArray", "mesh",
                       WithMeshLines("[mesh.parameters]\nform = \"table\"\nstiffness = 1e8\n"),
                       "hb", {"mesh.pinion-wheel.parameters.stiffness", "array"}));
  c.push_back(SceneRow("MeshUnknownKey", "mesh", WithMeshLines("stifness_per_length = 1e10\n"),
                       "simulate", {"mesh.pinion-wheel.stifness_per_length", "unknown key"}));
  c.push_back(SceneRow("MeshContactUnknownTeeth", "mesh",
                       WithMeshLines("model = \"contact\"\n[mesh.contact]\nteeth = \"rubber\"\n"),
                       "info", {"mesh.pinion-wheel.contact.teeth", "rubber"}));
  c.push_back(SceneRow("MeshContactDensityInGramsPerCc", "mesh",
                       WithMeshLines("model = \"contact\"\n[mesh.contact]\nteeth = \"revolute\"\n"
                                     "bending_stiffness = 11.5e3\ndensity = 7.85\n"),
                       "simulate", {"mesh.pinion-wheel.contact.density", "100"}));
  c.push_back(SceneRow(
      "MeshContactPoissonHalf", "mesh",
      WithMeshLines("model = \"contact\"\n[mesh.contact]\nlaw = \"line\"\npoisson = 0.5\n"), "info",
      {"mesh.pinion-wheel.contact.poisson", "0.5"}));
  // --- [[bearing]] --------------------------------------------------------------------------
  c.push_back(SceneRow("BearingUnknownBody", "bearing",
                       Replace(b, "body = \"pinion\"", "body = \"shaft9\""), "modes",
                       {"bearing.b1.body", "shaft9"}));
  c.push_back(SceneRow("BearingStiffnessFiveNumbers", "bearing",
                       Replace(b, "stiffness = [1e9, 1e9, 1e9, 1e7, 1e7, 0]",
                               "stiffness = [1e9, 1e9, 1e9, 1e7, 1e7]"),
                       "floquet", {"bearing.b1.stiffness", "6"}));
  c.push_back(SceneRow("BearingNegativeStiffness", "bearing",
                       Replace(b, "stiffness = [1e9, 1e9, 1e9, 1e7, 1e7, 0]",
                               "stiffness = [1e9, -1e9, 1e9, 1e7, 1e7, 0]"),
                       "hb", {"bearing.b1.stiffness", "must be >= 0", "-1e+09"}));
  c.push_back(SceneRow("BearingStiffnessNan", "bearing",
                       Replace(b, "stiffness = [1e9, 1e9, 1e9, 1e7, 1e7, 0]",
                               "stiffness = [1e9, nan, 1e9, 1e7, 1e7, 0]"),
                       "simulate", {"bearing.b1.stiffness", "finite"}));
  c.push_back(SceneRow("BearingAsymmetricMatrix", "bearing",
                       Replace(b, "stiffness = [1e9, 1e9, 1e9, 1e7, 1e7, 0]",
                               "stiffness = [[1e9, 1e8, 0, 0, 0, 0], [0, 1e9, 0, 0, 0, 0],\n"
                               "  [0, 0, 1e9, 0, 0, 0], [0, 0, 0, 1e7, 0, 0],\n"
                               "  [0, 0, 0, 0, 1e7, 0], [0, 0, 0, 0, 0, 0]]"),
                       "modes", {"bearing.b1.stiffness", "symmetric"}));
  c.push_back(SceneRow("BearingNegativeDamping", "bearing",
                       Replace(b, "stiffness = [1e9, 1e9, 1e9, 1e7, 1e7, 0]",
                               "stiffness = [1e9, 1e9, 1e9, 1e7, 1e7, 0]\n"
                               "damping = [-1e3, 0, 0, 0, 0, 0]"),
                       "info", {"bearing.b1.damping", "must be >= 0", "-1000"}));
  c.push_back(SceneRow("BearingMissingStiffness", "bearing",
                       Replace(b, "stiffness = [1e9, 1e9, 1e9, 1e7, 1e7, 0]\n", ""), "floquet",
                       {"bearing.b1.stiffness", "missing"}));
  c.push_back(SceneRow("BearingStationOnAGear", "bearing",
                       Replace(b, "body = \"pinion\"", "body = \"pinion\"\nstation = 0.1"), "hb",
                       {"bearing.b1.station"}));
  // --- [[load]] -----------------------------------------------------------------------------
  c.push_back(SceneRow("LoadTorqueNan", "load", Replace(b, "torque = 100.0", "torque = nan"),
                       "modes", {"load.brake.torque", "finite"}));
  c.push_back(SceneRow("LoadUnknownBody", "load",
                       Replace(b, "body = \"wheel\"\ntorque", "body = \"brake\"\ntorque"), "hb",
                       {"load.brake.body", "brake"}));
  c.push_back(SceneRow("LoadMissingTorque", "load", Replace(b, "torque = 100.0\n", ""), "simulate",
                       {"load.brake.torque", "missing"}));
  c.push_back(SceneRow("LoadTorqueString", "load",
                       Replace(b, "torque = 100.0", "torque = \"100 N m\""), "info",
                       {"load.brake.torque", "number"}));
  // --- [operating_point] --------------------------------------------------------------------
  c.push_back(SceneRow("SpeedNegative", "operating_point",
                       Replace(b, "speed_rpm = 3000", "speed_rpm = -3000"), "floquet",
                       {"operating_point.speed_rpm", ">= 0"}));
  c.push_back(SceneRow("SpeedNan", "operating_point",
                       Replace(b, "speed_rpm = 3000", "speed_rpm = nan"), "hb",
                       {"operating_point.speed_rpm", "finite"}));
  c.push_back(SceneRow("SpeedInf", "operating_point",
                       Replace(b, "speed_rpm = 3000", "speed_rpm = inf"), "simulate",
                       {"operating_point.speed_rpm", "finite"}));
  c.push_back(SceneRow("OperatingTorqueMissing", "operating_point", Replace(b, "torque = 50\n", ""),
                       "modes", {"operating_point.torque", "missing"}));
  c.push_back(SceneRow("OperatingPointMissing", "operating_point",
                       Replace(b, "[operating_point]\nspeed_rpm = 3000\ntorque = 50\n", ""), "info",
                       {"operating_point", "missing"}));
  c.push_back(SceneRow("OperatingBodyUnknown", "operating_point",
                       Replace(b, "speed_rpm = 3000", "body = \"motor\"\nspeed_rpm = 3000"),
                       "floquet", {"operating_point.body", "motor"}));
  c.push_back(SceneRow("OperatingUnknownKey", "operating_point",
                       Replace(b, "speed_rpm = 3000", "speed = 3000\nspeed_rpm = 3000"), "hb",
                       {"operating_point.speed", "unknown key"}));
  // --- [damping] ----------------------------------------------------------------------------
  c.push_back(SceneRow("DampingModalRatioAboveOne", "damping",
                       Replace(b, "modal_ratio = 0.02", "modal_ratio = 1.5"), "modes",
                       {"damping.modal_ratio", "[0, 1)"}));
  c.push_back(SceneRow("DampingNegativeRayleigh", "damping",
                       Replace(b, "modal_ratio = 0.02", "rayleigh_alpha = -1.0"), "floquet",
                       {"damping.rayleigh_alpha", ">= 0"}));
  c.push_back(SceneRow("DampingModalAndRayleigh", "damping",
                       Replace(b, "modal_ratio = 0.02", "modal_ratio = 0.02\nrayleigh_beta = 1e-5"),
                       "hb", {"damping", "rayleigh"}));
  c.push_back(SceneRow("DampingUnknownKey", "damping",
                       Replace(b, "modal_ratio = 0.02", "modal_ration = 0.02"), "simulate",
                       {"damping.modal_ration", "unknown key"}));
  c.push_back(SceneRow("DampingRatiosNotArray", "damping",
                       Replace(b, "modal_ratio = 0.02", "modal_ratios = 0.02"), "info",
                       {"damping.modal_ratios", "array"}));
  // --- top level ----------------------------------------------------------------------------
  c.push_back(SceneRow("TopUnknownTable", "top level", b + "\n[solver]\norder = 2\n", "modes",
                       {"solver", "unknown key"}));
  c.push_back(SceneRow("TopTomlSyntaxError", "top level", Replace(b, "teeth = 40", "teeth = = 40"),
                       "info", {"TOML syntax error"}));
  c.push_back(SceneRow("TopNoGears", "top level", "[operating_point]\nspeed_rpm = 1\ntorque = 1\n",
                       "floquet", {"gear", "at least one [[gear]]"}));
  c.push_back(SceneRow("TopPlanarNotBoolean", "top level",
                       Replace(b, "title = ", "planar = \"yes\"\ntitle = "), "hb",
                       {"planar", "boolean"}));
  c.push_back(SceneRow("TopGearNotArrayOfTables", "top level",
                       "gear = 3\n" + b.substr(b.find("[[mesh]]")), "info", {"gear", "array"}));
  return c;
}

std::vector<BadInput> FlagRows() {
  const std::string pair = "builtin:helical-pair";
  const std::string rig = "builtin:kahraman-blankenship-rig";
  std::vector<BadInput> c;
  // --- the command line itself ----------------------------------------------------------------
  c.push_back(FlagRow("CliNoSubcommand", "command line", {}, {"subcommand"}));
  c.push_back(FlagRow("CliUnknownSubcommand", "command line", {"frobnicate"},
                      {"frobnicate", "unknown subcommand"}));
  c.push_back(FlagRow("CliMissingScene", "command line", {"info"}, {"scene", "required"}));
  c.push_back(FlagRow("CliNonexistentScene", "command line", {"modes", "/nonexistent/x.toml"},
                      {"/nonexistent/x.toml"}));
  c.push_back(FlagRow("CliUnknownBuiltin", "command line", {"hb", "builtin:no-such-scene"},
                      {"builtin:no-such-scene"}));
  c.push_back(
      FlagRow("CliUnknownOption", "command line", {"floquet", pair, "--bogus"}, {"--bogus"}));
  c.push_back(FlagRow("CliOptionOfAnotherCommand", "command line",
                      {"modes", pair, "--mesh-frequency", "100"}, {"--mesh-frequency"}));
  c.push_back(FlagRow("CliOutIsAFile", "command line", {"info", pair, "--out", "{file}"},
                      {"--out", "not a directory"}));
  // --- --set --------------------------------------------------------------------------------
  c.push_back(FlagRow("SetUnknownKey", "--set",
                      {"info", "{scene}", "--set", "gear.pinion.teeeth=23"},
                      {"gear.pinion.teeeth", "unknown key"}));
  c.push_back(FlagRow("SetUnknownGear", "--set", {"modes", pair, "--set", "gear.nobody.teeth=3"},
                      {"nobody"}));
  c.push_back(FlagRow("SetNoEquals", "--set", {"floquet", pair, "--set", "gear.pinion.teeth"},
                      {"--set", "gear.pinion.teeth", "="}));
  c.push_back(FlagRow("SetNonNumeric", "--set",
                      {"hb", "{scene}", "--set", "gear.pinion.face_width=wide"},
                      {"gear.pinion.face_width", "wide"}));
  c.push_back(FlagRow("SetNan", "--set", {"simulate", "{scene}", "--set", "gear.wheel.mass=nan"},
                      {"gear.wheel.mass", "finite"}));
  c.push_back(FlagRow("SetNegativeTeeth", "--set", {"info", rig, "--set", "gear.pinion.teeth=-5"},
                      {"gear.pinion.teeth", "must be a positive integer"}));
  c.push_back(FlagRow("SetEmptyValue", "--set", {"modes", "{scene}", "--set", "gear.pinion.mass="},
                      {"gear.pinion.mass"}));
  // --- hb -------------------------------------------------------------------------------------
  c.push_back(FlagRow("HbFrequencyNotANumber", "hb", {"hb", pair, "--mesh-frequency", "abc"},
                      {"--mesh-frequency", "abc"}));
  c.push_back(FlagRow("HbFrequencyNan", "hb", {"hb", pair, "--mesh-frequency", "nan"},
                      {"--mesh-frequency", "nan"}));
  c.push_back(FlagRow("HbFrequencyInf", "hb", {"hb", pair, "--mesh-frequency", "inf"},
                      {"--mesh-frequency", "inf"}));
  c.push_back(FlagRow("HbFrequencyNegative", "hb", {"hb", pair, "--mesh-frequency", "-100"},
                      {"--mesh-frequency", "-100"}));
  c.push_back(FlagRow("HbFrequencyZero", "hb", {"hb", pair, "--mesh-frequency", "0"},
                      {"--mesh-frequency", "must be a positive frequency", "got 0"}));
  c.push_back(FlagRow("HbFrequencyRangeReversed", "hb",
                      {"hb", pair, "--mesh-frequency", "3000:1000:10"},
                      {"--mesh-frequency", "hi must be >= lo"}));
  c.push_back(FlagRow("HbFrequencyRangeZeroPoints", "hb",
                      {"hb", pair, "--mesh-frequency", "1000:3000:0"},
                      {"--mesh-frequency", "n must be an integer in 1 … 100000", "got 0"}));
  c.push_back(FlagRow("HbFrequencyRangeHugeCount", "hb",
                      {"hb", pair, "--mesh-frequency", "1000:3000:1000000000"},
                      {"--mesh-frequency", "n must be an integer in 1 … 100000", "1e+09"}));
  c.push_back(FlagRow("HbFrequencyRangeMalformed", "hb",
                      {"hb", pair, "--mesh-frequency", "1000:3000"},
                      {"--mesh-frequency", "1000:3000"}));
  c.push_back(FlagRow("HbHarmonicsZero", "hb",
                      {"hb", pair, "--mesh-frequency", "1000", "--harmonics", "0"},
                      {"--harmonics", "must be >= 1", "got 0"}));
  c.push_back(FlagRow("HbHarmonicsHuge", "hb",
                      {"hb", pair, "--mesh-frequency", "1000", "--harmonics", "1000000000"},
                      {"--harmonics", "must be <= 2048", "1000000000"}));
  c.push_back(FlagRow("HbHarmonicsNotInteger", "hb",
                      {"hb", pair, "--mesh-frequency", "1000", "--harmonics", "2.5"},
                      {"--harmonics", "2.5"}));
  c.push_back(FlagRow("HbToleranceNegative", "hb",
                      {"hb", pair, "--mesh-frequency", "1000", "--tolerance", "-1e-4"},
                      {"--tolerance", "must be > 0", "-0.0001"}));
  c.push_back(FlagRow("HbToleranceNan", "hb",
                      {"hb", pair, "--mesh-frequency", "1000", "--tolerance", "nan"},
                      {"--tolerance", "must be > 0", "nan"}));
  c.push_back(
      FlagRow("HbToleranceWithHarmonics", "hb",
              {"hb", pair, "--mesh-frequency", "1000", "--harmonics", "4", "--tolerance", "1e-3"},
              {"--tolerance", "--harmonics"}));
  c.push_back(FlagRow("HbLinearAndNonlinear", "hb",
                      {"hb", pair, "--mesh-frequency", "1000", "--linear", "--nonlinear"},
                      {"--linear", "--nonlinear"}));
  c.push_back(FlagRow("HbUnknownStability", "hb",
                      {"hb", pair, "--mesh-frequency", "1000", "--stability", "lyapunov"},
                      {"--stability", "lyapunov"}));
  c.push_back(FlagRow("HbNegativeBranchSearch", "hb",
                      {"hb", pair, "--mesh-frequency", "1000", "--branch-search", "-1"},
                      {"--branch-search", "-1"}));
  c.push_back(FlagRow("HbMonodromyStepsNegative", "hb",
                      {"hb", pair, "--mesh-frequency", "1000", "--monodromy-steps", "-1"},
                      {"--monodromy-steps", "must be a finite number in", "-1"}));
  // --- floquet --------------------------------------------------------------------------------
  c.push_back(FlagRow("FloquetUnknownMethod", "floquet", {"floquet", pair, "--method", "euler"},
                      {"--method", "euler"}));
  c.push_back(FlagRow("FloquetZeroTolerance", "floquet", {"floquet", pair, "--tolerance", "0"},
                      {"--tolerance", "(0, 1)", "got 0"}));
  c.push_back(FlagRow("FloquetToleranceNan", "floquet", {"floquet", pair, "--tolerance", "nan"},
                      {"--tolerance", "(0, 1)", "got nan"}));
  c.push_back(FlagRow("FloquetNevZero", "floquet",
                      {"floquet", pair, "--method", "arpack_monodromy", "--nev", "0"},
                      {"--nev", "must be >= 1", "got 0"}));
  c.push_back(FlagRow("FloquetNevAboveTwiceDofs", "floquet",
                      {"floquet", pair, "--method", "arpack_monodromy", "--nev", "100000"},
                      {"--nev", "must be <= 2n = 24", "100000"}));
  // --- modes ----------------------------------------------------------------------------------
  c.push_back(
      FlagRow("ModesNegativeCount", "modes", {"modes", pair, "--modes", "-3"}, {"--modes", "-3"}));
  c.push_back(
      FlagRow("ModesNotANumber", "modes", {"modes", pair, "--modes", "all"}, {"--modes", "all"}));
  c.push_back(FlagRow("ModesUnknownMethod", "modes", {"modes", pair, "--method", "lanczos"},
                      {"--method", "lanczos"}));
  // --- mesh -----------------------------------------------------------------------------------
  c.push_back(
      FlagRow("MeshSamplesNan", "mesh", {"mesh", pair, "--samples", "nan"}, {"--samples", "nan"}));
  c.push_back(
      FlagRow("MeshSamplesZero", "mesh", {"mesh", pair, "--samples", "0"}, {"--samples", "got 0"}));
  c.push_back(
      FlagRow("MeshCyclesNegative", "mesh", {"mesh", pair, "--cycles", "-2"}, {"--cycles", "-2"}));
  c.push_back(
      FlagRow("MeshCyclesInf", "mesh", {"mesh", pair, "--cycles", "inf"}, {"--cycles", "inf"}));
  // --- simulate -------------------------------------------------------------------------------
  c.push_back(FlagRow("SimFrequencyNan", "simulate",
                      {"simulate", "{scene}", "--mesh-frequency", "nan"},
                      {"--mesh-frequency", "nan"}));
  c.push_back(FlagRow("SimFrequencyNegative", "simulate",
                      {"simulate", "{scene}", "--mesh-frequency", "-50"},
                      {"--mesh-frequency", "-50"}));
  c.push_back(FlagRow("SimToleranceTooLarge", "simulate",
                      {"simulate", "{scene}", "--tolerance", "0.5"}, {"--tolerance", "0.5"}));
  c.push_back(FlagRow("SimSteadyToleranceZero", "simulate",
                      {"simulate", "{scene}", "--steady-tolerance", "0"},
                      {"--steady-tolerance", "0"}));
  c.push_back(FlagRow("SimMaxPeriodsZero", "simulate",
                      {"simulate", "{scene}", "--max-periods", "0"}, {"--max-periods", "0"}));
  c.push_back(FlagRow("SimRecordPeriodsHuge", "simulate",
                      {"simulate", "{scene}", "--record-periods", "5000"},
                      {"--record-periods", "5000"}));
  c.push_back(FlagRow("SimSamplesPerPeriodTwo", "simulate",
                      {"simulate", "{scene}", "--samples-per-period", "2"},
                      {"--samples-per-period", "2"}));
  c.push_back(FlagRow("SimMaxStepAboveOne", "simulate", {"simulate", "{scene}", "--max-step", "2"},
                      {"--max-step", "2"}));
  c.push_back(FlagRow("SimThreadsNegative", "simulate", {"simulate", "{scene}", "--threads", "-1"},
                      {"--threads", "-1"}));
  c.push_back(
      FlagRow("SimUnknownSweep", "simulate",
              {"simulate", "{scene}", "--mesh-frequency", "500:1000:3", "--sweep", "sideways"},
              {"--sweep", "sideways"}));
  c.push_back(FlagRow("SimUnknownIntegrator", "simulate",
                      {"simulate", "{scene}", "--integrator", "euler"}, {"--integrator", "euler"}));
  c.push_back(FlagRow("SimTorqueNan", "simulate", {"simulate", "{scene}", "--torque", "nan"},
                      {"--torque", "nan"}));
  c.push_back(FlagRow("SimSweepWithoutRange", "simulate", {"simulate", "{scene}", "--sweep", "up"},
                      {"--sweep", "lo:hi:n"}));
  // --- stability-chart ------------------------------------------------------------------------
  const std::vector<std::string> y = {"--y", "operating_point.torque=10:50:2"};
  auto chart = [&](std::vector<std::string> a) {
    std::vector<std::string> args = {"stability-chart", pair};
    args.insert(args.end(), a.begin(), a.end());
    return args;
  };
  c.push_back(FlagRow("ChartMissingY", "stability-chart",
                      chart({"--x", "operating_point.speed_rpm=1000:3000:2"}), {"--y"}));
  c.push_back(FlagRow("ChartAxisMalformed", "stability-chart",
                      chart({"--x", "operating_point.speed_rpm", y[0], y[1]}),
                      {"--x", "operating_point.speed_rpm"}));
  c.push_back(FlagRow("ChartAxisUnknownPath", "stability-chart",
                      chart({"--x", "gear.pinion.colour=1:2:3", y[0], y[1]}),
                      {"gear.pinion.colour", "unknown key"}));
  c.push_back(FlagRow("ChartAxisZeroPoints", "stability-chart",
                      chart({"--x", "operating_point.speed_rpm=1000:3000:0", y[0], y[1]}),
                      {"--x", "0"}));
  c.push_back(FlagRow("ChartAxisNan", "stability-chart",
                      chart({"--x", "operating_point.speed_rpm=nan:3000:3", y[0], y[1]}),
                      {"--x", "nan"}));
  c.push_back(FlagRow("ChartAxisHugeGrid", "stability-chart",
                      chart({"--x", "operating_point.speed_rpm=1000:3000:100000", "--y",
                             "operating_point.torque=10:50:100000"}),
                      {"--x", "at most 10000", "100000"}));
  c.push_back(FlagRow(
      "ChartMaxOrderZero", "stability-chart",
      chart({"--x", "operating_point.speed_rpm=1000:3000:2", y[0], y[1], "--max-order", "0"}),
      {"--max-order", "0"}));
  c.push_back(FlagRow("ChartBoundaryToleranceOne", "stability-chart",
                      chart({"--x", "operating_point.speed_rpm=1000:3000:2", y[0], y[1],
                             "--boundary-tolerance", "1"}),
                      {"--boundary-tolerance", "1"}));
  c.push_back(FlagRow(
      "ChartThreadsNegative", "stability-chart",
      chart({"--x", "operating_point.speed_rpm=1000:3000:2", y[0], y[1], "--threads", "-2"}),
      {"--threads", "must be a finite number in [0, ", "-2"}));
  c.push_back(FlagRow(
      "ChartToleranceNan", "stability-chart",
      chart({"--x", "operating_point.speed_rpm=1000:3000:2", y[0], y[1], "--tolerance", "nan"}),
      {"--tolerance", "(0, 1)", "nan"}));
  // --- compare --------------------------------------------------------------------------------
  c.push_back(FlagRow("CompareUnknownLevel", "compare",
                      {"compare", pair, "--levels", "blankenship_singh,quantum"},
                      {"--levels", "quantum"}));
  c.push_back(FlagRow("CompareUnknownAnalysis", "compare", {"compare", pair, "--analyses", "fem"},
                      {"--analyses", "fem"}));
  c.push_back(FlagRow("CompareMacThresholdAboveOne", "compare",
                      {"compare", pair, "--analyses", "modes", "--mac-threshold", "2"},
                      {"--mac-threshold", "2"}));
  c.push_back(FlagRow("CompareThreadsHuge", "compare",
                      {"compare", pair, "--analyses", "modes", "--threads", "5000"},
                      {"--threads", "5000"}));
  c.push_back(FlagRow("CompareModesZero", "compare",
                      {"compare", pair, "--analyses", "modes", "--modes", "0"}, {"--modes", "0"}));
  c.push_back(FlagRow("CompareUnknownMesh", "compare",
                      {"compare", pair, "--analyses", "modes", "--mesh", "sun-planet"},
                      {"--mesh", "sun-planet"}));
  c.push_back(FlagRow("CompareFrequencyToleranceNegative", "compare",
                      {"compare", pair, "--analyses", "modes", "--frequency-tolerance", "-0.1"},
                      {"--frequency-tolerance", "-0.1"}));
  // --- campbell (issue 18) -------------------------------------------------------------------
  const std::string planetary = "builtin:planetary-lin-parker";
  c.push_back(FlagRow("CampbellCarrierSpeedNotPlanetary", "campbell",
                      {"campbell", pair, "--carrier-speed", "0:1000:3"},
                      {"--carrier-speed", "needs a planetary set"}));
  c.push_back(FlagRow("CampbellNoSpeedAxis", "campbell", {"campbell", pair},
                      {"--speed, --carrier-speed", "exactly one"}));
  c.push_back(FlagRow("CampbellBothSpeedAxes", "campbell",
                      {"campbell", planetary, "--speed", "0:1000:3", "--carrier-speed", "0:100:3"},
                      {"--carrier-speed", "exactly one"}));
  c.push_back(FlagRow("CampbellSpeedMalformed", "campbell", {"campbell", pair, "--speed", "0:1000"},
                      {"--speed", "lo:hi:n"}));
  c.push_back(FlagRow("CampbellSpeedOnePoint", "campbell",
                      {"campbell", pair, "--speed", "0:1000:1"}, {"--speed", "n must be"}));
  c.push_back(FlagRow("CampbellSpeedDescending", "campbell",
                      {"campbell", pair, "--speed", "100:10:5"}, {"--speed", "hi must be"}));
  c.push_back(FlagRow("CampbellSpeedNegative", "campbell", {"campbell", pair, "--speed", "-5:10:5"},
                      {"--speed", "lo must be"}));
  c.push_back(FlagRow("CampbellSpeedNan", "campbell", {"campbell", pair, "--speed", "0:nan:5"},
                      {"--speed", "nan"}));
  c.push_back(FlagRow("CampbellOrdersZero", "campbell",
                      {"campbell", pair, "--speed", "0:10:5", "--orders", "0"}, {"--orders", "0"}));
  c.push_back(FlagRow("CampbellOscillatorScene", "campbell",
                      {"campbell", "builtin:kahraman-singh-oscillator", "--speed", "0:10:5"},
                      {"oscillator"}));
  c.push_back(FlagRow("CampbellAnisotropicSunBearing", "campbell",
                      {"campbell", planetary, "--speed", "0:10:5", "--set",
                       "bearing.sun-support.stiffness=[1e8, 2e8, 1e8, 1e6, 1e6, 0]"},
                      {"sun-support", "isotropic"}));
  return c;
}

std::vector<BadInput> AllRows() {
  std::vector<BadInput> rows = SceneRows();
  for (BadInput& r : FlagRows()) rows.push_back(std::move(r));
  return rows;
}

// The row's edit, for the table: the lines of `scene` that the base does not have, and
// "removed: LINE" for the base's lines that `scene` lacks.
std::string SceneEdit(const std::string& scene) {
  const auto lines = [](const std::string& text) {
    std::set<std::string> out;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);) out.insert(line);
    return out;
  };
  const std::set<std::string> base = lines(kBase), edited = lines(scene);
  std::string edit;
  for (const std::string& line : edited) {
    if (!base.count(line)) edit += (edit.empty() ? "" : "; ") + line;
  }
  for (const std::string& line : base) {
    if (!edited.count(line)) edit += (edit.empty() ? "removed: " : "; removed: ") + line;
  }
  return edit;
}

std::filesystem::path OutputDir() {
  return std::filesystem::path(GEARDYN_BINARY_DIR) / "test-output" / "bad_input";
}

class BadInputCatalogueTest : public ::testing::TestWithParam<BadInput> {};

TEST_P(BadInputCatalogueTest, ExitsWithTwoNamingTheFileTheFieldAndTheReason) {
  const BadInput& c = GetParam();
  const std::filesystem::path dir = OutputDir();
  std::filesystem::create_directories(dir);
  const std::string file_name = c.name + ".toml";
  const std::string path = (dir / file_name).string();
  if (!c.scene.empty()) std::ofstream(path) << c.scene;
  const std::string blocker = (dir / (c.name + ".blocker")).string();
  std::vector<std::string> args = c.args;
  for (std::string& a : args) {
    if (a == "{scene}") a = path;
    if (a == "{file}") {
      std::ofstream(blocker) << "a file where --out wants a directory\n";
      a = blocker;
    }
  }
  const CliRun run = RunGeardyn(args);
  EXPECT_EQ(run.code, app::kExitBadInput) << run.err << run.out.substr(0, 2000);
  // (b) the file: a scene error starts with FILE:LINE.
  if (c.scene_error) {
    EXPECT_NE(run.err.find(file_name + ":"), std::string::npos) << run.err;
  }
  // (b), (c): the field and the reason.
  for (const std::string& part : c.expected) {
    EXPECT_NE(run.err.find(part), std::string::npos) << "expected '" << part << "' in\n" << run.err;
  }
  // Never a NaN in the output of a rejected input, never a crash report.
  EXPECT_EQ(run.err.find("internal error"), std::string::npos) << run.err;
  EXPECT_EQ(run.out.find("nan"), std::string::npos) << run.out.substr(0, 2000);
}

INSTANTIATE_TEST_SUITE_P(Rows, BadInputCatalogueTest, ::testing::ValuesIn(AllRows()),
                         [](const ::testing::TestParamInfo<BadInput>& p) { return p.param.name; });

// The catalogue's size and uniqueness: ≥ 100 rows, names unique (they name the tests and the
// files), every row with a field and a reason, and no two rows with the same input.
TEST(BadInputCatalogueTest, HasUniqueRowsWithFieldAndReason) {
  const std::vector<BadInput> rows = AllRows();
  std::set<std::string> names, inputs;
  for (const BadInput& r : rows) {
    EXPECT_TRUE(names.insert(r.name).second) << r.name;
    std::string input = r.scene;
    for (const std::string& a : r.args) input += "\x1f" + a;
    EXPECT_TRUE(inputs.insert(input).second) << "duplicate input: " << r.name;
    EXPECT_FALSE(r.expected.empty()) << r.name;
  }
  EXPECT_GE(rows.size(), 100u);
  // GEARDYN_BAD_INPUT_TABLE=FILE writes the rows for docs/bad-input.md.
  if (const char* file = std::getenv("GEARDYN_BAD_INPUT_TABLE")) {
    std::ofstream md(file);
    std::map<std::string, int> per_category;
    for (const BadInput& r : rows) {
      std::string cmd = "geardyn";
      for (const std::string& a : r.args) cmd += " " + a;
      if (r.scene_error) cmd += "` with `" + SceneEdit(r.scene).substr(0, 160);
      std::string expected;
      for (const std::string& e : r.expected) expected += (expected.empty() ? "" : " … ") + e;
      md << "| " << r.name << " | " << r.category << " | `" << cmd << "` | " << expected
         << " | 2 |\n";
      ++per_category[r.category];
    }
    md << "\n";
    for (const auto& [category, n] : per_category) md << "| " << category << " | " << n << " |\n";
    md << "| total | " << rows.size() << " |\n";
  }
}

}  // namespace
}  // namespace geardyn
