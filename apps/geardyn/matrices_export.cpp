#include "geardyn/matrices_export.hpp"

#include <complex>
#include <cstdio>
#include <sstream>

#include "geardyn/common/check.hpp"
#include "geardyn/models/system/scene_system.hpp"
#include "geardyn/output_files.hpp"
#include "geardyn/system/workspace.hpp"

namespace geardyn::app {
namespace {

std::string Number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof(buf), "%.17g", v);
  return buf;
}

std::string Header(const char* field, const std::string& comment, Eigen::Index rows,
                   Eigen::Index cols, Eigen::Index entries) {
  std::ostringstream s;
  s << "%%MatrixMarket matrix coordinate " << field << " general\n";
  if (!comment.empty()) s << "% " << comment << "\n";
  s << rows << " " << cols << " " << entries << "\n";
  return s.str();
}

template <typename Dense>
std::string DenseToMarket(const Dense& a, const char* field, const std::string& comment) {
  std::ostringstream body;
  Eigen::Index entries = 0;
  for (Eigen::Index j = 0; j < a.cols(); ++j) {
    for (Eigen::Index i = 0; i < a.rows(); ++i) {
      const std::complex<double> v = a(i, j);
      if (v == std::complex<double>(0.0)) continue;
      ++entries;
      body << i + 1 << " " << j + 1 << " " << Number(v.real());
      if (field[0] == 'c') body << " " << Number(v.imag());
      body << "\n";
    }
  }
  return Header(field, comment, a.rows(), a.cols(), entries) + body.str();
}

}  // namespace

std::string FormatMatrixMarket(const SparseMatrix& a, const std::string& comment) {
  std::ostringstream body;
  for (int j = 0; j < a.outerSize(); ++j) {
    for (SparseMatrix::InnerIterator it(a, j); it; ++it) {
      body << it.row() + 1 << " " << it.col() + 1 << " " << Number(it.value()) << "\n";
    }
  }
  return Header("real", comment, a.rows(), a.cols(), a.nonZeros()) + body.str();
}

std::string FormatMatrixMarket(const MatrixXc& a, const std::string& comment) {
  return DenseToMarket(a, "complex", comment);
}

std::string FormatMatrixMarket(const VectorX& v, const std::string& comment) {
  return DenseToMarket(v, "real", comment);
}

std::string FormatMatrixMarket(const VectorXc& v, const std::string& comment) {
  return DenseToMarket(v, "complex", comment);
}

