/// @file
/// @brief MeshForceLaw (mesh_force_law.hpp).
#include "system_nhb/mesh_force_law.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <variant>

#include "geardyn/common/check.hpp"
#include "geardyn/system/system_harmonics.hpp"

namespace geardyn::internal {
namespace {

const SliceMeshCore* AsSlice(const SystemMesh& mesh) {
  return std::get_if<SliceMeshCore>(&mesh.core);
}

}  // namespace

MeshForceLaw::MeshForceLaw(const SystemModel& model, std::vector<MeshForceTerm> terms)
    : model_(model), terms_(std::move(terms)) {
  for (const MeshForceTerm& t : terms_) n_ = std::max(n_, t.first + t.count);
  const int T = static_cast<int>(terms_.size());
  k2_.resize(T);
  load_.resize(T);
  eps_.resize(T);
  slice_k_.resize(T);
  slice_e_.resize(T);
  // Contact-branch offset: θ-mean of g̃(0, θ) = −mean(K2 ε) (linear) or −Σ_s mean(k_s e_s)
  // [1, −σ_s] (slices, every slice loaded), each over its own mesh's period (the meshes may run
  // at several frequencies: the quasi-periodic HB). Linear cores: the exact mean of the load
  // channel (ExpandOwnPhaseMeshHarmonics: sinc sums for steps, exact for Fourier series); slices
  // without separation: zero; slices with separation: the rectangle rule on 256·P_k samples of
  // the mesh's own phase (exact for steps whose breakpoints fall on the grid, O(1/(256 P_k))
  // otherwise).
  contact_offset_ = VectorX::Zero(n_);
  for (const MeshForceTerm& term : terms_) {
    const SystemMesh& mesh = model_.meshes()[term.mesh];
    const SliceMeshCore* core = AsSlice(mesh);
    if (core == nullptr) {
      const Vector2 mean = ExpandOwnPhaseMeshHarmonics(mesh, 0).load[0].real();
      contact_offset_.segment(term.first, term.count) = -mean.head(term.count);
      continue;
    }
    if (!core->separation()) continue;
    const std::int64_t period = PeriodMeshes(mesh.core);
    const int samples = 256 * static_cast<int>(period);
    const int N = core->num_slices();
    VectorX k(N), e(N);
    Vector2 mean = Vector2::Zero();
    for (int s = 0; s < samples; ++s) {
      const double theta =
          2.0 * std::numbers::pi * static_cast<double>(period) * s / samples + mesh.phase_offset;
      geardyn::Evaluate(core->stiffness(), theta, k);
      geardyn::Evaluate(*core->separation(), theta, e);
      for (int i = 0; i < N; ++i) mean += k(i) * e(i) * Vector2(1.0, -core->sigma()(i));
    }
    contact_offset_.segment(term.first, term.count) = -(mean / samples).head(term.count);
  }
}

void MeshForceLaw::UpdateCache(const VectorX& phase) const {
  if (cached_phase_.size() == phase.size() && cached_phase_ == phase) return;
  const int S = static_cast<int>(phase.size());
  for (size_t t = 0; t < terms_.size(); ++t) {
    const SystemMesh& mesh = model_.meshes()[terms_[t].mesh];
    if (const SliceMeshCore* core = AsSlice(mesh)) {
      const int N = core->num_slices();
      slice_k_[t].resize(N, S);
      slice_e_[t].resize(core->separation() ? N : 0, S);
      VectorX buf(N);
      for (int s = 0; s < S; ++s) {
        const double theta = mesh.MeshPhase(phase(s));
        geardyn::Evaluate(core->stiffness(), theta, buf);
        slice_k_[t].col(s) = buf;
        if (core->separation()) {
          geardyn::Evaluate(*core->separation(), theta, buf);
          slice_e_[t].col(s) = buf;
        }
      }
    } else {
      const auto& linear = std::get<LinearMeshCore>(mesh.core);
      k2_[t].resize(S);
      load_[t].resize(S);
      eps_[t].resize(S);
      for (int s = 0; s < S; ++s) {
        const double theta = mesh.MeshPhase(phase(s));
        k2_[t][s] = EvalStiffnessCore(linear, theta);
        load_[t][s] = EvalTransmissionErrorLoad(linear, theta);
        eps_[t][s] = EvalTransmissionError(linear, theta);
      }
    }
  }
  cached_phase_ = phase;
}

void MeshForceLaw::TermForce(int t, int s, const MatrixX& u, Vector2* delta, Vector2* force,
                             Matrix2* jacobian, int* drive, int* back) const {
  const MeshForceTerm& term = terms_[t];
  delta->setZero();
  delta->head(term.count) = u.col(s).segment(term.first, term.count);
  const SystemMesh& mesh = model_.meshes()[term.mesh];
  if (const SliceMeshCore* core = AsSlice(mesh)) {
    const SliceForce f =
        slice_e_[t].size()
            ? CalcSliceForce(*core, slice_k_[t].col(s), slice_e_[t].col(s), (*delta)(0),
                             (*delta)(1))
            : CalcSliceForce(*core, slice_k_[t].col(s), VectorX(), (*delta)(0), (*delta)(1));
    *force = f.force;
    *jacobian = f.jacobian;
    *drive = f.num_loaded;
    *back = f.num_back_loaded;
  } else {
    *force = k2_[t][s] * (*delta) - load_[t][s];
    *jacobian = k2_[t][s];
    *drive = (*force)(0) > 0.0 ? 1 : 0;
    *back = 0;
  }
}

void MeshForceLaw::Evaluate(const MatrixX& u, const VectorX& phase, MatrixX& force,
                            MatrixX& jacobian) const {
  std::lock_guard<std::mutex> lock(mutex_);
  UpdateCache(phase);
  const int S = static_cast<int>(phase.size());
  force.setZero(n_, S);
  jacobian.setZero(static_cast<Eigen::Index>(n_) * n_, S);
  Vector2 delta, f;
  Matrix2 J;
  int drive = 0, back = 0;
  for (int s = 0; s < S; ++s) {
    for (size_t t = 0; t < terms_.size(); ++t) {
      const MeshForceTerm& term = terms_[t];
      const int a = term.first, c = term.count;
      TermForce(static_cast<int>(t), s, u, &delta, &f, &J, &drive, &back);
      f -= term.mean_k2 * delta;
      J -= term.mean_k2;
      force.col(s).segment(a, c) = f.head(c);
      for (int j = 0; j < c; ++j) {
        for (int i = 0; i < c; ++i) jacobian((a + j) * n_ + a + i, s) = J(i, j);
      }
    }
  }
}

bool MeshForceLaw::ProjectedForm(int period_multiple, NhbProjectedForm* form) const {
  constexpr double kTwoPi = 2.0 * std::numbers::pi;
  NhbProjectedForm out;
  out.linear = MatrixX::Zero(n_, n_);
  for (const MeshForceTerm& term : terms_) {
    const SystemMesh& mesh = model_.meshes()[term.mesh];
    const SliceMeshCore* core = AsSlice(mesh);
    if (core == nullptr || core->separation()) return false;
    const auto* steps = std::get_if<PiecewiseConstantCoefficient>(&core->stiffness());
    if (steps == nullptr && !std::holds_alternative<ConstantCoefficient>(core->stiffness())) {
      return false;  // smooth or tabulated stiffness: sampled AFT
    }
    // Base angle θ ∈ [0, 2π) ↦ mesh phase r·p·θ + φ; the stiffness repeats every 2π·P_k, so it
    // must repeat q = r·p/P_k (a whole number) times over the base period.
    const double slope = mesh.phase_ratio * period_multiple;
    const double period = Period(core->stiffness());
    const double repeats = slope * kTwoPi / period;
    if (!(slope > 0.0) || std::abs(repeats - std::round(repeats)) > 1e-9 * repeats) return false;
    std::vector<double> starts{0.0};
    if (steps != nullptr) {
      starts.clear();
      for (Eigen::Index b = 0; b < steps->breakpoints().size(); ++b) {
        // θ = (θ_b − φ + j·period) / slope, every j with θ ∈ [0, 2π).
        const double first = (steps->breakpoints()[b] - mesh.phase_offset) / slope;
        const double spacing = period / slope;
        double theta = first - std::floor(first / spacing) * spacing;
        for (; theta < kTwoPi * (1.0 - 1e-15); theta += spacing) starts.push_back(theta);
      }
      std::sort(starts.begin(), starts.end());
      starts.erase(std::unique(starts.begin(), starts.end(),
                               [](double a, double b) { return b - a < 1e-13 * kTwoPi; }),
                   starts.end());
    }
    const auto K = static_cast<Eigen::Index>(starts.size());
    const int N = core->num_slices();
    MatrixX weights(N, K);
    VectorX buf(N);
    for (Eigen::Index b = 0; b < K; ++b) {
      const double end = b + 1 < K ? starts[static_cast<size_t>(b + 1)] : starts[0] + kTwoPi;
      const double mid = 0.5 * (starts[static_cast<size_t>(b)] + end);
      geardyn::Evaluate(core->stiffness(), mesh.MeshPhase(period_multiple * mid), buf);
      weights.col(b) = buf;
    }
    const int a = term.first, c = term.count;
    out.linear.block(a, a, c, c) = -term.mean_k2.topLeftCorner(c, c);
    for (int s = 0; s < N; ++s) {
      if (!(weights.row(s).maxCoeff() > 0.0)) continue;  // no contact line ever in this slice
      NhbProjectedTerm t;
      t.direction = VectorX::Zero(n_);
      t.direction[a] = 1.0;
      if (c == 2) t.direction[a + 1] = -core->sigma()(s);  // v = δ_η − σ_s δ_ζ
      t.breakpoints = Eigen::Map<const VectorX>(starts.data(), K);
      t.weights = weights.row(s).transpose();
      t.ramp_points = {0.0};  // drive flank [v]₊
      t.ramp_slopes = {1.0};
      t.ramp_sides = {1};
      if (std::isfinite(core->backlash())) {
        // back flank −[−v − j]₊ = s [σ(v − β)]₊ with s = −1, σ = −1, β = −j
        t.ramp_points.push_back(-core->backlash());
        t.ramp_slopes.push_back(-1.0);
        t.ramp_sides.push_back(-1);
      }
      out.terms.push_back(std::move(t));
    }
  }
  *form = std::move(out);
  return true;
}

void MeshForceLaw::ContactBranch(MatrixX& stiffness, VectorX& offset) const {
  stiffness.setZero(n_, n_);
  offset = contact_offset_;
}

MeshForceSamples MeshForceLaw::SampleMeshForces(const MatrixX& u, const VectorX& phase) const {
  std::lock_guard<std::mutex> lock(mutex_);
  UpdateCache(phase);
  const int S = static_cast<int>(phase.size());
  const int meshes = model_.num_meshes();
  MeshForceSamples out;
  out.force_eta.setZero(meshes, S);
  out.te_eta.setZero(meshes, S);
  out.drive_loaded.setZero(meshes, S);
  out.back_loaded.setZero(meshes, S);
  Vector2 delta, f;
  Matrix2 J;
  int drive = 0, back = 0;
  for (int s = 0; s < S; ++s) {
    for (size_t t = 0; t < terms_.size(); ++t) {
      const MeshForceTerm& term = terms_[t];
      TermForce(static_cast<int>(t), s, u, &delta, &f, &J, &drive, &back);
      out.force_eta(term.mesh, s) = f(0);
      if (!eps_[t].empty()) out.te_eta(term.mesh, s) = eps_[t][s](0);
      out.drive_loaded(term.mesh, s) = drive > 0 ? 1.0 : 0.0;
      out.back_loaded(term.mesh, s) = back > 0 ? 1.0 : 0.0;
    }
  }
  return out;
}

}  // namespace geardyn::internal
