/// @file
/// @brief Independent reference for the system nonlinear HB tests: a GSL rk8pd time integration
/// of M q̈ + C̄ q̇ + K0 q + Σ_k P_kᵀ G_kᵀ F_k(G_k P_k q, θ_k) = f0 on ALL the model's DOFs (rigid
/// modes included, no reduction), with the slice forces evaluated by EvalSliceForce on the
/// model's cores (not through the HB law) and C̄ the θ-mean of the assembled damping — the
/// equation the HB solves (system_nonlinear_hb.hpp).
#pragma once

#include <gsl/gsl_errno.h>
#include <gsl/gsl_odeiv2.h>

#include <Eigen/LU>
#include <cmath>
#include <complex>
#include <numbers>
#include <variant>
#include <vector>

#include "geardyn/system/mesh_core.hpp"
#include "geardyn/system/probes.hpp"
#include "geardyn/system/static_deflection.hpp"
#include "geardyn/system/system_model.hpp"
#include "geardyn/system/workspace.hpp"

namespace geardyn::testing {

/// DTE statistics of mesh 0 over the last periods of a time integration.
struct SystemTiStats {
  double mean = 0.0, rms = 0.0, peak_to_peak = 0.0;
  double contact_loss_fraction = 0.0;  ///< fraction of samples with no drive-flank contact
  bool ok = true;
};

class SystemTimeIntegrator {
 public:
  explicit SystemTimeIntegrator(const SystemModel& model) : model_(model) {
    n_ = model.num_dofs();
    SystemWorkspace ws(model, StorageKind::kDense);
    const int samples = 256 * static_cast<int>(model.period_meshes());
    C_ = MatrixX::Zero(n_, n_);
    for (int s = 0; s < samples; ++s) {
      C_ += AssembleDamping(
          model, ws,
          2.0 * std::numbers::pi * static_cast<double>(model.period_meshes()) * s / samples);
    }
    C_ /= samples;
    K0_ = model.DenseConstantStiffness();
    Minv_ = model.DenseMass().inverse();
    f0_ = model.constant_load();
    for (const SystemMesh& m : model.meshes()) {
      const auto* core = std::get_if<SliceMeshCore>(&m.core);
      slice_ws_.emplace_back(*core);
    }
  }

  /// Integrates from the static deflection at rest for `settle` mesh periods at f_m [Hz], then
  /// records `record` periods with `per_period` samples each.
  SystemTiStats Run(double mesh_frequency_hz, int settle, int record, int per_period = 256) {
    VectorX y = VectorX::Zero(2 * n_);
    y.head(n_) = SolveStaticDeflection(model_).deflection;
    phase_ = 0.0;
    return Continue(mesh_frequency_hz, settle, record, per_period, &y);
  }

  /// The state [q; q̇] at t = 0 of a periodic orbit q = Q_0 + 2 Re Σ_k Q_k e^{ikωt} (ω = 2π f_m/p,
  /// `harmonics` = (N × (H+1)) one-sided Q_k), to start an integration on a given branch.
  VectorX StateFromHarmonics(const MatrixXc& harmonics, double mesh_frequency_hz,
                             int period_multiple) const {
    const double w = 2.0 * std::numbers::pi * mesh_frequency_hz / period_multiple;
    VectorX y = VectorX::Zero(2 * n_);
    y.head(n_) = harmonics.col(0).real();
    for (Eigen::Index k = 1; k < harmonics.cols(); ++k) {
      y.head(n_) += 2.0 * harmonics.col(k).real();
      y.tail(n_) +=
          2.0 * (std::complex<double>(0.0, static_cast<double>(k) * w) * harmonics.col(k)).real();
    }
    return y;
  }

