// Output of ComputeModes: JSON (frequencies_hz plus per-mode details) and the per-mode CSV table.
// Written by hand (geardyn::analyses links geardyn::core only, which has no JSON library).
#include <cmath>
#include <cstdio>
#include <sstream>
#include <string>
#include <vector>

#include "geardyn/analyses/modal.hpp"

namespace geardyn {
namespace {

std::string Number(double x) {
  if (!std::isfinite(x)) return "null";
  char buffer[32];
  std::snprintf(buffer, sizeof(buffer), "%.17g", x);
  return buffer;
}

std::string Quote(const std::string& s) {
  std::string out = "\"";
  for (const char c : s) {
    switch (c) {
      case '"':
        out += "\\\"";
        break;
      case '\\':
        out += "\\\\";
        break;
      case '\n':
        out += "\\n";
        break;
      case '\t':
        out += "\\t";
        break;
      default:
        if (static_cast<unsigned char>(c) < 0x20) {
          char buffer[8];
          std::snprintf(buffer, sizeof(buffer), "\\u%04x", static_cast<unsigned>(c));
          out += buffer;
        } else {
          out += c;  // UTF-8 bytes pass through
        }
    }
  }
  return out + "\"";
}

// CSV field: quoted when it holds a comma, a quote or a newline.
std::string CsvField(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string out = "\"";
  for (const char c : s) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

constexpr DofKind kKinds[kNumDofKinds] = {DofKind::kTranslationTransverse,
                                          DofKind::kTranslationAxial, DofKind::kRotationAxial,
                                          DofKind::kRotationTilt};

std::vector<int> MultiplicityOfMode(const ModalResult& r) {
  std::vector<int> mult(static_cast<std::size_t>(r.frequencies_hz.size()), 1);
  for (const std::vector<int>& g : r.multiplicity_groups) {
    for (const int k : g) mult[static_cast<std::size_t>(k)] = static_cast<int>(g.size());
  }
  return mult;
}

}  // namespace

std::string ModalResultToJson(const ModalResult& r) {
  std::ostringstream out;
  const Eigen::Index m = r.frequencies_hz.size();
  const std::vector<int> mult = MultiplicityOfMode(r);
  const bool fractions = r.kinetic_fractions.rows() == m && m > 0;
  out << "{\n  \"method_used\": " << Quote(ToString(r.method_used))
      << ",\n  \"status\": " << Quote(StatusName(r.summary.status))
      << ",\n  \"message\": " << Quote(r.summary.message) << ",\n  \"warnings\": [";
  for (std::size_t i = 0; i < r.summary.warnings.size(); ++i) {
    out << (i ? ", " : "") << Quote(r.summary.warnings[i]);
  }
  out << "],\n  \"wall_time_s\": " << Number(r.summary.wall_time_s)
      << ",\n  \"residual\": " << Number(r.summary.error_estimate)
      << ",\n  \"num_rigid_body_modes\": " << r.num_rigid_body_modes
      << ",\n  \"damping_kind\": " << Quote(ToString(r.damping_kind));
  if (r.damping_kind == DampingKind::kRayleigh) {
    out << ",\n  \"rayleigh\": {\"alpha\": " << Number(r.rayleigh_alpha)
        << ", \"beta\": " << Number(r.rayleigh_beta) << "}";
  }
  out << ",\n  \"frequencies_hz\": [";
  for (Eigen::Index k = 0; k < m; ++k) out << (k ? ", " : "") << Number(r.frequencies_hz(k));
  out << "],\n  \"modes\": [";
  for (Eigen::Index k = 0; k < m; ++k) {
    out << (k ? ",\n" : "\n") << "    {\"index\": " << k
        << ", \"frequency_hz\": " << Number(r.frequencies_hz(k))
        << ", \"eigenvalue\": " << Number(r.eigenvalues(k))
        << ", \"multiplicity\": " << mult[static_cast<std::size_t>(k)];
    if (r.modal_damping_ratios.size() == m) {
      out << ", \"modal_damping_ratio\": " << Number(r.modal_damping_ratios(k));
    }
    if (static_cast<Eigen::Index>(r.planetary_labels.size()) == m) {
      out << ", \"planetary_type\": "
          << Quote(ToString(r.planetary_labels[static_cast<std::size_t>(k)]));
    }
    if (fractions) {
      out << ", \"label\": " << Quote(ToString(r.labels[static_cast<std::size_t>(k)]))
          << ", \"kinetic\": {";
      for (int c = 0; c < kNumDofKinds; ++c) {
        out << (c ? ", " : "") << Quote(ToString(kKinds[c])) << ": "
            << Number(r.kinetic_fractions(k, static_cast<int>(kKinds[c])));
      }
      out << "}, \"body_kinetic\": {";
      for (Eigen::Index b = 0; b < r.body_kinetic_fractions.cols(); ++b) {
        out << (b ? ", " : "") << Quote(r.body_names[static_cast<std::size_t>(b)]) << ": "
            << Number(r.body_kinetic_fractions(k, b));
      }
      out << "}, \"strain\": {";
      for (std::size_t s = 0; s < r.strain_names.size(); ++s) {
        out << (s ? ", " : "") << Quote(r.strain_names[s]) << ": "
            << Number(r.strain_fractions(k, static_cast<Eigen::Index>(s)));
      }
      out << "}";
    }
    out << "}";
  }
  out << (m ? "\n  ]" : "]") << ",\n  \"damped_modes\": [";
  for (std::size_t i = 0; i < r.damped_modes.size(); ++i) {
    const DampedMode& d = r.damped_modes[i];
    out << (i ? ",\n" : "\n") << "    {\"frequency_hz\": " << Number(d.frequency_hz)
        << ", \"natural_frequency_hz\": " << Number(d.natural_frequency_hz)
        << ", \"damping_ratio\": " << Number(d.damping_ratio) << ", \"eigenvalue\": ["
        << Number(d.eigenvalue.real()) << ", " << Number(d.eigenvalue.imag()) << "]}";
  }
  out << (r.damped_modes.empty() ? "]" : "\n  ]");
  if (r.shapes.cols() == m && m > 0) {
    out << ",\n  \"dof_names\": [";
    for (std::size_t i = 0; i < r.dof_names.size(); ++i) {
      out << (i ? ", " : "") << Quote(r.dof_names[i]);
    }
    out << "],\n  \"shapes\": [";
    for (Eigen::Index k = 0; k < m; ++k) {
      out << (k ? ",\n    [" : "\n    [");
      for (Eigen::Index i = 0; i < r.shapes.rows(); ++i) {
        out << (i ? ", " : "") << Number(r.shapes(i, k));
      }
      out << "]";
    }
    out << "\n  ]";
  }
  out << "\n}\n";
  return out.str();
}

std::string ModalResultToCsv(const ModalResult& r) {
  std::ostringstream out;
  const Eigen::Index m = r.frequencies_hz.size();
  const std::vector<int> mult = MultiplicityOfMode(r);
  const bool fractions = r.kinetic_fractions.rows() == m && m > 0;
  const bool ratios = r.modal_damping_ratios.size() == m && m > 0;
  out << "mode,frequency_hz,eigenvalue,multiplicity";
  const bool planetary = static_cast<Eigen::Index>(r.planetary_labels.size()) == m && m > 0;
  if (ratios) out << ",modal_damping_ratio";
  if (planetary) out << ",planetary_type";
  if (fractions) {
    out << ",label";
    for (const DofKind kind : kKinds)
      out << "," << CsvField(std::string("kinetic_") + ToString(kind));
    for (const std::string& name : r.strain_names) out << "," << CsvField("strain_" + name);
  }
  out << "\n";
  for (Eigen::Index k = 0; k < m; ++k) {
    out << k << "," << Number(r.frequencies_hz(k)) << "," << Number(r.eigenvalues(k)) << ","
        << mult[static_cast<std::size_t>(k)];
    if (ratios) out << "," << Number(r.modal_damping_ratios(k));
    if (planetary) out << "," << ToString(r.planetary_labels[static_cast<std::size_t>(k)]);
    if (fractions) {
      out << "," << ToString(r.labels[static_cast<std::size_t>(k)]);
      for (const DofKind kind : kKinds) {
        out << "," << Number(r.kinetic_fractions(k, static_cast<int>(kind)));
      }
      for (Eigen::Index s = 0; s < r.strain_fractions.cols(); ++s) {
        out << "," << Number(r.strain_fractions(k, s));
      }
    }
    out << "\n";
  }
  return out.str();
}

}  // namespace geardyn
