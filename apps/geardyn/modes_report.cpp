#include "geardyn/modes_report.hpp"

#include <cstdio>
#include <sstream>

#include "geardyn/common/check.hpp"

namespace geardyn::app {
namespace {

using nlohmann::json;

// Short names of the kinetic-energy kinds in the text table.
std::string ShortKind(const std::string& kind) {
  if (kind == "translation_transverse") return "transverse";
  if (kind == "translation_axial") return "axial";
  if (kind == "rotation_axial") return "torsional";
  if (kind == "rotation_tilt") return "rocking";
  return kind;
}

std::string Percent(double fraction) {
  char buffer[16];
  std::snprintf(buffer, sizeof(buffer), "%5.1f %%", 100.0 * fraction);
  return buffer;
}

// The (name, fraction) of the largest entry of a {name: fraction} object ("", 0 when all are 0).
std::pair<std::string, double> Largest(const json& fractions) {
  std::pair<std::string, double> best{"", 0.0};
  for (auto it = fractions.begin(); it != fractions.end(); ++it) {
    if (it.value().is_number() && it.value().get<double>() > best.second) {
      best = {it.key(), it.value().get<double>()};
    }
  }
  return best;
}

std::string Pad(const std::string& s, std::size_t width) {
  // Column widths count characters, not UTF-8 bytes (names may hold θ).
  std::size_t chars = 0;
  for (const char c : s) chars += (static_cast<unsigned char>(c) & 0xC0) != 0x80;
  return s + std::string(chars < width ? width - chars : 1, ' ');
}

}  // namespace

ModalOptions MakeModesOptions(const ModesSettings& settings, int num_dofs) {
  GEARDYN_THROW_UNLESS(
      settings.num_modes >= 1,
      "--modes: must be ≥ 1 (the number of lowest modes wanted), got " << settings.num_modes);
  ModalOptions options;
  if (settings.method == "auto") {
    options.method = ModalMethod::kAuto;
  } else if (settings.method == "dense") {
    options.method = ModalMethod::kDense;
  } else if (settings.method == "arpack") {
    options.method = ModalMethod::kArpack;
  } else {
    GEARDYN_THROW_UNLESS(
        false, "--method: must be auto, dense or arpack, got '" << settings.method << "'");
  }
  options.num_modes = settings.num_modes >= num_dofs ? 0 : settings.num_modes;
  // All modes: only the dense solver gives them (ARPACK needs num_modes < n − 1, and kAuto would
  // read 0 as its default count).
  if (options.num_modes == 0 && options.method == ModalMethod::kAuto) {
    options.method = ModalMethod::kDense;
  }
  options.compute_energy_fractions = true;
  options.compute_shapes = settings.shapes;
  options.compute_damped = settings.damped;
  return options;
}

void AddMeshPreloadReport(const SceneSystem& built, nlohmann::json* report) {
  json list = json::array();
  for (const MeshPreload& p : built.mesh_preloads) {
    list.push_back({{"mesh", p.mesh},
                    {"force_n", p.force},
                    {"coefficient_n_per_m", p.coefficient},
                    {"line_length_m", p.line_length}});
  }
  (*report)["mesh_preload"] = list;
  (*report)["mesh_preload_rigid_modes"] = built.mesh_preload_rigid_modes;
}

nlohmann::json MakeModesReport(const std::string& scene_source, int num_dofs,
                               const ModalResult& result,
                               const std::vector<std::string>& scene_warnings) {
  json report = json::parse(ModalResultToJson(result));
  report["scene"] = scene_source;
  report["num_dofs"] = num_dofs;
  report["num_modes"] = result.frequencies_hz.size();
  report["multiplicity_groups"] = result.multiplicity_groups;
  for (std::size_t g = 0; g < result.multiplicity_groups.size(); ++g) {
    for (const int k : result.multiplicity_groups[g]) {
      report["modes"][static_cast<std::size_t>(k)]["group"] = g;
    }
  }
  for (const std::string& w : scene_warnings) report["warnings"].push_back("scene: " + w);
  return report;
}

std::string FormatModesText(const nlohmann::json& report) {
  std::ostringstream out;
  out << "scene: " << report["scene"].get<std::string>() << "\n"
      << report["num_dofs"].get<int>() << " DOFs, " << report["num_modes"].get<int>() << " modes ("
      << report["num_rigid_body_modes"].get<int>() << " rigid-body), method "
      << report["method_used"].get<std::string>() << ", status "
      << report["status"].get<std::string>();
  if (!report["message"].get<std::string>().empty()) {
    out << ": " << report["message"].get<std::string>();
  }
  out << "\n";
  if (report.contains("mesh_preload")) {
    // --loaded: what the tangent stiffness added (mesh_preload_stiffness.hpp).
    out << "about the loaded state: mesh preload stiffness κ = −F̄ cos ψ_b / L across each line "
           "of action\n";
    for (const json& p : report["mesh_preload"]) {
      char line[160];
      std::snprintf(line, sizeof(line), "  mesh %s: F̄ = %.6g N, κ = %.6g N/m\n",
                    p["mesh"].get<std::string>().c_str(), p["force_n"].get<double>(),
                    p["coefficient_n_per_m"].get<double>());
      out << line;
    }
    if (report.value("mesh_preload_rigid_modes", 0) > 0) {
      out << "  kept as zero modes: the " << report["mesh_preload_rigid_modes"].get<int>()
          << " rigid-body mode(s) of the unloaded system (the preload projected off them)\n";
    }
  }
  out << "\n";
  out << Pad("mode", 6) << Pad("f [Hz]", 15) << Pad("type", 15) << Pad("kinetic (dominant)", 22)
      << Pad("strain energy (largest)", 40) << "group\n";
  for (const json& mode : report["modes"]) {
    char frequency[32];
    std::snprintf(frequency, sizeof(frequency), "%.6g", mode["frequency_hz"].get<double>());
    std::string kinetic = "—", strain = "—";
    if (mode.contains("kinetic")) {
      const auto [kind, fraction] = Largest(mode["kinetic"]);
      if (!kind.empty()) kinetic = ShortKind(kind) + " " + Percent(fraction);
      const auto [owner, share] = Largest(mode["strain"]);
      if (!owner.empty()) strain = owner + " " + Percent(share);
    }
    // Planetary sets: the Lin & Parker type (rotational/translational/planet) of the group.
    const std::string label =
        mode.contains("planetary_type")
            ? mode["planetary_type"].get<std::string>()
            : (mode.contains("label") ? mode["label"].get<std::string>() : "—");
    std::string group = std::to_string(mode.value("group", 0));
    if (mode["multiplicity"].get<int>() > 1) {
      group += " (×" + std::to_string(mode["multiplicity"].get<int>()) + ")";
    }
    out << Pad(std::to_string(mode["index"].get<int>()), 6) << Pad(frequency, 15) << Pad(label, 15)
        << Pad(kinetic, 22) << Pad(strain, 40) << group << "\n";
  }
  if (!report["damped_modes"].empty()) {
    out << "\ndamped modes (damping: " << report["damping_kind"].get<std::string>() << ")\n"
        << Pad("mode", 6) << Pad("f_d [Hz]", 15) << Pad("f_n [Hz]", 15) << "ζ\n";
    int k = 0;
    for (const json& d : report["damped_modes"]) {
      char fd[32], fn[32], zeta[32];
      std::snprintf(fd, sizeof(fd), "%.6g", d["frequency_hz"].get<double>());
      std::snprintf(fn, sizeof(fn), "%.6g", d["natural_frequency_hz"].get<double>());
      std::snprintf(zeta, sizeof(zeta), "%.4g", d["damping_ratio"].get<double>());
      out << Pad(std::to_string(k++), 6) << Pad(fd, 15) << Pad(fn, 15) << zeta << "\n";
    }
  }
  for (const json& w : report["warnings"]) out << "warning: " << w.get<std::string>() << "\n";
  return out.str();
}

std::string FormatModeShapesCsv(const ModalResult& result) {
  const Eigen::Index m = result.shapes.cols();
  if (m == 0) return "";
  std::ostringstream out;
  out << "dof";
  for (Eigen::Index k = 0; k < m; ++k) out << ",mode_" << k;
  out << "\n";
  for (Eigen::Index i = 0; i < result.shapes.rows(); ++i) {
    out << result.dof_names[static_cast<std::size_t>(i)];
    for (Eigen::Index k = 0; k < m; ++k) {
      char buffer[32];
      std::snprintf(buffer, sizeof(buffer), "%.17g", result.shapes(i, k));
      out << "," << buffer;
    }
    out << "\n";
  }
  return out.str();
}

}  // namespace geardyn::app
