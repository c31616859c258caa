/// @file
/// @brief Independent Floquet multipliers of a periodic orbit of the system nonlinear HB: a GSL
/// rk8pd integration of the nonlinear equation of motion on ALL the model's DOFs together with
/// its variational equation Y′ = A(t) Y, A = [0 I; −M⁻¹(K0 + Σ Gᵀ J(δ(t)) G)  −M⁻¹C̄], over the
/// period from the orbit's state at t = 0. The slice force Jacobian J comes from EvalSliceForce
/// along the integrated trajectory (not from the HB law or its projected form), and the
/// multipliers from the eigenvalues of Y(T).
#pragma once

#include <gsl/gsl_errno.h>
#include <gsl/gsl_odeiv2.h>

#include <Eigen/Eigenvalues>
#include <numbers>
#include <variant>
#include <vector>

#include "geardyn/system/mesh_core.hpp"
#include "geardyn/system/probes.hpp"
#include "geardyn/system/system_model.hpp"
#include "geardyn/system/workspace.hpp"

namespace geardyn::testing {

/// GSL right-hand side of [q; q̇; vec Y] (Y column-major, 2N × 2N).
struct Variational {
  const SystemModel* model = nullptr;
  int n = 0;
  double omega = 1.0;  // mesh frequency [rad/s]; θ = ω t
  MatrixX Minv, K0, C;
  std::vector<SliceMeshWorkspace> ws;
};

inline int VariationalRhs(double t, const double y[], double dydt[], void* params) {
  auto* v = static_cast<Variational*>(params);
  const int n = v->n;
  const SystemModel& model = *v->model;
  Eigen::Map<const VectorX> q(y, n), qd(y + n, n);
  VectorX force = model.constant_load() - v->K0 * q - v->C * qd;
  MatrixX K = v->K0;  // tangent stiffness K0 + Σ Gᵀ J G
  for (int k = 0; k < model.num_meshes(); ++k) {
    const SystemMesh& m = model.meshes()[k];
    const Vector2 delta = CalcMeshDeflection(model, MeshIndex(k), q);
    const SliceForce f = EvalSliceForce(std::get<SliceMeshCore>(m.core), v->ws[k],
                                        m.MeshPhase(v->omega * t), delta(0), delta(1));
    const Vector12 fp = -m.G.transpose() * f.force;
    const Matrix12 kp = m.G.transpose() * f.jacobian * m.G;
    for (int a = 0; a < 12; ++a) {
      if (m.dofs[a] < 0) continue;
      force(m.dofs[a]) += fp(a);
      for (int b = 0; b < 12; ++b) {
        if (m.dofs[b] >= 0) K(m.dofs[a], m.dofs[b]) += kp(a, b);
      }
    }
  }
  Eigen::Map<VectorX>(dydt, n) = qd;
  Eigen::Map<VectorX>(dydt + n, n) = v->Minv * force;
  const int s = 2 * n;
  Eigen::Map<const MatrixX> Y(y + s, s, s);
  Eigen::Map<MatrixX> dY(dydt + s, s, s);
  dY.topRows(n) = Y.bottomRows(n);
  dY.bottomRows(n) = -v->Minv * (K * Y.topRows(n) + v->C * Y.bottomRows(n));
  return GSL_SUCCESS;
}

/// Multipliers of the orbit through state y0 at θ = 0 over `periods` mesh periods.
inline VectorXc ReferenceMultipliers(const SystemModel& model, const VectorX& y0, double mesh_hz,
                                     int periods) {
  Variational v;
  v.model = &model;
  v.n = model.num_dofs();
  v.omega = 2.0 * std::numbers::pi * mesh_hz;
  // C̄: the θ-mean of the assembled damping, as in the HB (system_nonlinear_hb.hpp) and in
  // SystemTimeIntegrator.
  SystemWorkspace sw(model, StorageKind::kDense);
  const int samples = 256 * static_cast<int>(model.period_meshes());
  v.C = MatrixX::Zero(v.n, v.n);
  for (int s = 0; s < samples; ++s) {
    v.C += AssembleDamping(
        model, sw,
        2.0 * std::numbers::pi * static_cast<double>(model.period_meshes()) * s / samples);
  }
  v.C /= samples;
  v.K0 = model.DenseConstantStiffness();
  v.Minv = model.DenseMass().inverse();
  for (const SystemMesh& m : model.meshes()) v.ws.emplace_back(std::get<SliceMeshCore>(m.core));
  const int s = 2 * v.n;
  VectorX y(s + s * s);
  y.head(s) = y0;
  Eigen::Map<MatrixX>(y.data() + s, s, s).setIdentity();
  gsl_odeiv2_system sys{&VariationalRhs, nullptr, static_cast<size_t>(y.size()), &v};
  gsl_odeiv2_driver* d =
      gsl_odeiv2_driver_alloc_y_new(&sys, gsl_odeiv2_step_rk8pd, 1e-9 / v.omega, 1e-11, 1e-11);
  double t = 0.0;
  const double T = periods * 2.0 * std::numbers::pi / v.omega;
  const int status = gsl_odeiv2_driver_apply(d, &t, T, y.data());
  gsl_odeiv2_driver_free(d);
  if (status != GSL_SUCCESS) return VectorXc();
  Eigen::EigenSolver<MatrixX> es(Eigen::Map<MatrixX>(y.data() + s, s, s), false);
  if (es.info() != Eigen::Success) return VectorXc();
  return es.eigenvalues();
}

}  // namespace geardyn::testing
