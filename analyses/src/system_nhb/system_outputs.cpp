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
      keep_response_(keep_response) {}

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

MatrixXc SystemPointDescriber::RecoverResponse(const NhbPoint& point) {
  Sample(point);
  const NhbProblem& p = problem_.problem;
  MatrixX g, dg;
  p.law->Evaluate(u_, phase_, g, dg);
  // N_k = (1/S) Σ_s g_s e^{−ik2πs/S}.
  const MatrixXc Nk = (g * cos_.transpose().cast<Complex>() -
                       Complex(0.0, 1.0) * (g * sin_.transpose()).cast<Complex>()) /
                      static_cast<double>(S_);
  const double w = point.omega / p_;
  const Complex I(0.0, 1.0);
  const MatrixXc Pt = p.projection.transpose().cast<Complex>();
  MatrixXc Z(p.mass.rows(), H_ + 1);
  for (int k = 0; k <= H_; ++k) {
    const double kk = k;
    const MatrixXc D = (-kk * kk * w * w) * p.mass.cast<Complex>() +
                       (I * kk * w) * p.damping.cast<Complex>() + p.stiffness.cast<Complex>();
    VectorXc rhs = -Pt * Nk.col(k);
    if (k == 0) rhs += p.force_mean.cast<Complex>();
    if (k == p_) rhs += 0.5 * p.force_amplitude;
    Z.col(k) = D.partialPivLu().solve(rhs);
  }
  MatrixXc Q = problem_.reduction.cast<Complex>() * Z;
  Q.col(0) += problem_.static_response.cast<Complex>();
  return Q;
}

SystemNhbPoint SystemPointDescriber::Describe(const NhbPoint& point) {
  SystemNhbPoint out;
  out.point = point;
  out.mesh_frequency_hz = point.omega / (2.0 * std::numbers::pi);
  Sample(point);
  const MeshForceSamples f = law_.SampleMeshForces(u_, phase_);
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
