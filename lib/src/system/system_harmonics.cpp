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

// True for a linear core whose ε repeats over a longer period than its stiffness (tooth errors)
// and has a finite series (Fourier, or a table as its trigonometric interpolant): the load
// harmonics are then the convolution of those of K2 and ε (ErrorPeriodValueHarmonics).
bool HasErrorPeriodLoad(const MeshCore& core, std::int64_t core_period) {
  const auto* linear = std::get_if<LinearMeshCore>(&core);
  if (linear == nullptr || !linear->transmission_error()) return false;
  if (PeriodMeshes(linear->stiffness()) >= core_period) return false;
  const Coefficient& eps = *linear->transmission_error();
  return std::holds_alternative<FourierCoefficient>(eps) ||
         std::holds_alternative<TableCoefficient>(eps);
}

// The 8 value channels' harmonics n = 0 … N (units of 1/P_k, P_k = core_period; column n) of a
// core with HasErrorPeriodLoad, by FFT synthesis instead of samples over the hunting period:
// K2 and C2 from one stiffness period P_K (exact steps, or samples; harmonic j of 1/P_K is n = jr,
// r = P_k/P_K), ε from its own series (a table's FFT: its trigonometric interpolant, as
// everywhere in this file), and the load K2 ε as their convolution
//   (K2 ε)_n = Σ_j K2_j ε_{n − jr},   X_{−i} = conj(X_i),
// over the j that reach ε's band |n − jr| ≤ B. Exact for that ε: K2's harmonics are exact (steps,
// Fourier) or those of its own interpolant up to the order (N + B)/r the sum needs. Memory
// O(N + B + samples of one stiffness period), against 8 channels sampled at
// 2(N + 2B) + 2 points over the hunting period before (0.7 GB for the helical pair with runout).
MatrixXc ErrorPeriodValueHarmonics(const SystemMesh& mesh, const LinearMeshCore& core,
                                   std::int64_t core_period, int N) {
  const std::int64_t pk = PeriodMeshes(core.stiffness());
  const std::int64_t r = core_period / pk;
  const Coefficient& eps = *core.transmission_error();
  const std::int64_t pe = PeriodMeshes(eps);
  const std::int64_t re = core_period / pe;  // ε's harmonic i is core harmonic i·re
  const int eps_terms = HighestHarmonic(eps, pe);
  const FourierCoefficient eps_series = ToFourier(eps, eps_terms);
  const std::int64_t B = static_cast<std::int64_t>(eps_terms) * re;
  const auto J = static_cast<int>((N + B) / r);
  const FourierCoefficient op =
      ToFourier(MeshValueCoefficient(mesh, pk, J, /*with_load=*/false), J);
  const auto op_at = [&](std::int64_t j) -> VectorXc {  // K2, C2 channels at harmonic j of 1/P_K
    const std::int64_t a = std::abs(j);
    const VectorXc c = a == 0 ? VectorXc(op.mean().cast<std::complex<double>>())
                              : VectorXc(op.harmonics().col(a - 1));
    return j >= 0 ? c : VectorXc(c.conjugate());
  };
  std::vector<Matrix2c> k2(static_cast<size_t>(2 * J + 1));  // index j + J
  for (int j = -J; j <= J; ++j) {
    const VectorXc c = op_at(j);
    k2[static_cast<size_t>(j + J)] << c(0), c(1), c(1), c(2);
  }
  const auto eps_at = [&](std::int64_t i) -> Vector2c {  // ε at core harmonic i, |i| ≤ B
    const std::int64_t a = std::abs(i) / re;
    const Vector2c c = a == 0 ? Vector2c(eps_series.mean().cast<std::complex<double>>())
                              : Vector2c(eps_series.harmonics().col(a - 1));
    return i >= 0 ? c : Vector2c(c.conjugate());
  };
  MatrixXc values = MatrixXc::Zero(kNumValueChannels, N + 1);
  for (int n = 0; n <= N; ++n) {
    if (n % r == 0) values.col(n).head<6>() = op_at(n / r).head<6>();
    // j with |n − jr| ≤ B: ⌈(n − B)/r⌉ … ⌊(n + B)/r⌋ (n + B ≥ 0, so the upper one truncates).
    const std::int64_t lo_num = n - B;
    const std::int64_t j_lo = lo_num >= 0 ? (lo_num + r - 1) / r : -((-lo_num) / r);
    const std::int64_t j_hi = (n + B) / r;
    Vector2c load = Vector2c::Zero();
    for (std::int64_t j = std::max<std::int64_t>(j_lo, -J); j <= std::min<std::int64_t>(j_hi, J);
         ++j) {
      const std::int64_t i = n - j * r;
      if (i % re != 0) continue;
      load += k2[static_cast<size_t>(j + J)] * eps_at(i);
    }
    values.col(n).tail<2>() = load;
  }
  return values;
}

