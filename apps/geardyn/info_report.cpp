#include "geardyn/info_report.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <numbers>
#include <numeric>
#include <sstream>

#include "geardyn/common/units.hpp"
#include "geardyn/models/contact/contact_law.hpp"
#include "geardyn/models/contact/contact_mesh_def.hpp"
#include "geardyn/models/contact/tooth_body.hpp"
#include "geardyn/models/gear/iso_stiffness.hpp"
#include "geardyn/models/scene/mesh_model.hpp"
#include "geardyn/models/system/oscillator_system.hpp"
#include "geardyn/shaft_report.hpp"

namespace geardyn::app {
namespace {

using nlohmann::json;

const char* HandName(HelixHand hand) {
  switch (hand) {
    case HelixHand::kNone:
      return "none";
    case HelixHand::kRight:
      return "right";
    case HelixHand::kLeft:
      return "left";
  }
  return "none";
}

json GearReport(const Scene& scene, const GearDef& def, const GearGeometry& g,
                const MeshDef& mesh) {
  if (g.kind == GearKind::kRack) {
    // It translates with its pinion's pitch line: v = Ω_pinion r_1 along Z × ê.
    return {{"name", def.name},
            {"rack", true},
            {"hand", HandName(g.hand)},
            {"tip_thickness_normal", g.tip_thickness_normal},
            {"face_width", g.face_width},
            {"mass", def.mass ? json(*def.mass) : json(nullptr)},
            {"inertia", def.inertia ? json(*def.inertia) : json(nullptr)},
            {"speed_m_per_s",
             scene.GearSpeed(mesh.pinion) * mesh.geometry.pinion.operating_pitch_radius}};
  }
  return {{"name", def.name},
          {"teeth", g.teeth},
          {"internal", g.kind == GearKind::kInternal},
          {"hand", HandName(g.hand)},
          {"reference_radius", g.reference_radius},
          {"base_radius", g.base_radius},
          {"tip_radius", g.tip_radius},
          {"root_radius", g.root_radius},
          {"operating_pitch_radius", g.operating_pitch_radius},
          {"virtual_teeth", g.virtual_teeth},
          {"tip_thickness_normal", g.tip_thickness_normal},
          {"profile_shift", g.profile_shift},
          {"face_width", g.face_width},
          {"mass", def.mass ? json(*def.mass) : json(nullptr)},  // optional in a scene
          {"inertia", def.inertia ? json(*def.inertia) : json(nullptr)},
          {"speed_rpm", RadPerSecToRpm(scene.GearSpeed(def.name))}};
}

json MeshReport(const Scene& scene, const MeshDef& mesh) {
  const GearPairGeometry& g = mesh.geometry;
  IsoStiffnessOptions iso_options;
  iso_options.line_load = geardyn::MeshLineLoad(scene, mesh);  // K_A = 1, nullopt off the op. gear
  const IsoMeshStiffness iso = CalcIsoMeshStiffness(g, iso_options);
  const double f_mesh = scene.MeshFrequencyHz(mesh);
  json r = {
      {"name", mesh.name},
      {"pinion", mesh.pinion},
      {"gear", mesh.gear},
      {"internal", g.internal},
      {"rack", g.rack},
      {"normal_module", g.spec.normal_module},
      {"transverse_module", g.transverse_module},
      {"normal_pressure_angle_deg", RadToDeg(g.spec.normal_pressure_angle)},
      {"transverse_pressure_angle_deg", RadToDeg(g.transverse_pressure_angle)},
      {"operating_pressure_angle_deg", RadToDeg(g.operating_pressure_angle)},
      {"helix_angle_deg", RadToDeg(g.spec.helix_angle)},
      {"base_helix_angle_deg", RadToDeg(g.base_helix_angle)},
      {"center_distance", g.center_distance},
      {"reference_center_distance", g.reference_center_distance},
      {"zero_backlash_center_distance", g.zero_backlash_center_distance},
      {"backlash_circumferential", g.backlash_circumferential},
      {"backlash_normal", g.backlash_normal},
      {"interference_normal", g.interference_normal},
      {"base_pitch", g.transverse_base_pitch},
      {"normal_base_pitch", g.normal_base_pitch},
      {"line_of_action_length", g.line_of_action_length},
      {"face_width", g.face_width},
      {"transverse_contact_ratio", g.transverse_contact_ratio},
      {"overlap_contact_ratio", g.overlap_contact_ratio},
      {"total_contact_ratio", g.total_contact_ratio},
      {"gear_ratio", g.gear_ratio},
      {"base_radius_pinion", g.pinion.base_radius},
      {"base_radius_gear", g.gear.base_radius},
      {"tip_radius_pinion", g.pinion.tip_radius},
      {"tip_radius_gear", g.gear.tip_radius},
      {"mean_contact_line_length", g.mean_contact_line_length},
      {"min_contact_line_length", g.min_contact_line_length},
      {"max_contact_line_length", g.max_contact_line_length},
      {"single_tooth_stiffness", iso.single_pair},
      {"mesh_stiffness_alpha", iso.mesh_alpha},
      {"mesh_stiffness_beta", iso.mesh_beta},
      {"iso_line_load", iso_options.line_load ? json(*iso_options.line_load) : json(nullptr)},
      {"iso_factors",
       {{"C_M", iso.blank_factor}, {"C_R", iso.rim_factor}, {"C_B", iso.basic_rack_factor}}},
      {"mesh_frequency_hz", f_mesh},
      {"teeth_gcd", g.teeth_gcd},
      {"hunting_period_meshes", g.hunting_period_meshes},
      {"hunting_period_s",
       f_mesh > 0.0 ? json(static_cast<double>(g.hunting_period_meshes) / f_mesh) : json(nullptr)},
  };
  // Inputs accepted with an adjustment (geometry) and ISO 6336-1 validity notes.
  json warnings = json::array();
  for (const std::string& w : g.warnings) warnings.push_back("mesh." + mesh.name + ": " + w);
  for (const std::string& w : iso.warnings) warnings.push_back("mesh." + mesh.name + ": " + w);
  // The model's own notes (drive-sign fallbacks, keys without effect on the built core), as the
  // analyses print them; the mean operator suffices (ε, the costly part with tooth errors, only
  // adds its own size checks, which the analyses that need it report).
  // A tooth-contact mesh has no contact-line core (BuildMeshCore refuses it: time domain only);
  // info shows its [mesh.contact] settings and the tooth DOF it adds instead.
  if (mesh.model.level == MeshModelLevel::kContact) {
    const ContactMeshDef def = mesh.model.contact.value_or(ContactMeshDef{});
    const int per_tooth = ToothDofs(def.teeth);
    r["contact"] = {{"teeth", ToString(def.teeth)},
                    {"tooth_dofs", per_tooth * (g.pinion.teeth + g.gear.teeth)},
                    {"law", ToString(def.law.kind)},
                    {"friction_coefficient", def.friction_coefficient},
                    {"profile", ToString(def.profile)},
                    {"face_slices", def.face_slices}};
  } else {
    for (const std::string& w : BuildMeshCore(scene, mesh, /*transmission_error=*/false).warnings) {
      // Already "mesh.NAME: …"; the ISO notes among them are listed above.
      if (std::find(warnings.begin(), warnings.end(), json(w)) == warnings.end()) {
        warnings.push_back(w);
      }
    }
  }
  r["warnings"] = warnings;
  return r;
}

json Units() {
  return {{"lengths", "m"},
          {"angles", "deg where the key ends in _deg, else rad"},
          {"stiffness_per_face_width", "N/m per m of face width (N/m^2); 1 N/(mm um) = 1e9"},
          {"line_load", "N/m"},
          {"mass", "kg"},
          {"inertia", "kg m^2"},
          {"torque", "N m"},
          {"frequency", "Hz"},
          {"speed", "rpm"}};
}

}  // namespace

nlohmann::json MakeInfoReport(const Scene& scene) {
  json report;
  report["scene"] = {{"source", scene.source}, {"title", scene.title}};
  if (scene.oscillator) {
    // An oscillator scene: its parameters and the scaling of its model (oscillator_system.hpp).
    const OscillatorDef& o = *scene.oscillator;
    report["oscillator"] = {
        {"equation",
         "x'' + 2 zeta x' + (1 + alpha cos(Omega t)) g(x) = F_m + F_a cos(Omega t + phi)"},
        {"zeta", o.zeta},
        {"alpha", o.alpha},
        {"mean_force", o.mean_force},
        {"alternating_force", o.alternating_force},
        {"force_phase_deg", o.force_phase * 180.0 / std::numbers::pi},
        {"backlash", o.backlash},
        {"back_contact", o.back_contact},
        {"model", ToString(o.model)},
        {"frequency_ratio", o.frequency_ratio},
        {"natural_frequency_hz", kOscillatorNaturalFrequencyHz},
        {"scaling",
         "dimensionless: the model's natural frequency is 1 Hz, so a mesh frequency in Hz "
         "(hb, floquet, simulate) is the frequency ratio Omega = omega_m/omega_n, and the DTE "
         "is x in units of the half backlash b"}};
    report["units"] = {{"x", "-"}, {"frequency", "Omega = omega_m/omega_n (Hz of the 1 Hz model)"}};
    return report;
  }
  report["units"] = Units();
  report["operating_point"] = {{"body", scene.operating_point.body},
                               {"speed_rpm", RadPerSecToRpm(scene.operating_point.speed)},
                               {"torque", scene.operating_point.torque}};
  json gears = json::array();
  json meshes = json::array();
  for (const MeshDef& mesh : scene.meshes) {
    meshes.push_back(MeshReport(scene, mesh));
  }
  for (const GearDef& def : scene.gears) {
    // A gear's geometry comes from (any) mesh it takes part in; a gear in no mesh has none.
    for (const MeshDef& mesh : scene.meshes) {
      if (mesh.pinion == def.name || mesh.gear == def.name) {
        gears.push_back(GearReport(
            scene, def, mesh.pinion == def.name ? mesh.geometry.pinion : mesh.geometry.gear, mesh));
        break;
      }
    }
  }
  report["gears"] = gears;
  report["meshes"] = meshes;
  report["shafts"] = MakeShaftsReport(scene);
  report["damping"] = MakeSystemDampingReport(scene);
  report["counts"] = {{"gears", scene.gears.size()},
                      {"meshes", scene.meshes.size()},
                      {"bearings", scene.bearings.size()},
                      {"shafts", scene.shafts.size()},
                      {"loads", scene.loads.size()}};
  return report;
}

namespace {

void Line(std::ostringstream& out, const std::string& label, double value, const std::string& unit,
          int precision = 6) {
  out << "  " << std::left << std::setw(34) << label << std::right << std::setw(14)
      << std::setprecision(precision) << value << " " << unit << "\n";
}

}  // namespace

std::string FormatInfoText(const nlohmann::json& report) {
  std::ostringstream out;
  out << "scene: " << report["scene"]["source"].get<std::string>();
  const std::string title = report["scene"]["title"].get<std::string>();
  if (!title.empty()) out << " — " << title;
  out << "\n";
  if (report.contains("oscillator")) {
    const json& o = report["oscillator"];
    out << "oscillator (dimensionless): " << o["equation"].get<std::string>() << "\n";
    Line(out, "zeta", o["zeta"].get<double>(), "-");
    Line(out, "alpha", o["alpha"].get<double>(), "-");
    Line(out, "mean force F_m", o["mean_force"].get<double>(), "-");
    Line(out, "alternating force F_a", o["alternating_force"].get<double>(), "-");
    Line(out, "force phase phi", o["force_phase_deg"].get<double>(), "deg");
    out << "  g(x): "
        << (o["backlash"].get<bool>()
                ? (o["back_contact"].get<bool>() ? "clearance, both flanks (|x| <= 1 free)"
                                                 : "clearance, front flank only (x <= 1 free)")
                : "linear, g(x) = x")
        << "; model " << o["model"].get<std::string>() << "\n";
    Line(out, "frequency ratio Omega", o["frequency_ratio"].get<double>(), "-");
    out << "  scaling: " << o["scaling"].get<std::string>() << "\n";
    return out.str();
  }
  const json& op = report["operating_point"];
  out << "operating point: " << op["speed_rpm"].get<double>() << " rpm, "
      << op["torque"].get<double>() << " N·m on " << op["body"].get<std::string>() << "\n";
  for (const json& gear : report["gears"]) {
    if (gear.contains("rack")) {
      out << "\ngear " << gear["name"].get<std::string>() << " (rack, hand "
          << gear["hand"].get<std::string>() << ")\n";
      Line(out, "normal top land", 1e3 * gear["tip_thickness_normal"].get<double>(), "mm");
      Line(out, "speed", gear["speed_m_per_s"].get<double>(), "m/s");
      continue;
    }
    out << "\ngear " << gear["name"].get<std::string>() << " (" << gear["teeth"].get<int>()
        << " teeth" << (gear["internal"].get<bool>() ? ", internal" : "") << ", hand "
        << gear["hand"].get<std::string>() << ")\n";
    Line(out, "reference radius", 1e3 * gear["reference_radius"].get<double>(), "mm");
    Line(out, "base radius", 1e3 * gear["base_radius"].get<double>(), "mm");
    Line(out, "tip radius", 1e3 * gear["tip_radius"].get<double>(), "mm");
    Line(out, "root radius", 1e3 * gear["root_radius"].get<double>(), "mm");
    Line(out, "operating pitch radius", 1e3 * gear["operating_pitch_radius"].get<double>(), "mm");
    Line(out, "normal tooth thickness at tip", 1e3 * gear["tip_thickness_normal"].get<double>(),
         "mm");
    Line(out, "speed", gear["speed_rpm"].get<double>(), "rpm");
  }
  for (const json& mesh : report["meshes"]) {
    out << "\nmesh " << mesh["name"].get<std::string>() << " (" << mesh["pinion"].get<std::string>()
        << " → " << mesh["gear"].get<std::string>()
        << (mesh["internal"].get<bool>() ? ", internal" : "") << ")\n";
    Line(out, "centre distance", 1e3 * mesh["center_distance"].get<double>(), "mm");
    Line(out, "operating pressure angle", mesh["operating_pressure_angle_deg"].get<double>(),
         "deg");
    Line(out, "base helix angle", mesh["base_helix_angle_deg"].get<double>(), "deg");
    Line(out, "transverse base pitch", 1e3 * mesh["base_pitch"].get<double>(), "mm");
    Line(out, "length of path of contact", 1e3 * mesh["line_of_action_length"].get<double>(), "mm");
    Line(out, "transverse contact ratio", mesh["transverse_contact_ratio"].get<double>(), "");
    Line(out, "overlap contact ratio", mesh["overlap_contact_ratio"].get<double>(), "");
    Line(out, "total contact ratio", mesh["total_contact_ratio"].get<double>(), "");
    Line(out, "normal backlash", 1e6 * mesh["backlash_normal"].get<double>(), "µm");
    Line(out, "contact line length mean", 1e3 * mesh["mean_contact_line_length"].get<double>(),
         "mm");
    Line(out, "contact line length min", 1e3 * mesh["min_contact_line_length"].get<double>(), "mm");
    Line(out, "contact line length max", 1e3 * mesh["max_contact_line_length"].get<double>(), "mm");
    Line(out, "single-pair stiffness c'", 1e-9 * mesh["single_tooth_stiffness"].get<double>(),
         "N/(mm·µm)");
    Line(out, "mesh stiffness c_γα", 1e-9 * mesh["mesh_stiffness_alpha"].get<double>(),
         "N/(mm·µm)");
    Line(out, "mesh stiffness c_γβ", 1e-9 * mesh["mesh_stiffness_beta"].get<double>(), "N/(mm·µm)");
    Line(out, "mesh frequency", mesh["mesh_frequency_hz"].get<double>(), "Hz");
    out << "  " << std::left << std::setw(34) << "hunting period" << std::right << std::setw(14)
        << mesh["hunting_period_meshes"].get<long>() << " mesh cycles\n";
    if (mesh.contains("contact")) {
      const json& c = mesh["contact"];
      out << "  model contact (time-domain only: geardyn simulate): teeth "
          << c["teeth"].get<std::string>() << " (" << c["tooth_dofs"].get<int>()
          << " tooth DOF), law " << c["law"].get<std::string>() << ", friction "
          << c["friction_coefficient"].get<double>() << ", " << c["profile"].get<std::string>()
          << " flanks, " << c["face_slices"].get<int>() << " face slice(s)\n";
    }
    for (const json& w : mesh["warnings"]) out << "warning: " << w.get<std::string>() << "\n";
  }
  FormatShaftsText(report, out);
  return out.str();
}

}  // namespace geardyn::app
