#include "geardyn/mesh_report.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <optional>
#include <sstream>
#include <string>
#include <type_traits>
#include <variant>

#include "geardyn/common/check.hpp"
#include "geardyn/common/units.hpp"
#include "geardyn/models/mesh/contact_lines.hpp"
#include "geardyn/models/mesh/stiffness_core.hpp"
#include "geardyn/models/scene/mesh_model.hpp"
#include "geardyn/models/scene/mesh_transmission_error.hpp"
#include "geardyn/svg_plot.hpp"

namespace geardyn::app {
namespace {

using nlohmann::json;

constexpr int kReportedHarmonics = 10;
constexpr int kDefaultSamplesPerMesh = 360;
constexpr int kMinAutoSamplesPerMesh = 16;

// The sampled window [mesh cycles]: --cycles, else the period up to kMaxAutoCycles.
std::int64_t WindowCycles(const MeshSamplingOptions& options, std::int64_t period_meshes) {
  if (options.cycles) return static_cast<std::int64_t>(*options.cycles);
  return std::min<std::int64_t>(period_meshes, MeshSamplingOptions::kMaxAutoCycles);
}

int SamplesPerMesh(const MeshSamplingOptions& options, std::int64_t cycles) {
  if (options.samples_per_mesh) return static_cast<int>(*options.samples_per_mesh);
  const long budget = MeshSamplingOptions::kMaxAutoSamples / std::max<std::int64_t>(1, cycles);
  return static_cast<int>(std::clamp<long>(budget, kMinAutoSamplesPerMesh, kDefaultSamplesPerMesh));
}

// What `rows` samples cost: memory and CSV size.
std::string RowCost(double rows) {
  std::ostringstream out;
  out << std::setprecision(3) << static_cast<double>(rows) * MeshSamplingOptions::kBytesPerRow / 1e9
      << " GB in memory, " << static_cast<double>(rows) * MeshSamplingOptions::kCsvBytesPerRow / 1e9
      << " GB of CSV";
  return out.str();
}

void AppendParameters(const MeshParameters& p, MeshSamples* s) {
  s->stiffness.push_back(p.stiffness);
  s->load_centre.push_back(p.load_centre);
  s->kappa.push_back(p.kappa);
  s->mu.push_back(p.mu);
}

// Samples a linear core: stiffness channels (K, K·h, K·μ·b²) from the core, ε from the exact
// model te when given (contact lines), else from the core (user parameters).
// scalar_te: the level keeps only ε_η (five_dof, B–S Eq. 42), so the exact ε_ζ of `te` is not
// the core's.
void SampleLinear(const LinearMeshCore& core, const TransmissionErrorModel* te, bool scalar_te,
                  const std::vector<double>& thetas, MeshSamples* s) {
  VectorX channels(LinearMeshCore::kNumStiffnessChannels);
  const double b = core.half_face_width();
  for (double theta : thetas) {
    Evaluate(core.stiffness(), theta, channels);
    AppendParameters(MeshParametersFromChannels(channels[0], channels[1], channels[2], b), s);
    if (te != nullptr || core.transmission_error()) {
      const Vector2 eps =
          te != nullptr ? te->CalcTransmissionError(theta) : EvalTransmissionError(core, theta);
      s->te_eta.push_back(eps[0]);
      s->te_zeta.push_back(scalar_te ? 0.0 : eps[1]);
    }
  }
}

// Samples a slice core with every slice loaded (its small-motion limit): the same channels as
// the contact lines, and ε = K2⁻¹ [Σ k_s e_s, −Σ k_s σ_s e_s] when slices carry separations.
void SampleSlices(const SliceMeshCore& core, const std::vector<double>& thetas, MeshSamples* s) {
  SliceMeshWorkspace ws(core);
  const double b = core.half_face_width();
  for (double theta : thetas) {
    EvalSliceValues(core, ws, theta);
    const double k = ws.stiffness.sum();
    const double kh = ws.stiffness.dot(core.sigma());
    const double kmu = ws.stiffness.dot(core.sigma().cwiseAbs2());
    AppendParameters(MeshParametersFromChannels(k, kh, kmu, b), s);
    if (core.separation()) {
      const Matrix2 K2 = (Matrix2() << k, -kh, -kh, kmu).finished();
      const double ke = ws.stiffness.dot(ws.separation);
      const double kse = ws.stiffness.cwiseProduct(core.sigma()).dot(ws.separation);
      const Vector2 eps = CalcTransmissionErrorPair(K2, ke, kse);
      s->te_eta.push_back(eps[0]);
      s->te_zeta.push_back(eps[1]);
    }
  }
}

json Range(const std::vector<double>& v) {
  if (v.empty()) return nullptr;
  const auto [lo, hi] = std::minmax_element(v.begin(), v.end());
  double sum = 0.0;
  for (double x : v) sum += x;
  return {{"min", *lo},
          {"max", *hi},
          {"mean", sum / static_cast<double>(v.size())},
          {"peak_to_peak", *hi - *lo}};
}

// Amplitudes 2|c_n| of the first harmonics of K (mesh orders n = 1, 2, …) from the core's own
// coefficient (exact for piecewise-constant and Fourier forms).
json StiffnessHarmonics(const MeshCore& core) {
  const Coefficient* coef = std::visit(
      [](const auto& c) -> const Coefficient* {
        using T = std::decay_t<decltype(c)>;
        if constexpr (std::is_same_v<T, LinearMeshCore>) {
          return &c.stiffness();
        } else {
          return nullptr;
        }
      },
      core);
  if (coef == nullptr) return nullptr;
  const FourierCoefficient f = ToFourier(*coef, kReportedHarmonics);
  json amplitudes = json::array();
  for (int n = 0; n < f.num_terms(); ++n) amplitudes.push_back(2.0 * std::abs(f.harmonics()(0, n)));
  return amplitudes;
}

}  // namespace

bool MeshSamplingOptions::IsValid(std::string* why) const {
  std::ostringstream out;
  if (cycles) {
    const double c = *cycles;
    if (!std::isfinite(c) || c != std::floor(c) || c < 1 || c > kMaxCycles) {
      out << "--cycles: must be an integer in [1, " << kMaxCycles << "], got " << c;
      if (why != nullptr) *why = out.str();
      return false;
    }
  }
  if (!samples_per_mesh) return true;
  const double n = *samples_per_mesh;
  if (!std::isfinite(n) || n != std::floor(n)) {
    out << "--samples: must be an integer, got " << n;
  } else if (n < 1) {
    out << "--samples: must be ≥ 1 (omit it for the automatic count), got " << n;
  } else if (n > kMaxSamplesPerMesh) {
    out << "--samples: must be ≤ " << kMaxSamplesPerMesh << " per mesh cycle, got " << n << " ("
        << RowCost(n) << " per mesh cycle)";
  } else {
    return true;
  }
  if (why != nullptr) *why = out.str();
  return false;
}

json MakeMeshReport(const Scene& scene, const MeshSamplingOptions& options,
                    std::vector<MeshSamples>* samples) {
  std::string why;
  GEARDYN_THROW_UNLESS(options.IsValid(&why), why);
  json meshes = json::array();
  samples->clear();
  for (const MeshDef& mesh : scene.meshes) {
    // The slice core keeps its separations (from ε); a linear core is built without ε, which is
    // evaluated exactly at the samples instead of tabulated over the hunting period.
    const bool slices = mesh.model.level == MeshModelLevel::kNonlinearSlices;
    const BuiltMeshCore built = BuildMeshCore(scene, mesh, /*transmission_error=*/slices);
    std::optional<TransmissionErrorModel> te;
    if (!slices && built.contact_lines) {
      te = MakeMeshTransmissionErrorModel(scene, mesh, *built.contact_lines);
    }
    const std::int64_t period = std::max(PeriodMeshes(built.core), te ? te->period_meshes() : 1);
    const std::int64_t cycles = WindowCycles(options, period);
    const int per_mesh = SamplesPerMesh(options, cycles);
    const std::int64_t count = cycles * per_mesh;
    GEARDYN_THROW_UNLESS(
        count <= MeshSamplingOptions::kMaxSamples,
        "--samples: " << per_mesh << " samples per mesh cycle × " << cycles << " mesh cycles ("
                      << (options.cycles ? "--cycles" : "mesh." + mesh.name + "'s period")
                      << ") = " << count << " rows exceed the limit "
                      << MeshSamplingOptions::kMaxSamples << " ("
                      << RowCost(static_cast<double>(count)) << "); use fewer samples or cycles");
    std::vector<std::string> warnings = built.warnings;
    if (!options.cycles && cycles < period) {
      warnings.push_back("mesh." + mesh.name + ": sampled over the first " +
                         std::to_string(cycles) + " of the " + std::to_string(period) +
                         " mesh cycles of its hunting period (--cycles to choose the window)");
    }
    MeshSamples s;
    s.mesh_name = mesh.name;
    std::vector<double> thetas(static_cast<size_t>(count));
    for (std::int64_t i = 0; i < count; ++i) {
      s.cycle.push_back(static_cast<double>(i) / per_mesh);
      thetas[static_cast<size_t>(i)] = 2.0 * kPi * s.cycle.back();
    }
    std::visit(
        [&](const auto& core) {
          using T = std::decay_t<decltype(core)>;
          if constexpr (std::is_same_v<T, LinearMeshCore>) {
            SampleLinear(core, te ? &*te : nullptr, mesh.model.level == MeshModelLevel::kFiveDof,
                         thetas, &s);
          } else if constexpr (std::is_same_v<T, SliceMeshCore>) {
            SampleSlices(core, thetas, &s);
          } else {
            GEARDYN_THROW_UNLESS(false, "mesh." << mesh.name
                                                << ": a nonlinear contact core has no sampled "
                                                   "mesh parameters");
          }
        },
        built.core);
    json m = {{"name", mesh.name},
              {"level", ToString(mesh.model.level)},
              {"time_dependence", TimeDependenceName(Classify(built.core))},
              {"drive_sign", built.drive_sign},
              {"period_meshes", period},
              {"cycles", cycles},
              {"samples_per_mesh", per_mesh},
              {"stiffness", Range(s.stiffness)},
              {"load_centre", Range(s.load_centre)},
              {"kappa", Range(s.kappa)},
              {"mu", Range(s.mu)},
              {"te_eta", Range(s.te_eta)},
              {"te_zeta", Range(s.te_zeta)},
              {"stiffness_harmonic_amplitudes", StiffnessHarmonics(built.core)},
              {"warnings", warnings}};
    // The mean of K over whole periods is the coefficient's exact mean, not the rectangle rule of
    // the samples (0.1 % low on the rig's rectangular wave at 360 samples: 3.97324e8 against
    // c_γα·b = 3.97754e8, which `info` prints).
    if (const auto* linear = std::get_if<LinearMeshCore>(&built.core);
        linear != nullptr && cycles % PeriodMeshes(built.core) == 0) {
      m["stiffness"]["mean"] = Mean(linear->stiffness())[0];
    }
    meshes.push_back(m);
    samples->push_back(std::move(s));
  }
  return {{"scene", {{"source", scene.source}, {"title", scene.title}}},
          {"units",
           {{"stiffness", "N/m"},
            {"load_centre", "m (along the contact lines from the pitch point)"},
            {"kappa", "-"},
            {"mu", "-"},
            {"te_eta", "m"},
            {"te_zeta", "rad"},
            {"cycle", "mesh cycles (theta / 2 pi)"}}},
          {"meshes", meshes}};
}

std::string FormatMeshCsv(const MeshSamples& s) {
  std::ostringstream out;
  out.precision(12);
  const bool te = !s.te_eta.empty();
  out << "cycle,stiffness_N_per_m,load_centre_m,kappa,mu" << (te ? ",te_eta_m,te_zeta_rad" : "")
      << "\n";
  for (size_t i = 0; i < s.cycle.size(); ++i) {
    out << s.cycle[i] << "," << s.stiffness[i] << "," << s.load_centre[i] << "," << s.kappa[i]
        << "," << s.mu[i];
    if (te) out << "," << s.te_eta[i] << "," << s.te_zeta[i];
    out << "\n";
  }
  return out.str();
}

std::string RenderMeshSvg(const MeshSamples& s, const std::string& title) {
  PlotSpec spec;
  spec.title = title;
  spec.x_label = "mesh cycles θ/2π [-]";
  auto add = [&](const char* label, const std::vector<double>& y) {
    PlotPanel panel;
    panel.y_label = label;
    PlotSeries series;
    series.x = s.cycle;
    series.y = y;
    panel.series.push_back(std::move(series));
    spec.panels.push_back(std::move(panel));
  };
  add("K [N/m]", s.stiffness);
  add("h [m]", s.load_centre);
  add("μ [-]", s.mu);
  if (!s.te_eta.empty()) {
    add("ε_η [m]", s.te_eta);
    add("ε_ζ [rad]", s.te_zeta);
  }
  return RenderSvg(spec);
}

}  // namespace geardyn::app
