/// @file
/// @brief NhbClearanceLaw and the B&K (1995) oscillator problem.
#include <cmath>
#include <complex>
#include <utility>

#include "geardyn/analyses/nonlinear_hb_clearance.hpp"
#include "geardyn/common/check.hpp"

namespace geardyn {

NhbClearanceLaw::NhbClearanceLaw(VectorX stiffness, VectorX modulation, VectorX modulation_phase,
                                 VectorX front_gap, VectorX back_gap)
    : stiffness_(std::move(stiffness)),
      modulation_(std::move(modulation)),
      modulation_phase_(std::move(modulation_phase)),
      front_gap_(std::move(front_gap)),
      back_gap_(std::move(back_gap)) {
  const Eigen::Index n = stiffness_.size();
  GEARDYN_THROW_UNLESS(n > 0, "stiffness: at least one coordinate is needed");
  GEARDYN_CHECK_SIZE(modulation_.size(), n, "modulation");
  GEARDYN_CHECK_SIZE(modulation_phase_.size(), n, "modulation_phase");
  GEARDYN_CHECK_SIZE(front_gap_.size(), n, "front_gap");
  GEARDYN_CHECK_SIZE(back_gap_.size(), n, "back_gap");
  for (Eigen::Index i = 0; i < n; ++i) {
    GEARDYN_THROW_UNLESS(
        std::isfinite(stiffness_[i]) && stiffness_[i] > 0,
        "stiffness[" << i << "]: must be positive and finite, got " << stiffness_[i]);
    GEARDYN_THROW_UNLESS(std::abs(modulation_[i]) < 1,
                         "modulation[" << i << "]: |α| must be < 1, got " << modulation_[i]);
    GEARDYN_THROW_UNLESS(std::isfinite(modulation_phase_[i]),
                         "modulation_phase[" << i << "]: must be finite");
    GEARDYN_THROW_UNLESS(std::isfinite(front_gap_[i]) && front_gap_[i] >= 0,
                         "front_gap[" << i << "]: must be ≥ 0 and finite, got " << front_gap_[i]);
    GEARDYN_THROW_UNLESS(
        back_gap_[i] >= -front_gap_[i],
        "back_gap[" << i << "]: must be ≥ −front_gap (or +inf), got " << back_gap_[i]);
  }
}

void NhbClearanceLaw::Evaluate(const MatrixX& u, const VectorX& phase, MatrixX& force,
                               MatrixX& jacobian) const {
  const Eigen::Index n = stiffness_.size();
  const Eigen::Index samples = u.cols();
  jacobian.setZero();
  for (Eigen::Index s = 0; s < samples; ++s) {
    for (Eigen::Index i = 0; i < n; ++i) {
      const double k =
          stiffness_[i] * (1.0 + modulation_[i] * std::cos(phase[s] + modulation_phase_[i]));
      const double x = u(i, s);
      double c = 0.0;
      double dc = 0.0;
      if (x > front_gap_[i]) {
        c = x - front_gap_[i];
        dc = 1.0;
      } else if (x < -back_gap_[i]) {
        c = x + back_gap_[i];
        dc = 1.0;
      }
      force(i, s) = k * c;
      jacobian(i + n * i, s) = k * dc;
    }
  }
}

bool NhbClearanceLaw::SwitchFunction(const MatrixX& u, const VectorX& phase, MatrixX& value) const {
  (void)phase;
  const Eigen::Index n = stiffness_.size();
  for (Eigen::Index s = 0; s < u.cols(); ++s) {
    for (Eigen::Index i = 0; i < n; ++i) {
      const double front = u(i, s) - front_gap_[i];
      value(i, s) = std::isfinite(back_gap_[i]) ? front * (u(i, s) + back_gap_[i]) : front;
    }
  }
  return true;
}

bool NhbClearanceLaw::PiecewiseLinearForm(NhbPiecewiseLinearForm* form) const {
  const Eigen::Index n = stiffness_.size();
  form->modulation.resize(n, 2);
  form->slope.resize(n);
  form->offset.resize(n);
  form->ramp_points.assign(static_cast<size_t>(n), {});
  form->ramp_slopes.assign(static_cast<size_t>(n), {});
  for (Eigen::Index i = 0; i < n; ++i) {
    const size_t ii = static_cast<size_t>(i);
    // k(1 + α cos(φ + ψ)) = k + (kα/2) e^{iψ} e^{iφ} + c.c.
    form->modulation(i, 0) = stiffness_[i];
    form->modulation(i, 1) = std::polar(0.5 * stiffness_[i] * modulation_[i], modulation_phase_[i]);
    const bool back = std::isfinite(back_gap_[i]);
    form->slope[i] = back ? 1.0 : 0.0;
    form->offset[i] = back ? back_gap_[i] : 0.0;
    if (back) {
      form->ramp_points[ii].push_back(-back_gap_[i]);
      form->ramp_slopes[ii].push_back(-1.0);
    }
    form->ramp_points[ii].push_back(front_gap_[i]);
    form->ramp_slopes[ii].push_back(1.0);
  }
  return true;
}

void NhbClearanceLaw::ContactBranch(MatrixX& stiffness, VectorX& offset) const {
  stiffness = stiffness_.asDiagonal();
  offset = -stiffness_.cwiseProduct(front_gap_);
}

NhbProblem MakeClearanceOscillator(const ClearanceOscillatorParameters& p) {
  GEARDYN_THROW_UNLESS(std::isfinite(p.zeta) && p.zeta >= 0,
                       "zeta: must be ≥ 0 and finite, got " << p.zeta);
  GEARDYN_THROW_UNLESS(std::isfinite(p.mean_force), "mean_force: must be finite");
  GEARDYN_THROW_UNLESS(std::isfinite(p.alternating_force), "alternating_force: must be finite");
  NhbProblem problem;
  problem.mass = MatrixX::Ones(1, 1);
  problem.damping = MatrixX::Constant(1, 1, 2.0 * p.zeta);
  problem.stiffness = MatrixX::Zero(1, 1);
  problem.projection = MatrixX::Ones(1, 1);
  problem.force_mean = VectorX::Constant(1, p.mean_force);
  problem.force_amplitude = VectorXc::Constant(1, std::polar(p.alternating_force, p.force_phase));
  problem.law = std::make_shared<NhbClearanceLaw>(
      VectorX::Ones(1), VectorX::Constant(1, p.alpha), VectorX::Zero(1), VectorX::Ones(1),
      VectorX::Constant(1, p.back_contact ? 1.0 : NhbClearanceLaw::kNoBackContact));
  return problem;
}

}  // namespace geardyn
