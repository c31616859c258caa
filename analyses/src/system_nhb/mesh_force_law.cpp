/// @file
/// @brief MeshForceLaw (mesh_force_law.hpp).
#include "system_nhb/mesh_force_law.hpp"

#include <numbers>
#include <variant>

#include "geardyn/common/check.hpp"

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
  // [1, −σ_s] (slices, every slice loaded), by the rectangle rule on 256·P samples.
  const int samples = 256 * static_cast<int>(model.period_meshes());
  VectorX phase(samples);
  for (int s = 0; s < samples; ++s) {
    phase(s) = 2.0 * std::numbers::pi * static_cast<double>(model.period_meshes()) * s / samples;
  }
  UpdateCache(phase);
  contact_offset_ = VectorX::Zero(n_);
  for (int t = 0; t < T; ++t) {
    const MeshForceTerm& term = terms_[t];
    const SystemMesh& mesh = model_.meshes()[term.mesh];
    Vector2 mean = Vector2::Zero();
    for (int s = 0; s < samples; ++s) {
      if (const SliceMeshCore* core = AsSlice(mesh)) {
        for (int i = 0; i < core->num_slices(); ++i) {
          const double ke = slice_k_[t](i, s) * (slice_e_[t].size() ? slice_e_[t](i, s) : 0.0);
          mean += ke * Vector2(1.0, -core->sigma()(i));
        }
      } else {
        mean += load_[t][s];
      }
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
