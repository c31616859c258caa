/// @file
/// @brief The implicit method: generalized-α of Chung & Hulbert (1993), J. Appl. Mech. 60(2)
/// 371–375, with Newton on the analytic tangent and the local error estimate of Zienkiewicz &
/// Xie (1991), e = (β − 1/6) h² (a_{n+1} − a_n); the energy quadrature by the trapezoidal rule on
/// the step ends.
#include <Eigen/LU>
#include <Eigen/SparseLU>
#include <algorithm>
#include <limits>
#include <vector>

#include "td_steppers.hpp"

namespace geardyn::internal {
namespace {

class AlphaStepper final : public TdStepper {
 public:
  AlphaStepper(const TdSystem& sys, const TimeIntegrationOptions& options, TdScales scales,
               double omega, double theta0)
      : TdStepper(sys, options, std::move(scales), omega, theta0) {
    // Chung–Hulbert parameters for the spectral radius ρ∞ at infinite frequency.
    const double rho = options.spectral_radius;
    alpha_m_ = (2.0 * rho - 1.0) / (rho + 1.0);
    alpha_f_ = rho / (rho + 1.0);
    gamma_ = 0.5 - alpha_m_ + alpha_f_;
    beta_ = 0.25 * (1.0 - alpha_m_ + alpha_f_) * (1.0 - alpha_m_ + alpha_f_);
    a_ = trial_a_ = VectorX::Zero(sys.n);
    // Large systems: the iteration matrix is sparse (bodies couple through elements and meshes,
    // teeth through their trunk and their contacts); assembled from triplets, factored by
    // SparseLU with the pattern analysis reused while the contact pattern stays the same.
    sparse_ = sys.n >= options.sparse_threshold;
    ws_.sparse_tangents = sparse_;
  }

 protected:
  int order() const override { return 2; }

  void OnReset() override {
    // Consistent initial acceleration a = M⁻¹ force(x, v, t) and the end-point powers.
    sys_.mass_solver->Solve(ws_.force, &a_);
    power_ = ws_.mesh_phase_power;
    dissipation_ = DissipationPower(sys_, ws_, v_);
  }

  void OnRestart() override { OnReset(); }

  double TrialStep(double h) override {
    constexpr double kInf = std::numeric_limits<double>::infinity();
    trial_h_ = h;
    const int n = sys_.n;
    VectorX a1 = a_;  // predictor: constant acceleration
    const double t_alpha = t_ + (1.0 - alpha_f_) * h;
    bool converged = false;
    for (int it = 0; it < options_.max_newton_iterations; ++it) {
      trial_x_ = x_ + h * v_ + h * h * ((0.5 - beta_) * a_ + beta_ * a1);
      trial_v_ = v_ + h * ((1.0 - gamma_) * a_ + gamma_ * a1);
      const VectorX x_alpha = (1.0 - alpha_f_) * trial_x_ + alpha_f_ * x_;
      const VectorX v_alpha = (1.0 - alpha_f_) * trial_v_ + alpha_f_ * v_;
      Eval(t_alpha, x_alpha, v_alpha, true);
      const VectorX residual =
          sys_.mass_sparse * ((1.0 - alpha_m_) * a1 + alpha_m_ * a_) - ws_.force;
      if (!residual.allFinite()) return kInf;
      const double ck = (1.0 - alpha_f_) * beta_ * h * h, cc = (1.0 - alpha_f_) * gamma_ * h;
      VectorX da;
      if (sparse_) {
        if (!FactorSparse(ck, cc)) return kInf;
        da = lu_.solve(residual);
      } else {
        const MatrixX jac = (1.0 - alpha_m_) * sys_.mass + ck * ws_.tangent_k + cc * ws_.tangent_c;
        const Eigen::PartialPivLU<MatrixX> lu(jac);
        da = lu.solve(residual);
      }
      if (!da.allFinite()) return kInf;
      a1 -= da;
      // Newton update in the units of the local error tolerance.
      const VectorX dx = beta_ * h * h * da, dv = gamma_ * h * da;
      if (ErrorNorm(dx, dv, trial_x_, trial_v_) <= options_.newton_tolerance) {
        converged = true;
        break;
      }
    }
    if (!converged) return kInf;
    trial_x_ = x_ + h * v_ + h * h * ((0.5 - beta_) * a_ + beta_ * a1);
    trial_v_ = v_ + h * ((1.0 - gamma_) * a_ + gamma_ * a1);
    trial_a_ = a1;
    // Energy quadrature on the nodes 0, τ = 1 − α_f (the α-point, where the step's equation is
    // enforced) and 1, exact for quadratics: Simpson's rule for ρ∞ = 1.
    const double tau = 1.0 - alpha_f_;
    const VectorX x_alpha = (1.0 - alpha_f_) * trial_x_ + alpha_f_ * x_;
    const VectorX v_alpha = (1.0 - alpha_f_) * trial_v_ + alpha_f_ * v_;
    Eval(t_alpha, x_alpha, v_alpha, false);
    const double power_alpha = ws_.mesh_phase_power;
    const double dissipation_alpha = DissipationPower(sys_, ws_, v_alpha);
    Eval(t_ + h, trial_x_, trial_v_, false);
    if (!ws_.force.allFinite()) return kInf;
    trial_power_ = ws_.mesh_phase_power;
    trial_dissipation_ = DissipationPower(sys_, ws_, trial_v_);
    // ρ∞ = 0 gives α_f = 0, τ = 1: the α-point is the step end and the three-node rule
    // degenerates (w_τ = 1/0, a NaN energy balance; issue 16) — the trapezoidal rule then.
    const bool degenerate = 1.0 - tau < 1e-6;
    const double w_tau = degenerate ? 0.0 : 1.0 / (6.0 * tau * (1.0 - tau));
    const double w_1 = degenerate ? 0.5 : 0.5 - w_tau * tau;
    const double w_0 = 1.0 - w_tau - w_1;
    trial_work_ = h * (w_0 * power_ + w_tau * power_alpha + w_1 * trial_power_);
    trial_dissipated_ =
        h * (w_0 * dissipation_ + w_tau * dissipation_alpha + w_1 * trial_dissipation_);
    trial_switching_ = ws_.switching;
    trial_live_ = ws_.switching_live;
    const VectorX err_x = (beta_ - 1.0 / 6.0) * h * h * (a1 - a_);
    (void)n;
    return ErrorNorm(err_x, VectorX(), trial_x_, trial_v_);
  }

