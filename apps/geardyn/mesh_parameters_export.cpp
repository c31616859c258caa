#include "geardyn/mesh_parameters_export.hpp"

#include <cmath>
#include <cstdio>
#include <sstream>

#include "geardyn/common/check.hpp"

namespace geardyn::app {
namespace {

// The arrays of the table in the reader's key order: (key, values).
using Columns = std::vector<std::pair<std::string, std::vector<double>>>;

Columns MakeColumns(const MeshParameterSamples& s) {
  const std::size_t n = s.stiffness.size();
  GEARDYN_THROW_UNLESS(n >= 1, "mesh " << s.mesh << ": quasi-static samples: none");
  GEARDYN_THROW_UNLESS(
      std::isfinite(s.half_face_width) && s.half_face_width > 0.0,
      "mesh " << s.mesh << ": half_face_width: must be > 0, got " << s.half_face_width);
  const auto check = [&](const std::vector<double>& v, const char* what) {
    GEARDYN_THROW_UNLESS(v.empty() || v.size() == n, "mesh " << s.mesh << ": " << what << ": "
                                                             << v.size() << " samples, stiffness "
                                                             << n);
    for (std::size_t i = 0; i < v.size(); ++i) {
      GEARDYN_THROW_UNLESS(std::isfinite(v[i]),
                           "mesh " << s.mesh << ": " << what << "[" << i << "]: not finite");
    }
  };
  check(s.stiffness, "stiffness");
  check(s.stiffness_h, "stiffness_h");
  check(s.stiffness_mu_b2, "stiffness_mu_b2");
  check(s.transmission_error, "transmission_error");
  for (std::size_t i = 0; i < n; ++i) {
    GEARDYN_THROW_UNLESS(s.stiffness[i] >= 0.0, "mesh " << s.mesh << ": stiffness[" << i
                                                        << "]: must be >= 0, got "
                                                        << s.stiffness[i]);
  }
  Columns columns = {{"stiffness", s.stiffness}};
  const double b2 = s.half_face_width * s.half_face_width;
  // h = K·h/K, μ = K·μ·b²/(K b²); both 0 without contact (K2 = 0 whatever they are).
  if (!s.stiffness_h.empty()) {
    std::vector<double> h(n, 0.0);
    for (std::size_t i = 0; i < n; ++i) {
      if (s.stiffness[i] > 0.0) h[i] = s.stiffness_h[i] / s.stiffness[i];
    }
    columns.emplace_back("load_centre", std::move(h));
  }
  if (!s.stiffness_mu_b2.empty()) {
    std::vector<double> mu(n, 0.0);
    for (std::size_t i = 0; i < n; ++i) {
      if (s.stiffness[i] > 0.0) mu[i] = s.stiffness_mu_b2[i] / (s.stiffness[i] * b2);
    }
    columns.emplace_back("mu", std::move(mu));
  }
  if (!s.transmission_error.empty()) columns.emplace_back("te_eta", s.transmission_error);
  return columns;
}

std::string Number(double v) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.17g", v);
  return text;
}

// "[a, b, c]"; with `wrap`, 4 numbers per line (a long table stays readable).
std::string Array(const std::vector<double>& v, bool wrap) {
  std::string text = "[";
  for (std::size_t i = 0; i < v.size(); ++i) {
    if (i > 0) text += (wrap && i % 4 == 0) ? ",\n  " : ", ";
    text += Number(v[i]);
  }
  return text + "]";
}

}  // namespace

std::string FormatMeshParametersToml(const MeshParameterSamples& samples,
                                     const std::vector<std::string>& comment) {
  const Columns columns = MakeColumns(samples);
  std::ostringstream out;
  for (const std::string& line : comment) out << "# " << line << "\n";
  out << "# Paste below the [[mesh]] table named \"" << samples.mesh << "\"; it replaces the\n"
      << "# contact lines: drop model = \"slices\", stiffness_per_length, [mesh.modifications]\n"
      << "# and [mesh.errors] there. One-line --set form: mesh_parameters_set.txt.\n"
      << "# " << samples.stiffness.size() << " samples over one mesh cycle, theta_s = 2 pi s / "
      << samples.stiffness.size() << ".\n";
  out << "[mesh.parameters]\nform = \"table\"\n";
  for (const auto& [key, values] : columns) out << key << " = " << Array(values, true) << "\n";
  return out.str();
}

std::string FormatMeshParametersOverride(const MeshParameterSamples& samples) {
  const Columns columns = MakeColumns(samples);
  std::string text = "mesh." + samples.mesh + ".parameters={form=\"table\"";
  for (const auto& [key, values] : columns) text += ", " + key + "=" + Array(values, false);
  return text + "}";
}

}  // namespace geardyn::app