SystemMatrices ExportSystemMatrices(const Scene& scene, int harmonics) {
  GEARDYN_THROW_UNLESS(
      harmonics >= 0 && harmonics <= kMaxExportHarmonics,
      "--harmonics: must be in [0, " << kMaxExportHarmonics << "], got " << harmonics);
  // The mean pencil as `geardyn modes` builds it: ε is forcing, not part of M, C̄, K̄.
  SceneSystemOptions options;
  options.analysis = "matrices";  // named if a mass is missing
  options.transmission_error = false;
  const SceneSystem built = BuildSceneSystem(scene, options);
  const SystemModel& model = built.model;
  SystemMatrices out;
  out.mean = AssembleMeanSystemMatrices(model);
  SystemWorkspace ws(model, StorageKind::kSparse);
  out.mean_load = AssembleMeanLoad(model, ws);
  const DofMap& map = model.dof_map();
  for (int i = 0; i < model.num_dofs(); ++i) {
    out.dof_names.push_back(map.dof_name(i));
    out.dof_bodies.push_back(map.body_name(map.dof_body(i)));
    out.dof_components.push_back(ToString(map.dof_component(i)));
    out.dof_kinds.push_back(ToString(map.dof_kind(i)));
  }
  out.mesh_frequency_hz = scene.NominalMeshFrequencyHz();
  std::vector<std::string> warnings = built.warnings;
  for (const std::string& w : out.mean.warnings) warnings.push_back(w);
  std::int64_t period = model.period_meshes();
  if (harmonics > 0) {
    // The periodic system with its transmission-error excitation (f_m).
    SceneSystemOptions periodic;
    periodic.analysis = "matrices";
    const SceneSystem with_errors = BuildSceneSystem(scene, periodic);
    out.harmonics = ExpandSystemHarmonics(with_errors.model, harmonics);
    period = out.harmonics.period_meshes;
  }

  nlohmann::json dofs = nlohmann::json::array();
  for (int i = 0; i < model.num_dofs(); ++i) {
    dofs.push_back({{"index", i},
                    {"name", out.dof_names[i]},
                    {"body", out.dof_bodies[i]},
                    {"component", out.dof_components[i]},
                    {"kind", out.dof_kinds[i]},
                    {"unit", out.dof_kinds[i].rfind("translation", 0) == 0 ? "m" : "rad"}});
  }
  nlohmann::json files = {
      {"mass", "M.mtx"}, {"damping", "C.mtx"}, {"stiffness", "K.mtx"}, {"mean_load", "f.mtx"}};
  nlohmann::json harmonic_files = nlohmann::json::array();
  for (int m = 1; m <= harmonics; ++m) {
    const std::string k = std::to_string(m);
    harmonic_files.push_back({{"m", m},
                              {"stiffness", "K_" + k + ".mtx"},
                              {"damping", "C_" + k + ".mtx"},
                              {"load", "f_" + k + ".mtx"}});
  }
  out.report = {
      {"scene", scene.source},
      {"num_dofs", model.num_dofs()},
      {"mesh_frequency_hz", out.mesh_frequency_hz},
      {"period_meshes", period},
      {"harmonics", harmonics},
      {"equation",
       "M q'' + C(θ) q' + K(θ) q = f(θ); K(θ) = K_0 + Σ_{m≥1} (K_m e^{imθ/P} + conj(K_m) "
       "e^{-imθ/P}), θ the mesh phase (2π per mesh cycle), P = period_meshes; M, C, K are the "
       "mean (LTI) system that `geardyn modes` solves"},
      {"units",
       {{"M", "kg, kg·m, kg·m² (rows/columns in the DOFs' units m or rad)"},
        {"C", "N·s/m, N·s, N·m·s"},
        {"K", "N/m, N, N·m"},
        {"f", "N, N·m"}}},
      {"files", files},
      {"harmonic_files", harmonic_files},
      {"dofs", dofs},
      {"warnings", warnings}};
  return out;
}

void WriteSystemMatrices(const SystemMatrices& m, const std::string& dir) {
  const std::string& source = m.report["scene"].get_ref<const std::string&>();
  WriteOutputFile(dir, "M.mtx", FormatMatrixMarket(m.mean.mass, "geardyn M [kg…] of " + source));
  WriteOutputFile(dir, "C.mtx",
                  FormatMatrixMarket(m.mean.damping, "geardyn mean C [N·s/m…] of " + source));
  WriteOutputFile(dir, "K.mtx",
                  FormatMatrixMarket(m.mean.stiffness, "geardyn mean K [N/m…] of " + source));
  WriteOutputFile(dir, "f.mtx",
                  FormatMatrixMarket(m.mean_load, "geardyn mean f [N…] of " + source));
  const SystemHarmonics& h = m.harmonics;
  for (int k = 1; k <= h.num_harmonics(); ++k) {
    const std::string s = std::to_string(k);
    WriteOutputFile(dir, "K_" + s + ".mtx",
                    FormatMatrixMarket(h.stiffness[k], "geardyn K_" + s + " of " + source));
    WriteOutputFile(dir, "C_" + s + ".mtx",
                    FormatMatrixMarket(h.damping[k], "geardyn C_" + s + " of " + source));
    WriteOutputFile(dir, "f_" + s + ".mtx",
                    FormatMatrixMarket(h.load[k], "geardyn f_" + s + " of " + source));
  }
  WriteOutputFile(dir, "dofs.json", m.report.dump(2) + "\n");
}

}  // namespace geardyn::app