  /// Continues the integration from the state *y (updated) at f_m [Hz]: `settle` periods, then
  /// `record` periods sampled. The mesh phase θ stays continuous across calls (a change of f_m
  /// changes only dθ/dt), so that successive calls form a stepped frequency sweep; the phase
  /// starts at θ = 0 at the first call, as for an orbit from StateFromHarmonics.
  SystemTiStats Continue(double mesh_frequency_hz, int settle, int record, int per_period,
                         VectorX* state, double rel_tol = 1e-10) {
    omega_ = 2.0 * std::numbers::pi * mesh_frequency_hz;
    VectorX& y = *state;
    gsl_odeiv2_system sys{&Rhs, nullptr, static_cast<size_t>(2 * n_), this};
    gsl_odeiv2_driver* d =
        gsl_odeiv2_driver_alloc_y_new(&sys, gsl_odeiv2_step_rk8pd, 1e-8 / omega_, rel_tol, rel_tol);
    const double T = 2.0 * std::numbers::pi / omega_;
    double t = 0.0;  // local time of this call; θ = θ_start + ω t
    SystemTiStats st;
    std::vector<double> dte;
    int loss = 0;
    for (int p = 0; p < settle + record && st.ok; ++p) {
      const int steps = p < settle ? 1 : per_period;
      for (int s = 1; s <= steps; ++s) {
        const double t1 = (p + double(s) / steps) * T;
        if (gsl_odeiv2_driver_apply(d, &t, t1, y.data()) != GSL_SUCCESS) {
          st.ok = false;
          break;
        }
        if (p >= settle) {
          const Vector2 delta = CalcMeshDeflection(model_, MeshIndex(0), y.head(n_));
          const auto& core = std::get<SliceMeshCore>(model_.meshes()[0].core);
          const SliceForce f =
              EvalSliceForce(core, slice_ws_[0], model_.meshes()[0].MeshPhase(phase_ + omega_ * t),
                             delta(0), delta(1));
          dte.push_back(delta(0));
          if (f.num_loaded == 0) ++loss;
        }
      }
    }
    gsl_odeiv2_driver_free(d);
    phase_ = std::fmod(phase_ + omega_ * t,
                       2.0 * std::numbers::pi * static_cast<double>(model_.period_meshes()));
    if (dte.empty()) return st;
    double mx = -1e300, mn = 1e300, sum = 0.0;
    for (double v : dte) {
      mx = std::max(mx, v);
      mn = std::min(mn, v);
      sum += v;
    }
    const double count = static_cast<double>(dte.size());
    st.mean = sum / count;
    double s2 = 0.0;
    for (double v : dte) s2 += (v - st.mean) * (v - st.mean);
    st.rms = std::sqrt(s2 / count);
    st.peak_to_peak = mx - mn;
    st.contact_loss_fraction = loss / count;
    return st;
  }

 private:
  static int Rhs(double t, const double y[], double dydt[], void* params) {
    auto* self = static_cast<SystemTimeIntegrator*>(params);
    const int n = self->n_;
    Eigen::Map<const VectorX> q(y, n), v(y + n, n);
    VectorX force = self->f0_ - self->K0_ * q - self->C_ * v;
    for (int k = 0; k < self->model_.num_meshes(); ++k) {
      const SystemMesh& m = self->model_.meshes()[k];
      const Vector2 delta = CalcMeshDeflection(self->model_, MeshIndex(k), q);
      const SliceForce f =
          EvalSliceForce(std::get<SliceMeshCore>(m.core), self->slice_ws_[k],
                         m.MeshPhase(self->phase_ + self->omega_ * t), delta(0), delta(1));
      // Force on the pair's coordinates: −Gᵀ F (mesh_core.hpp sign convention).
      const Vector12 fp = -m.G.transpose() * f.force;
      for (int a = 0; a < 12; ++a) {
        if (m.dofs[a] >= 0) force(m.dofs[a]) += fp(a);
      }
    }
    Eigen::Map<VectorX>(dydt, n) = v;
    Eigen::Map<VectorX>(dydt + n, n) = self->Minv_ * force;
    return GSL_SUCCESS;
  }

  SystemModel model_;
  int n_ = 0;
  double omega_ = 1.0;
  double phase_ = 0.0;  // θ at the start of the current call [rad]
  MatrixX C_, K0_, Minv_;
  VectorX f0_;
  std::vector<SliceMeshWorkspace> slice_ws_;
};

}  // namespace geardyn::testing