  void Commit() override {
    x_ = trial_x_;
    v_ = trial_v_;
    a_ = trial_a_;
    power_ = trial_power_;
    dissipation_ = trial_dissipation_;
  }

 private:
  /// J = (1 − α_m) M + ck K_t + cc C_t from the triplets of the last evaluation, factored into
  /// lu_ (symbolic analysis only when the nonzero pattern changed). False when singular.
  bool FactorSparse(double ck, double cc) {
    triplets_.clear();
    AppendTriplets(sys_.mass_sparse, 1.0 - alpha_m_, &triplets_);
    for (const auto& e : ws_.tangent_k_triplets)
      triplets_.emplace_back(e.row(), e.col(), ck * e.value());
    for (const auto& e : ws_.tangent_c_triplets)
      triplets_.emplace_back(e.row(), e.col(), cc * e.value());
    jac_.resize(sys_.n, sys_.n);
    jac_.setFromTriplets(triplets_.begin(), triplets_.end());
    jac_.makeCompressed();
    const auto nnz = static_cast<std::size_t>(jac_.nonZeros());
    const bool same = analyzed_ && outer_.size() == static_cast<std::size_t>(sys_.n) + 1 &&
                      inner_.size() == nnz &&
                      std::equal(outer_.begin(), outer_.end(), jac_.outerIndexPtr()) &&
                      std::equal(inner_.begin(), inner_.end(), jac_.innerIndexPtr());
    if (!same) {
      lu_.analyzePattern(jac_);
      outer_.assign(jac_.outerIndexPtr(), jac_.outerIndexPtr() + sys_.n + 1);
      inner_.assign(jac_.innerIndexPtr(), jac_.innerIndexPtr() + nnz);
      analyzed_ = true;
    }
    lu_.factorize(jac_);
    return lu_.info() == Eigen::Success;
  }

  bool sparse_ = false;
  std::vector<Eigen::Triplet<double>> triplets_;
  SparseMatrix jac_;
  Eigen::SparseLU<SparseMatrix> lu_;
  bool analyzed_ = false;
  std::vector<int> outer_, inner_;  // pattern of the last symbolic analysis
  double alpha_m_ = 0.0, alpha_f_ = 0.0, gamma_ = 0.5, beta_ = 0.25;
  VectorX a_, trial_a_;
  double power_ = 0.0, dissipation_ = 0.0, trial_power_ = 0.0, trial_dissipation_ = 0.0;
};

}  // namespace

std::unique_ptr<TdStepper> MakeAlphaStepper(const TdSystem& sys,
                                            const TimeIntegrationOptions& options, TdScales scales,
                                            double omega, double theta0) {
  return std::make_unique<AlphaStepper>(sys, options, std::move(scales), omega, theta0);
}

}  // namespace geardyn::internal
