/// @file
/// @brief SystemPointDescriber (system_outputs.hpp).
#include "system_nhb/system_outputs.hpp"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <complex>
#include <numbers>

#include "geardyn/system/probes.hpp"

namespace geardyn::internal {
namespace {

using Complex = std::complex<double>;

}  // namespace

SystemPointDescriber::SystemPointDescriber(const SystemModel& model,
                                           const SystemNhbProblem& problem,
                                           const NhbOptions& options, bool element_forces,
                                           bool keep_response)
    : model_(model),
      problem_(problem),
      law_(dynamic_cast<const MeshForceLaw&>(*problem.problem.law)),
      options_(options),
      p_(options.period_multiple),
      element_forces_(element_forces),
      keep_response_(keep_response) {
  NhbProjectedForm form;
  exact_ = options.force_integration != NhbForceIntegration::kSampled &&
           law_.ProjectedForm(options.period_multiple, &form);
}

void SystemPointDescriber::Sample(const NhbPoint& point) {
  const int H = static_cast<int>(point.harmonics.cols()) - 1;
  if (H != H_) {
    H_ = H;
    S_ = NhbSolver::SamplesFor(options_, H);
    cos_.resize(H + 1, S_);
    sin_.resize(H + 1, S_);
    phase_.resize(S_);
    for (int s = 0; s < S_; ++s) {
      phase_(s) = p_ * 2.0 * std::numbers::pi * s / S_;
      for (int k = 0; k <= H; ++k) {
        const double a = 2.0 * std::numbers::pi * static_cast<double>(k * s % S_) / S_;
        cos_(k, s) = std::cos(a);
        sin_(k, s) = std::sin(a);
      }
    }
  }
  // u(t_s) = U_0 + 2 Σ_k (Re U_k cos − Im U_k sin).
  const MatrixX re = point.harmonics.real(), im = point.harmonics.imag();
  u_ = re.col(0).replicate(1, S_);
  if (H_ > 0) {
    u_ += 2.0 * (re.rightCols(H_) * cos_.bottomRows(H_) - im.rightCols(H_) * sin_.bottomRows(H_));
  }
}

MatrixXc SystemPointDescriber::ForceHarmonics(const NhbPoint& point) {
  // N_k from the engine itself (exact integration or AFT, whichever solved the point): kept
  // in the point by the engine, else integrated again.
  if (point.force_harmonics.cols() == point.harmonics.cols() &&
      point.force_harmonics.rows() == point.harmonics.rows()) {
    return point.force_harmonics;
  }
  const int H = static_cast<int>(point.harmonics.cols()) - 1;
  Solver(H);
  const int n = static_cast<int>(point.harmonics.rows());
  VectorX x(n * (2 * H + 1));
  for (int i = 0; i < n; ++i) {
    x[i] = point.harmonics(i, 0).real();
    for (int k = 1; k <= H; ++k) {
      x[n * (2 * k - 1) + i] = point.harmonics(i, k).real();
      x[n * 2 * k + i] = point.harmonics(i, k).imag();
    }
  }
  return solver_->ForceHarmonics(x);
}

MatrixXc SystemPointDescriber::RecoverResponse(const NhbPoint& point) {
  Sample(point);
  const NhbProblem& p = problem_.problem;
  const MatrixXc Nk = ForceHarmonics(point);
  // Z_k = D_k⁻¹ (F_k − Pᵀ N_k), by the engine's linear solve (pole–residue form or LU).
  MatrixXc rhs = -(p.projection.transpose().cast<Complex>() * Nk);
  rhs.col(0) += p.force_mean.cast<Complex>();
  if (p_ <= H_) rhs.col(p_) += 0.5 * p.force_amplitude;
  const MatrixXc Z = Solver(H_).SolveLinear(point.omega, rhs);
  MatrixXc Q = problem_.reduction.cast<Complex>() * Z;
  Q.col(0) += problem_.static_response.cast<Complex>();
  return Q;
}

NhbSolver& SystemPointDescriber::Solver(int H) {
  if (!solver_ || solver_->harmonics() != H) {
    solver_ = std::make_unique<NhbSolver>(problem_.problem, options_, H);
  }
  return *solver_;
}

SystemNhbPoint SystemPointDescriber::Describe(const NhbPoint& point) {
  SystemNhbPoint out;
  out.point = point;
  out.mesh_frequency_hz = point.omega / (2.0 * std::numbers::pi);
  Sample(point);
  const MeshForceSamples f = law_.SampleMeshForces(u_, phase_);
  MatrixXc Nk;  // exact force harmonics, when the engine integrates exactly
  for (int m = 0; m < model_.num_meshes(); ++m) {
    const int c = problem_.mesh_eta_coordinate[m];
    if (c < 0) continue;
    SystemNhbMeshOutput mo;
    mo.name = model_.meshes()[m].name;
    const VectorX dte = u_.row(c).transpose() - f.te_eta.row(m).transpose();
    mo.mean_dte = dte.mean();
    mo.rms_dte = std::sqrt((dte.array() - mo.mean_dte).square().mean());
    mo.peak_to_peak_dte = dte.maxCoeff() - dte.minCoeff();
    const VectorX a = cos_ * dte / S_, b = sin_ * dte / S_;  // Re, −Im of Y_k
    mo.dte_amplitudes = (a.array().square() + b.array().square()).sqrt() * 2.0;
    mo.dte_amplitudes(0) = std::abs(a(0));
    const VectorX force = f.force_eta.row(m).transpose();
    mo.mean_force = force.mean();
    if (exact_) {
      // The exact θ-mean: F = g̃ + K̄2 δ, so mean F_η = N_0 + (K̄2 U_0)_η (the samples' mean errs
      // by O(1/S) at the stiffness steps, 3e-3 at H = 8).
      if (Nk.size() == 0) Nk = ForceHarmonics(point);
      for (const MeshForceTerm& term : law_.terms()) {
        if (term.mesh != m) continue;
        double mean = Nk(term.first, 0).real();
        for (int j = 0; j < term.count; ++j) {
          mean += term.mean_k2(0, j) * point.harmonics(term.first + j, 0).real();
        }
        mo.mean_force = mean;
      }
    }
    mo.rms_force = std::sqrt((force.array() - mo.mean_force).square().mean());
    mo.min_force = force.minCoeff();
    mo.max_force = force.maxCoeff();
    mo.contact_loss_fraction = 1.0 - f.drive_loaded.row(m).mean();
    mo.back_contact = f.back_loaded.row(m).maxCoeff() > 0.0;
    out.meshes.push_back(std::move(mo));
  }
  if (!element_forces_ && !keep_response_) return out;
  const MatrixXc Q = RecoverResponse(point);
  if (keep_response_) out.response = Q;
  if (!element_forces_) return out;
  const double w = point.omega / p_;
  const Complex I(0.0, 1.0);
  for (const SystemElement& e : model_.elements()) {
    SystemNhbElementOutput eo;
    eo.name = e.name;
    const int ne = static_cast<int>(e.dofs.size());
    Vector6 sum2 = Vector6::Zero();
    for (int k = 0; k <= H_; ++k) {
      VectorXc qe = VectorXc::Zero(ne);
      for (int a = 0; a < ne; ++a) {
        if (e.dofs[a] >= 0) qe(a) = Q(e.dofs[a], k);
      }
      MatrixXc op = e.stiffness.cast<Complex>();
      if (e.damping.size() > 0) op += (I * double(k) * w) * e.damping.cast<Complex>();
      const VectorXc fe = op.topRows(6) * qe;
      if (k == 0) {
        eo.mean_force = fe.real();
      } else {
        sum2 += 2.0 * fe.cwiseAbs2();
      }
    }
    eo.rms_force = sum2.cwiseSqrt();
    out.elements.push_back(std::move(eo));
  }
  return out;
}

}  // namespace geardyn::internal