// The 8 value channels' harmonics n = 0 … N (units of 1/P_k, column n) of a core without
// sidebands, in its own phase.
MatrixXc CoefficientValueHarmonics(const SystemMesh& mesh, std::int64_t core_period, int N) {
  MatrixXc values(kNumValueChannels, N + 1);
  if (HasErrorPeriodLoad(mesh.core, core_period)) {
    return ErrorPeriodValueHarmonics(mesh, std::get<LinearMeshCore>(mesh.core), core_period, N);
  }
  const FourierCoefficient series = ToFourier(MeshValueCoefficient(mesh, core_period, N, true), N);
  values.col(0) = series.mean().cast<std::complex<double>>();
  if (N > 0) values.rightCols(N) = series.harmonics();
  // K2, C2 from their own coefficients when those are stepwise but the load's are not (a
  // spur pair with a smooth ε): exact sinc sums instead of sampled steps.
  if (!internal::AllStepwise(internal::MeshOperatorCoefficients(mesh.core, true)) &&
      internal::AllStepwise(internal::MeshOperatorCoefficients(mesh.core, false))) {
    const FourierCoefficient operator_series =
        ToFourier(MeshValueCoefficient(mesh, core_period, N, false), N);
    values.col(0).head<6>() = operator_series.mean().head<6>().cast<std::complex<double>>();
    if (N > 0) values.block(0, 1, 6, N) = operator_series.harmonics().topRows<6>();
  }
  return values;
}

// The mesh with its linear core's sidebands removed (the coefficient part of ε only).
SystemMesh WithoutSidebands(const SystemMesh& mesh) {
  SystemMesh out = mesh;
  if (const auto* c = std::get_if<LinearMeshCore>(&mesh.core); c && !c->sidebands().empty()) {
    out.core = LinearMeshCore(c->level(), c->stiffness(), c->half_face_width(),
                              c->transmission_error(), c->damping(), c->is_mean_lti());
  }
  return out;
}

// The load K2 ε_sb of a core's sidebands at its harmonics n (units of 1/P_c, the core period
// with the sidebands), in the core's own phase: with K2 = Σ_j K2_j e^{ijθ/P_K} and
// ε_sb = Σ_i c_i e^{i m_i θ/P_s} + conj, harmonic n collects K2_j c_i where
// j r_K + m_i r_s = n and K2_j conj(c_i) where j r_K − m_i r_s = n (r_K = P_c/P_K, r_s = P_c/P_s):
// exact for the core's K2 (steps exact, samples as their own interpolant).
class SidebandLoad {
 public:
  SidebandLoad(const SystemMesh& stripped, const LinearMeshCore& core, std::int64_t core_period,
               std::int64_t max_n)
      : sb_(core.sidebands()) {
    const std::int64_t pk = PeriodMeshes(core.stiffness());
    rk_ = core_period / pk;
    rs_ = core_period / sb_.period_meshes;
    std::int64_t reach = 0;
    for (std::int64_t m : sb_.harmonics) reach = std::max(reach, m * rs_);
    const std::int64_t J = (max_n + reach) / rk_ + 1;
    GEARDYN_THROW_UNLESS(J < (std::int64_t{1} << 26),
                         "sidebands: " << J << " stiffness harmonics needed (too many)");
    J_ = static_cast<int>(J);
    const FourierCoefficient op =
        ToFourier(MeshValueCoefficient(stripped, pk, J_, /*with_load=*/false), J_);
    k2_.resize(static_cast<size_t>(J_) + 1);
    for (int j = 0; j <= J_; ++j) {
      const VectorXc c = j == 0 ? VectorXc(op.mean().cast<std::complex<double>>())
                                : VectorXc(op.harmonics().col(j - 1));
      k2_[static_cast<size_t>(j)] << c(0), c(1), c(1), c(2);
    }
  }
  // Harmonic n (any sign) of K2 ε_sb.
  Vector2c At(std::int64_t n) const {
    Vector2c load = Vector2c::Zero();
    for (int i = 0; i < sb_.size(); ++i) {
      const std::int64_t shift = sb_.harmonics[static_cast<size_t>(i)] * rs_;
      const Vector2c c = sb_.coefficients.col(i);
      if ((n - shift) % rk_ == 0) load += K2((n - shift) / rk_) * c;
      if ((n + shift) % rk_ == 0) load += K2((n + shift) / rk_) * c.conjugate();
    }
    return load;
  }

