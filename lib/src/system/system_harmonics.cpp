#include "geardyn/system/system_harmonics.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <numbers>
#include <optional>

#include "geardyn/common/check.hpp"
#include "geardyn/common/overloaded.hpp"
#include "geardyn/system/system_steps.hpp"
#include "mesh_coefficients.hpp"
#include "mesh_core_values.hpp"

namespace geardyn {
namespace {

// Channels of the per-mesh value coefficient: K2 (00, 01, 11), C2 (00, 01, 11), load (0, 1).
constexpr int kNumValueChannels = 8;

void PackValues(const internal::MeshCoreValues& v, Eigen::Ref<VectorX> out) {
  out << v.stiffness(0, 0), v.stiffness(0, 1), v.stiffness(1, 1), v.damping(0, 0), v.damping(0, 1),
      v.damping(1, 1), v.load(0), v.load(1);
}

// The highest harmonic (in units of 1/P_k) of a coefficient over the core period P_k: Fourier
// series have their own terms, tables half their samples, steps none that matter here.
int HighestHarmonic(const Coefficient& coef, std::int64_t core_period) {
  const std::int64_t ratio = core_period / PeriodMeshes(coef);
  return std::visit(
      Overloaded{
          [](const ConstantCoefficient&) { return 0; },
          [](const PiecewiseConstantCoefficient&) { return 0; },
          [&](const FourierCoefficient& c) { return static_cast<int>(c.num_terms() * ratio); },
          [&](const TableCoefficient& c) { return static_cast<int>(c.num_samples() / 2 * ratio); },
      },
      coef);
}

// The 8 value channels of a mesh as a coefficient of its own phase (period 2π·P_k): exact steps
// when everything the channels depend on is stepwise, otherwise samples (see the header's
// "Exactness"). with_load = false: only the operator's coefficients count (K2, C2 exact for a
// stepwise stiffness even when ε is smooth; the load channels are then not meaningful).
Coefficient MeshValueCoefficient(const SystemMesh& mesh, std::int64_t core_period,
                                 int mesh_harmonics, bool with_load) {
  const std::vector<const Coefficient*> coefs =
      internal::MeshOperatorCoefficients(mesh.core, with_load);
  std::optional<SliceMeshWorkspace> slice_ws;
  if (const auto* slice = std::get_if<SliceMeshCore>(&mesh.core)) slice_ws.emplace(*slice);
  const auto eval = [&](double phase, Eigen::Ref<VectorX> out) {
    PackValues(
        internal::EvalMeshCoreValues(mesh.core, mesh.damping_coefficient,
                                     slice_ws ? &*slice_ws : nullptr, phase, internal::kWantAll),
        out);
  };
  const double period = 2.0 * std::numbers::pi * static_cast<double>(core_period);
  if (internal::AllStepwise(coefs)) {
    const std::vector<double> begins = internal::UnionBreakpoints(coefs, core_period, 0.0);
    const int num = static_cast<int>(begins.size());
    VectorX breakpoints(num);
    MatrixX values(kNumValueChannels, num);
    for (int k = 0; k < num; ++k) {
      breakpoints(k) = begins[k];
      const double end = k + 1 < num ? begins[k + 1] : period;
      eval(0.5 * (begins[k] + end), values.col(k));
    }
    if (num == 1) return ConstantCoefficient(values.col(0), core_period);  // no sinc round-off
    return PiecewiseConstantCoefficient(std::move(breakpoints), std::move(values), core_period);
  }
  int highest = 0;
  for (const Coefficient* c : coefs) highest = std::max(highest, HighestHarmonic(*c, core_period));
  const std::int64_t wanted = 2 * (static_cast<std::int64_t>(mesh_harmonics) + 2 * highest) + 2;
  // A whole number of samples per mesh cycle: a mesh-periodic channel (K of a pair with errors
  // over a hunting period) is then sampled at the same phases in every cycle, so its sampling
  // error stays mesh-periodic and the FFT puts nothing between the mesh orders (with, e.g., 546.04
  // samples per cycle the steps of a spur K leaked 1e-3 of the mesh line into every harmonic).
  const std::int64_t per_mesh =
      std::max<std::int64_t>(kMinSamplesPerMeshPeriod, (wanted + core_period - 1) / core_period);
  const std::int64_t samples = per_mesh * core_period;
  MatrixX table(kNumValueChannels, samples);
  const auto* linear = std::get_if<LinearMeshCore>(&mesh.core);
  if (linear == nullptr || PeriodMeshes(linear->stiffness()) == core_period) {
    for (std::int64_t s = 0; s < samples; ++s) {
      eval(period * static_cast<double>(s) / static_cast<double>(samples), table.col(s));
    }
    return TableCoefficient(std::move(table), core_period);
  }
  // A linear core whose ε has a longer period than its stiffness (tooth errors): K2 and C2 repeat
  // every `cycle` samples (a whole number per mesh), so they are evaluated over one stiffness
  // period only and reused; only ε is evaluated at every sample (a Fourier stiffness of N terms
  // otherwise costs N sin/cos per sample over the whole hunting period).
  const std::int64_t cycle = per_mesh * PeriodMeshes(linear->stiffness());
  std::vector<Matrix2> k2(static_cast<size_t>(cycle)), c2(static_cast<size_t>(cycle));
  for (std::int64_t s = 0; s < cycle; ++s) {
    const double theta = period * static_cast<double>(s) / static_cast<double>(samples);
    k2[static_cast<size_t>(s)] = EvalStiffnessCore(*linear, theta);
    c2[static_cast<size_t>(s)] = EvalDampingCore(*linear, theta, mesh.damping_coefficient);
  }
  internal::MeshCoreValues v;
  for (std::int64_t s = 0; s < samples; ++s) {
    const auto j = static_cast<size_t>(s % cycle);
    v.stiffness = k2[j];
    v.damping = c2[j];
    // K2 ε (for the mean-LTI level K2 is the constant K̄2: EvalTransmissionErrorLoad's rule).
    v.load = k2[j] * EvalTransmissionError(
                         *linear, period * static_cast<double>(s) / static_cast<double>(samples));
    PackValues(v, table.col(s));
  }
  return TableCoefficient(std::move(table), core_period);
}

}  // namespace

std::vector<MeshHarmonics> ExpandMeshHarmonics(const SystemModel& model, int num_harmonics) {
  GEARDYN_THROW_UNLESS(num_harmonics >= 0,
                       "ExpandMeshHarmonics: num_harmonics must be >= 0, got " << num_harmonics);
  CheckSingleMeshFrequency(model, "ExpandMeshHarmonics");
  const std::int64_t system_period = model.period_meshes();
  std::vector<MeshHarmonics> out;
  out.reserve(model.meshes().size());
  for (const SystemMesh& mesh : model.meshes()) {
    MeshHarmonics h;
    h.stiffness.assign(num_harmonics + 1, Matrix2c::Zero());
    h.damping.assign(num_harmonics + 1, Matrix2c::Zero());
    h.load.assign(num_harmonics + 1, Vector2c::Zero());
    const std::int64_t core_period = internal::MeshCorePeriod(mesh.core);
    // System harmonic m is mesh harmonic n = m / q (q = P / P_k); others vanish.
    const std::int64_t q = system_period / core_period;
    const int mesh_harmonics = static_cast<int>(num_harmonics / q);
    const FourierCoefficient series =
        ToFourier(MeshValueCoefficient(mesh, core_period, mesh_harmonics, true), mesh_harmonics);
    // K2, C2 from their own coefficients when those are stepwise but the load's are not (a spur
    // pair with a smooth ε): exact sinc sums instead of sampled steps.
    std::optional<FourierCoefficient> operator_series;
    if (!internal::AllStepwise(internal::MeshOperatorCoefficients(mesh.core, true)) &&
        internal::AllStepwise(internal::MeshOperatorCoefficients(mesh.core, false))) {
      operator_series =
          ToFourier(MeshValueCoefficient(mesh, core_period, mesh_harmonics, false), mesh_harmonics);
    }
    for (int n = 0; n <= mesh_harmonics; ++n) {
      VectorXc c = n == 0 ? VectorXc(series.mean().cast<std::complex<double>>())
                          : VectorXc(series.harmonics().col(n - 1));
      if (operator_series) {
        c.head<6>() = n == 0
                          ? VectorXc(operator_series->mean().cast<std::complex<double>>()).head<6>()
                          : VectorXc(operator_series->harmonics().col(n - 1).head<6>());
      }
      // θ_k = θ + φ_k: the mesh's e^{inθ_k/P_k} is e^{inφ_k/P_k} e^{imθ/P} in system phase.
      c *= std::polar(
          1.0, static_cast<double>(n) * mesh.phase_offset / static_cast<double>(core_period));
      const auto m = static_cast<std::size_t>(n * q);
      h.stiffness[m] << c(0), c(1), c(1), c(2);
      h.damping[m] << c(3), c(4), c(4), c(5);
      h.load[m] << c(6), c(7);
    }
    out.push_back(std::move(h));
  }
  return out;
}

SystemHarmonics AssembleSystemHarmonics(const SystemModel& model,
                                        const std::vector<MeshHarmonics>& meshes) {
  GEARDYN_CHECK_SIZE(meshes.size(), model.meshes().size(), "AssembleSystemHarmonics: meshes");
  const int n = model.num_dofs();
  const int num = meshes.empty() ? 0 : static_cast<int>(meshes.front().stiffness.size()) - 1;
  SystemHarmonics out;
  out.period_meshes = model.period_meshes();
  out.stiffness.assign(num + 1, MatrixXc::Zero(n, n));
  out.damping.assign(num + 1, MatrixXc::Zero(n, n));
  out.load.assign(num + 1, VectorXc::Zero(n));
  out.stiffness[0] = model.DenseConstantStiffness().cast<std::complex<double>>();
  out.damping[0] = model.DenseConstantDamping().cast<std::complex<double>>();
  out.load[0] = model.constant_load().cast<std::complex<double>>();
  for (std::size_t k = 0; k < meshes.size(); ++k) {
    const SystemMesh& mesh = model.meshes()[k];
    const Eigen::Matrix<std::complex<double>, 2, 12> G = mesh.G.cast<std::complex<double>>();
    GEARDYN_CHECK_SIZE(static_cast<int>(meshes[k].stiffness.size()), num + 1,
                       "AssembleSystemHarmonics: harmonics of mesh '" << mesh.name << "'");
    for (int m = 0; m <= num; ++m) {
      const Eigen::Matrix<std::complex<double>, 12, 12> kb =
          G.transpose() * meshes[k].stiffness[m] * G;
      const Eigen::Matrix<std::complex<double>, 12, 12> cb =
          G.transpose() * meshes[k].damping[m] * G;
      const Eigen::Matrix<std::complex<double>, 12, 1> fb = G.transpose() * meshes[k].load[m];
      for (int b = 0; b < 12; ++b) {
        const int db = mesh.dofs[b];
        if (db < 0) continue;
        out.load[m](db) += fb(b);
        for (int a = 0; a < 12; ++a) {
          const int da = mesh.dofs[a];
          if (da < 0) continue;
          out.stiffness[m](da, db) += kb(a, b);
          out.damping[m](da, db) += cb(a, b);
        }
      }
    }
  }
  return out;
}

SystemHarmonics ExpandSystemHarmonics(const SystemModel& model, int num_harmonics) {
  return AssembleSystemHarmonics(model, ExpandMeshHarmonics(model, num_harmonics));
}

}  // namespace geardyn
