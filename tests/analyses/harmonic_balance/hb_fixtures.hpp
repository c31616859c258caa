/// @file
/// @brief Fixtures of the harmonic-balance tests: hand-built damped gear systems (hand_pair.hpp)
/// and an independent steady-state reference, a long GSL odeiv2 (rk8pd) integration of
/// M q̈ + C(θ) q̇ + K(θ) q = f(θ) assembled with AssembleStiffness/Damping/Load.
#pragma once

#include <gsl/gsl_errno.h>
#include <gsl/gsl_odeiv2.h>

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "geardyn/common/check.hpp"
#include "geardyn/system/probes.hpp"
#include "geardyn/system/static_deflection.hpp"
#include "geardyn/system/system_steps.hpp"
#include "geardyn/system/workspace.hpp"
#include "lib/system/periodic_fixture.hpp"

namespace geardyn::test {

/// A smooth transmission error ε_η = e1 cos θ + e2 sin 2θ + e3 cos 3θ [m] (ε_ζ = 0).
inline FourierCoefficient SmoothTransmissionError(double e1, double e2, double e3) {
  MatrixX cosines = MatrixX::Zero(2, 3), sines = MatrixX::Zero(2, 3);
  cosines(0, 0) = e1;
  sines(0, 1) = e2;
  cosines(0, 2) = e3;
  return FourierCoefficient::FromCosSin(Vector2::Zero(), cosines, sines);
}

/// The hand pair (free rotation about the axes: a rigid-body mode) with a driving torque T on
/// the pinion and the balancing torque T r2/r1 on the wheel, optional modal damping ζ.
inline SystemModel LoadedPair(const MeshCore& core, double torque = 200.0, double modal_zeta = 0.0,
                              HandPairParams p = {}) {
  SystemBuilder builder = HandPairBuilder(p, core);
  Vector6 t = Vector6::Zero();
  // δ_η = … + r1 θz_i + r2 θz_j: a torque +T on θz_i and +T r2/r1 on θz_j compresses the mesh
  // (δ_η > 0), and r2 T − r1 (T r2/r1) = 0: nothing acts on the free rotation.
  t(5) = torque;
  builder.AddTorque(BodyIndex(0), t, "drive");
  t(5) = torque * p.r2 / p.r1;
  builder.AddTorque(BodyIndex(1), t, "brake");
  if (modal_zeta > 0.0) builder.SetModalDampingRatio(modal_zeta);
  return builder.Build();
}

/// The SDOF torsional pair: LoadedPair restricted to θz of both gears (DOFs 5 and 11).
inline SystemModel TorsionalPair(const MeshCore& core, double torque = 200.0) {
  return LoadedPair(core, torque).Restrict({5, 11});
}

/// Two meshes (periodic_fixture.hpp's TwoMeshSystem layout), planar, with modal damping and
/// balanced torques: a 9-DOF multi-mesh LTV system (mesh-b at `ratio_b` times mesh-a's
/// frequency).
inline SystemModel PlanarTwoMesh(const MeshCore& core_a, const MeshCore& core_b, double offset_b,
                                 double modal_zeta, double ratio_b = 1.0) {
  const HandPairParams p;
  SystemBuilder builder = TwoMeshBuilder(core_a, core_b, offset_b, 0.6, ratio_b);
  const BodyIndex pinion(0), a(1), b(2);
  Vector6 t = Vector6::Zero();
  t(5) = 300.0;
  builder.AddTorque(pinion, t, "drive");
  t(5) = 150.0 * p.r2 / p.r1;
  builder.AddTorque(a, t, "brake-a");
  builder.AddTorque(b, t, "brake-b");
  builder.SetModalDampingRatio(modal_zeta);
  return builder.Build().RestrictToPlanar();
}

/// @brief The DTE of every mesh over the last period of a long integration (reference).
struct OdeSteadyState {
  MatrixX dte;  ///< (meshes × S) at θ_s = 2πP s/S of the last period [m]
  int steps = 0;
};

namespace detail {
struct OdeParams {
  const SystemModel* model;
  SystemWorkspace* ws;
  Eigen::LLT<MatrixX>* mass;
  double omega_m;
  bool frozen;
  MatrixX K, C;
  VectorX f;
};

inline void Freeze(OdeParams& p, double theta) {
  p.K = AssembleStiffness(*p.model, *p.ws, theta);
  p.C = AssembleDamping(*p.model, *p.ws, theta);
  p.f = AssembleLoad(*p.model, *p.ws, theta);
}

inline int OdeRhs(double t, const double y[], double dydt[], void* params) {
  auto& p = *static_cast<OdeParams*>(params);
  const int n = p.model->num_dofs();
  if (!p.frozen) Freeze(p, p.omega_m * t);
  const Eigen::Map<const VectorX> q(y, n), v(y + n, n);
  Eigen::Map<VectorX>(dydt, n) = v;
  Eigen::Map<VectorX>(dydt + n, n) = p.mass->solve(p.f - p.C * v - p.K * q);
  return GSL_SUCCESS;
}
}  // namespace detail

/// @brief Integrates from the static deflection (q = q̄, q̇ = 0) for `periods` system periods at
/// mesh frequency f_m with GSL rk8pd (rel. tol. 1e-11), stopping and restarting at every step
/// breakpoint of K (piecewise-constant models: K, C, f frozen per interval, so the integrator
/// never crosses a jump), and samples the DTE over the last period at S points.
inline OdeSteadyState IntegrateSteadyState(const SystemModel& model, double mesh_frequency_hz,
                                           int periods, int samples) {
  const int n = model.num_dofs();
  const double P = static_cast<double>(model.period_meshes());
  const double T_theta = 2.0 * std::numbers::pi * P;
  const double omega_m = 2.0 * std::numbers::pi * mesh_frequency_hz;
  SystemWorkspace ws(model, StorageKind::kDense);
  Eigen::LLT<MatrixX> mass(model.DenseMass());
  detail::OdeParams params{&model, &ws, &mass, omega_m, false, MatrixX(), MatrixX(), VectorX()};
  const bool frozen = HasPiecewiseConstantOperator(model);
  params.frozen = frozen;
  std::vector<double> breaks = {0.0};
  if (frozen) {
    const SystemSteps steps = CollectSystemSteps(model);
    breaks.assign(steps.breakpoints.data(), steps.breakpoints.data() + steps.num_intervals());
  }
  gsl_odeiv2_system sys{detail::OdeRhs, nullptr, static_cast<size_t>(2 * n), &params};
  gsl_odeiv2_driver* driver =
      gsl_odeiv2_driver_alloc_y_new(&sys, gsl_odeiv2_step_rk8pd, 1e-7 / omega_m, 1e-13, 1e-11);
  std::vector<double> y(2 * n, 0.0);
  const VectorX q0 = SolveStaticDeflection(model).deflection;
  std::copy(q0.data(), q0.data() + n, y.begin());
  OdeSteadyState out;
  out.dte = MatrixX::Zero(model.num_meshes(), samples);
  VectorX dte(model.num_meshes());
  double t = 0.0;
  for (int period = 0; period < periods; ++period) {
    const bool last = period == periods - 1;
    std::vector<double> stops(breaks.begin() + 1, breaks.end());
    if (last) {
      for (int s = 1; s < samples; ++s) stops.push_back(T_theta * s / samples);
    }
    stops.push_back(T_theta);
    std::sort(stops.begin(), stops.end());
    double begin = 0.0;
    if (last) {
      EvalMeshDte(model, period * T_theta, Eigen::Map<const VectorX>(y.data(), n), dte);
      out.dte.col(0) = dte;
    }
    for (const double stop : stops) {
      if (stop <= begin) continue;
      if (frozen) detail::Freeze(params, period * T_theta + 0.5 * (begin + stop));
      const double t_end = (period * T_theta + stop) / omega_m;
      GEARDYN_DEMAND(gsl_odeiv2_driver_apply(driver, &t, t_end, y.data()) == GSL_SUCCESS);
      gsl_odeiv2_driver_reset(driver);
      begin = stop;
      if (last && stop < T_theta) {
        const int s = static_cast<int>(std::lround(stop / T_theta * samples));
        if (std::abs(stop - T_theta * s / samples) < 1e-12 * T_theta) {
          EvalMeshDte(model, period * T_theta + stop, Eigen::Map<const VectorX>(y.data(), n), dte);
          out.dte.col(s) = dte;
        }
      }
    }
  }
  out.steps = static_cast<int>(driver->n);
  gsl_odeiv2_driver_free(driver);
  return out;
}

/// RMS of a row about its mean.
inline double RmsAboutMean(const VectorX& x) {
  return std::sqrt((x.array() - x.mean()).square().mean());
}

}  // namespace geardyn::test
