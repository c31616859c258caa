/// @file
/// @brief The explicit method: GSL's rk8pd (Prince–Dormand 8(7)) single steps with this
/// module's step control and event location; the energy quadrature as two extra ODE states.
#include <gsl/gsl_errno.h>
#include <gsl/gsl_odeiv2.h>

#include <cmath>
#include <limits>

#include "td_steppers.hpp"

namespace geardyn::internal {
namespace {

class RkStepper final : public TdStepper {
 public:
  RkStepper(const TdSystem& sys, const TimeIntegrationOptions& options, TdScales scales,
            double omega, double theta0)
      : TdStepper(sys, options, std::move(scales), omega, theta0),
        dim_(2 * sys.n + 2),
        y_(VectorX::Zero(dim_)),
        yerr_(VectorX::Zero(dim_)),
        acc_(VectorX::Zero(sys.n)) {
    step_ = gsl_odeiv2_step_alloc(gsl_odeiv2_step_rk8pd, static_cast<size_t>(dim_));
    system_ = gsl_odeiv2_system{&Rhs, nullptr, static_cast<size_t>(dim_), this};
  }
  ~RkStepper() override { gsl_odeiv2_step_free(step_); }
  RkStepper(const RkStepper&) = delete;
  RkStepper& operator=(const RkStepper&) = delete;

 protected:
  int order() const override { return 7; }

  double TrialStep(double h) override {
    const int n = sys_.n;
    y_.head(n) = x_;
    y_.segment(n, n) = v_;
    y_.tail(2).setZero();  // quadrature increments over this step
    gsl_odeiv2_step_reset(step_);
    const int status =
        gsl_odeiv2_step_apply(step_, t_, h, y_.data(), yerr_.data(), nullptr, nullptr, &system_);
    trial_h_ = h;
    if (status != GSL_SUCCESS || !y_.allFinite()) return std::numeric_limits<double>::infinity();
    trial_x_ = y_.head(n);
    trial_v_ = y_.segment(n, n);
    trial_work_ = y_(2 * n);
    trial_dissipated_ = y_(2 * n + 1);
    double err = ErrorNorm(yerr_.head(n), yerr_.segment(n, n), trial_x_, trial_v_);
    Eval(t_ + h, trial_x_, trial_v_, false);
    if (sys_.num_switching > 0 && options_.locate_events) {
      trial_switching_ = ws_.switching;
      trial_live_ = ws_.switching_live;
    }
    // The energy quadrature in the error control: its increments against the energy the step
    // moves (|W| + D + |ΔE| of the step), so that a kink of P or D that the state hardly sees
    // (e.g. the involute → tip-corner hand-over) cannot spoil the balance unnoticed.
    trial_mesh_energy_ = ws_.mesh_energy;
    const double moved = std::abs(trial_work_) + std::abs(trial_dissipated_) +
                         std::abs(trial_mesh_energy_ - mesh_energy_);
    energy_scale_ = std::max(energy_scale_, std::abs(trial_mesh_energy_));
    const double scale =
        options_.relative_tolerance * moved + options_.absolute_tolerance * energy_scale_;
    const double err_e = (std::abs(yerr_(2 * n)) + std::abs(yerr_(2 * n + 1))) / scale;
    if (scale > 0.0) err = std::max(err, err_e);
    return err;
  }

  void OnReset() override {
    mesh_energy_ = ws_.mesh_energy;
    energy_scale_ = std::max(energy_scale_, std::abs(mesh_energy_));
  }
  void OnRestart() override { mesh_energy_ = ws_.mesh_energy; }

  void Commit() override {
    x_ = trial_x_;
    v_ = trial_v_;
    mesh_energy_ = trial_mesh_energy_;
  }

 private:
  // ẋ = v, M v̇ = force, Ẇ = ΣP, Ḋ = vᵀC0v + ΣD.
  static int Rhs(double t, const double y[], double dydt[], void* params) {
    auto* self = static_cast<RkStepper*>(params);
    const int n = self->sys_.n;
    Eigen::Map<const VectorX> x(y, n), v(y + n, n);
    self->Eval(t, x, v, false);
    if (!self->ws_.force.allFinite()) return GSL_EBADFUNC;
    self->sys_.mass_solver->Solve(self->ws_.force, &self->acc_);
    Eigen::Map<VectorX>(dydt, n) = v;
    Eigen::Map<VectorX>(dydt + n, n) = self->acc_;
    dydt[2 * n] = self->ws_.mesh_phase_power;
    dydt[2 * n + 1] = DissipationPower(self->sys_, self->ws_, v);
    return GSL_SUCCESS;
  }

  double mesh_energy_ = 0.0, trial_mesh_energy_ = 0.0, energy_scale_ = 0.0;
  int dim_;
  VectorX y_, yerr_, acc_;
  gsl_odeiv2_step* step_ = nullptr;
  gsl_odeiv2_system system_{};
};

}  // namespace

std::unique_ptr<TdStepper> MakeRkStepper(const TdSystem& sys, const TimeIntegrationOptions& options,
                                         TdScales scales, double omega, double theta0) {
  return std::make_unique<RkStepper>(sys, options, std::move(scales), omega, theta0);
}

}  // namespace geardyn::internal
