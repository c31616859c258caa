#include "geardyn/shaft_report.hpp"

#include <cmath>
#include <iomanip>
#include <numbers>
#include <string>

namespace geardyn::app {

using nlohmann::json;

json MakeShaftsReport(const Scene& scene) {
  json shafts = json::array();
  for (const ShaftDef& shaft : scene.shafts) {
    json sections = json::array();
    double mass = 0.0;
    for (const ShaftSectionDef& s : shaft.sections) {
      const double d_o = s.section.outer_diameter, d_i = s.section.inner_diameter;
      mass += shaft.material.density * std::numbers::pi / 4.0 * (d_o * d_o - d_i * d_i) * s.length;
      sections.push_back({{"length", s.length},
                          {"outer_diameter", d_o},
                          {"inner_diameter", d_i},
                          {"max_element_length", s.element_length}});
    }
    json gears = json::array();
    for (const ShaftGearDef& g : shaft.gears) {
      gears.push_back({{"gear", g.gear}, {"station", g.station}});
    }
    json bearings = json::array();
    for (const BearingDef& b : scene.bearings) {
      if (b.body == shaft.name) bearings.push_back({{"bearing", b.name}, {"station", *b.station}});
      if (b.other == shaft.name) {
        bearings.push_back({{"bearing", b.name}, {"station", *b.other_station}});
      }
    }
    const int nodes = static_cast<int>(shaft.nodes.size());
    shafts.push_back({{"name", shaft.name},
                      {"length", shaft.length()},
                      {"youngs_modulus", shaft.material.youngs_modulus},
                      {"shear_modulus", shaft.material.shear_modulus},
                      {"density", shaft.material.density},
                      {"mass", mass},
                      {"sections", sections},
                      {"nodes", nodes},
                      {"elements", nodes - 1},
                      {"dofs", 6 * nodes},
                      {"gears", gears},
                      {"bearings", bearings}});
  }
  return shafts;
}

json MakeSystemDampingReport(const Scene& scene) {
  const SystemDamping& d = scene.damping;
  if (d.has_modal()) {
    json j = {{"kind", "modal"}, {"modal_ratios", d.modal_ratios}};
    j["modal_ratio"] = d.modal_ratio.value_or(0.0);
    return j;
  }
  if (d.has_rayleigh()) {
    return {{"kind", "rayleigh"},
            {"rayleigh_alpha", d.rayleigh_alpha},
            {"rayleigh_beta", d.rayleigh_beta}};
  }
  return {{"kind", "none"}};
}

void FormatShaftsText(const json& report, std::ostringstream& out) {
  for (const json& s : report["shafts"]) {
    out << "\nshaft " << s["name"].get<std::string>() << " (" << s["elements"].get<int>()
        << " Timoshenko elements, " << s["nodes"].get<int>() << " nodes, " << s["dofs"].get<int>()
        << " DOFs)\n";
    out << "  length " << 1e3 * s["length"].get<double>() << " mm, mass " << s["mass"].get<double>()
        << " kg, E " << 1e-9 * s["youngs_modulus"].get<double>() << " GPa, G "
        << 1e-9 * s["shear_modulus"].get<double>() << " GPa, ρ " << s["density"].get<double>()
        << " kg/m³\n";
    for (const json& sec : s["sections"]) {
      out << "  section " << 1e3 * sec["length"].get<double>() << " mm, Ø "
          << 1e3 * sec["outer_diameter"].get<double>() << " mm";
      if (sec["inner_diameter"].get<double>() > 0.0) {
        out << " / " << 1e3 * sec["inner_diameter"].get<double>() << " mm bore";
      }
      out << "\n";
    }
    for (const json& g : s["gears"]) {
      out << "  gear " << g["gear"].get<std::string>() << " at " << 1e3 * g["station"].get<double>()
          << " mm\n";
    }
    for (const json& b : s["bearings"]) {
      out << "  bearing " << b["bearing"].get<std::string>() << " at "
          << 1e3 * b["station"].get<double>() << " mm\n";
    }
  }
  const json& d = report["damping"];
  const std::string kind = d["kind"].get<std::string>();
  if (kind == "modal") {
    out << "\nsystem damping: modal, ζ = " << d["modal_ratio"].get<double>();
    if (!d["modal_ratios"].empty()) out << " (lowest modes: " << d["modal_ratios"].dump() << ")";
    out << "\n";
  } else if (kind == "rayleigh") {
    out << "\nsystem damping: Rayleigh, α = " << d["rayleigh_alpha"].get<double>()
        << " 1/s, β = " << d["rayleigh_beta"].get<double>() << " s\n";
  }
}

void GroupShaftStrain(const Scene& scene, json* modes_report) {
  if (scene.shafts.empty()) return;
  for (json& mode : (*modes_report)["modes"]) {
    if (!mode.contains("strain")) continue;
    json grouped = json::object();
    for (auto it = mode["strain"].begin(); it != mode["strain"].end(); ++it) {
      std::string owner = it.key();
      for (const ShaftDef& shaft : scene.shafts) {
        if (owner.rfind("element:" + shaft.name + ".e", 0) == 0) owner = "shaft:" + shaft.name;
      }
      grouped[owner] = grouped.value(owner, 0.0) + it.value().get<double>();
    }
    mode["strain"] = grouped;
  }
}

}  // namespace geardyn::app