 private:
  Matrix2c K2(std::int64_t j) const {
    if (std::abs(j) > J_) return Matrix2c::Zero();
    const Matrix2c& x = k2_[static_cast<size_t>(std::abs(j))];
    return j >= 0 ? x : Matrix2c(x.conjugate());
  }
  const TransmissionErrorSidebands& sb_;
  std::int64_t rk_ = 1, rs_ = 1;
  int J_ = 0;
  std::vector<Matrix2c> k2_;
};

// The value channels n = 0 … N (units of 1/P_c, column n) of any core in its own phase: the
// coefficient part (CoefficientValueHarmonics at its own period) plus the sidebands' load.
MatrixXc MeshValueHarmonics(const SystemMesh& mesh, std::int64_t core_period, int N) {
  const auto* linear = std::get_if<LinearMeshCore>(&mesh.core);
  if (linear == nullptr || linear->sidebands().empty()) {
    return CoefficientValueHarmonics(mesh, core_period, N);
  }
  const SystemMesh stripped = WithoutSidebands(mesh);
  const std::int64_t pb = internal::MeshCorePeriod(stripped.core);
  const std::int64_t rb = core_period / pb;
  const MatrixXc base = CoefficientValueHarmonics(stripped, pb, static_cast<int>(N / rb));
  MatrixXc values = MatrixXc::Zero(kNumValueChannels, N + 1);
  for (Eigen::Index nb = 0; nb < base.cols(); ++nb) values.col(nb * rb) = base.col(nb);
  const SidebandLoad sidebands(stripped, *linear, core_period, N);
  for (int n = 0; n <= N; ++n) values.col(n).tail<2>() += sidebands.At(n);
  return values;
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
    const MatrixXc values = MeshValueHarmonics(mesh, core_period, mesh_harmonics);
    for (int n = 0; n <= mesh_harmonics; ++n) {
      VectorXc c = values.col(n);
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

namespace {

// One mesh of ExpandMeshHarmonicsSparse: system period P (a multiple of the core's period),
// operator harmonics j·q (j = 0 … J), load and ε at `harmonics` (all ≤ max_m).
SparseMeshHarmonics ExpandOneMeshSparse(const SystemMesh& mesh, std::int64_t P, std::int64_t q,
                                        int J, const std::vector<std::int64_t>& harmonics,
                                        std::int64_t max_m) {
  SparseMeshHarmonics h;
  h.stiffness.assign(static_cast<size_t>(J) + 1, Matrix2c::Zero());
  h.damping.assign(static_cast<size_t>(J) + 1, Matrix2c::Zero());
  h.load.assign(harmonics.size(), Vector2c::Zero());
  h.transmission_error.assign(harmonics.size(), Vector2c::Zero());
  const std::int64_t pc = internal::MeshCorePeriod(mesh.core);
  const std::int64_t qc = P / pc;  // system harmonic m is core harmonic m / qc
  const SystemMesh stripped = WithoutSidebands(mesh);
  const std::int64_t pb = internal::MeshCorePeriod(stripped.core);
  const std::int64_t rb = pc / pb;  // core harmonic n is coefficient harmonic n / rb
  const std::int64_t nb_max = max_m / (qc * rb);
  GEARDYN_THROW_UNLESS(nb_max <= (std::int64_t{1} << 24),
                       "mesh '" << mesh.name << "': its coefficients repeat over " << pb
                                << " mesh cycles; their expansion up to the requested harmonic "
                                << max_m << " of 1/" << P << " would need " << nb_max
                                << " harmonics (a long-period ε: pitch errors?)");
  const MatrixXc base = CoefficientValueHarmonics(stripped, pb, static_cast<int>(nb_max));
  const auto* linear = std::get_if<LinearMeshCore>(&mesh.core);
  std::optional<SidebandLoad> sidebands;
  std::optional<FourierCoefficient> eps;  // the ε coefficient's series
  std::int64_t re = 1;                    // core harmonic n is ε harmonic n / re
  if (linear != nullptr && !linear->sidebands().empty()) {
    sidebands.emplace(stripped, *linear, pc, max_m / qc);
  }
  if (linear != nullptr && linear->transmission_error()) {
    re = pc / PeriodMeshes(*linear->transmission_error());
    eps = ToFourier(*linear->transmission_error(), static_cast<int>(max_m / (qc * re)));
  }
  const auto phase = [&](std::int64_t n) {  // θ_k = θ + φ_k (see ExpandMeshHarmonics)
    return std::polar(1.0, static_cast<double>(n) * mesh.phase_offset / static_cast<double>(pc));
  };
  for (int j = 0; j <= J; ++j) {
    const std::int64_t m = static_cast<std::int64_t>(j) * q;
    if (m % qc != 0 || (m / qc) % rb != 0) continue;
    const std::int64_t n = m / qc;
    const VectorXc c = base.col(n / rb) * phase(n);
    h.stiffness[static_cast<size_t>(j)] << c(0), c(1), c(1), c(2);
    h.damping[static_cast<size_t>(j)] << c(3), c(4), c(4), c(5);
  }
  for (size_t i = 0; i < harmonics.size(); ++i) {
    const std::int64_t m = harmonics[i];
    if (m % qc != 0) continue;
    const std::int64_t n = m / qc;
    Vector2c load = Vector2c::Zero(), e = Vector2c::Zero();
    if (n % rb == 0) load = base.col(n / rb).tail<2>();
    if (sidebands) load += sidebands->At(n);
    if (eps && n % re == 0) {
      const std::int64_t a = n / re;
      e = a == 0 ? Vector2c(eps->mean().cast<std::complex<double>>())
                 : Vector2c(eps->harmonics().col(a - 1));
    }
    if (linear != nullptr) {
      const TransmissionErrorSidebands& sb = linear->sidebands();
      for (int l = 0; l < sb.size(); ++l) {
        if (sb.harmonics[static_cast<size_t>(l)] * (pc / sb.period_meshes) == n) {
          e += sb.coefficients.col(l);
        }
      }
    }
    h.load[i] = load * phase(n);
    h.transmission_error[i] = e * phase(n);
  }
  return h;
}

}  // namespace

std::vector<SparseMeshHarmonics> ExpandMeshHarmonicsSparse(
    const SystemModel& model, std::int64_t operator_period, int J,
    const std::vector<std::int64_t>& harmonics) {
  GEARDYN_THROW_UNLESS(J >= 0, "ExpandMeshHarmonicsSparse: J must be >= 0, got " << J);
  CheckSingleMeshFrequency(model, "ExpandMeshHarmonicsSparse");
  const std::int64_t P = model.period_meshes();
  GEARDYN_THROW_UNLESS(operator_period >= 1 && P % operator_period == 0,
                       "ExpandMeshHarmonicsSparse: operator_period "
                           << operator_period << " must divide the period " << P);
  const std::int64_t q = P / operator_period;
  std::int64_t max_m = static_cast<std::int64_t>(J) * q;
  for (std::int64_t m : harmonics) {
    GEARDYN_THROW_UNLESS(m >= 0, "ExpandMeshHarmonicsSparse: harmonics must be >= 0, got " << m);
    max_m = std::max(max_m, m);
  }
  std::vector<SparseMeshHarmonics> out;
  out.reserve(model.meshes().size());
  for (const SystemMesh& mesh : model.meshes()) {
    out.push_back(ExpandOneMeshSparse(mesh, P, q, J, harmonics, max_m));
  }
  return out;
}

SparseMeshHarmonics ExpandOwnPhaseMeshHarmonics(const SystemMesh& mesh, int num_harmonics) {
  GEARDYN_THROW_UNLESS(num_harmonics >= 0,
                       "ExpandOwnPhaseMeshHarmonics: num_harmonics must be "
                       ">= 0, got "
                           << num_harmonics);
  const std::int64_t pc = internal::MeshCorePeriod(mesh.core);
  std::vector<std::int64_t> harmonics(static_cast<std::size_t>(num_harmonics) + 1);
  for (int n = 0; n <= num_harmonics; ++n) harmonics[static_cast<std::size_t>(n)] = n;
  return ExpandOneMeshSparse(mesh, pc, 1, num_harmonics, harmonics, num_harmonics);
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
  // Harmonic loads Re(F e^{ilθ}) = (F e^{ilθ} + conj)/2: F/2 at harmonic l·P of 1/P.
  for (const SystemHarmonicLoad& h : model.harmonic_loads()) {
    const std::int64_t m = static_cast<std::int64_t>(h.order) * out.period_meshes;
    if (m > num) continue;
    for (int a = 0; a < kBodyDofs; ++a) {
      if (h.dofs[a] >= 0) out.load[static_cast<std::size_t>(m)](h.dofs[a]) += 0.5 * h.amplitude(a);
    }
  }
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
