/// @file
/// @brief Location of a fold (turning point in Ω) between two accepted continuation points A
/// and B whose tangents have opposite Ω components, to a requested relative tolerance.
///
/// Parametrisation: σ = t̂_Aᵀ(ŷ − ŷ_A), the pseudo-arclength along A's unit tangent in the
/// scaled variables ŷ = (x/x_scale, Ω/omega_scale); between A and B the tangent turns by less
/// than max_tangent_angle, so σ is monotone on the arc. At a given σ the point of the curve
/// solves the bordered system [R(x, Ω); t̂_Aᵀ(ŷ − ŷ_A) − σ] = 0 (Newton with the bordered
/// Jacobian [J R_Ω; t̂_A,x/x_scale t̂_A,Ω/omega_scale], regular at a simple fold where J is
/// singular), and the solution z of the same matrix with right-hand side [0; 1] is the tangent
/// dy/dσ, so f(σ) = dΩ/dσ = z_Ω is the function whose root is the fold.
/// f is smooth and nearly linear across a simple fold: its root is found by the Illinois
/// variant of regula falsi on [0, σ_B] (superlinear, always bracketed). With the slope f′ from
/// the bracket, Ω(σ) ≈ Ω_f − f²/(2f′) near the fold, so the fold is reported at the vertex
/// Ω_k − f_k²/(2f′) of the best iterate k, and its error estimate is the size of that
/// correction f_k²/(2|f′|) (the remaining error is of higher order in |σ_k − σ_f|).
#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <limits>

#include "nonlinear_hb/folds.hpp"

namespace geardyn::internal {
namespace {

/// Most root-finding iterations; a simple fold needs about five.
constexpr int kMaxFoldIterations = 40;

class FoldSystem {
 public:
  FoldSystem(NhbSolver& solver, const VectorX& ya, const VectorX& ta, double sx, double so,
             double residual_tolerance, int max_iterations)
      : solver_(solver),
        ya_(ya),
        ta_(ta),
        sx_(sx),
        so_(so),
        tol_(residual_tolerance),
        max_iterations_(max_iterations),
        m_(solver.num_unknowns()),
        R_(m_),
        dR_(m_),
        J_(m_, m_),
        B_(m_ + 1, m_ + 1),
        rhs_(m_ + 1) {}

  /// σ of a point y = (x, Ω).
  double Sigma(const VectorX& y) const {
    return ta_.head(m_).dot(y.head(m_) - ya_.head(m_)) / sx_ + ta_[m_] * (y[m_] - ya_[m_]) / so_;
  }

  /// Solves the curve point at `sigma` from the guess y (overwritten); on success `slope` is
  /// dΩ/dσ there. False when Newton does not converge.
  bool Solve(double sigma, VectorX& y, double* slope) {
    bool stagnated = false;
    for (int it = 0; it <= max_iterations_; ++it) {
      solver_.Evaluate(y.head(m_), y[m_], &R_, &J_, &dR_);
      B_.topLeftCorner(m_, m_) = J_;
      B_.topRightCorner(m_, 1) = dR_;
      B_.bottomLeftCorner(1, m_) = ta_.head(m_).transpose() / sx_;
      B_(m_, m_) = ta_[m_] / so_;
      lu_.compute(B_);
      const double res = R_.lpNorm<Eigen::Infinity>();
      const double border = Sigma(y) - sigma;
      if (!std::isfinite(res)) return false;
      // Converged; or stagnated at the residual floor (as the continuation's corrector).
      if ((res <= tol_ && std::abs(border) <= 1e-12 * (1.0 + std::abs(sigma))) ||
          (stagnated && res <= 1e3 * tol_)) {
        rhs_.setZero();
        rhs_[m_] = 1.0;
        const VectorX z = lu_.solve(rhs_);
        if (!z.allFinite()) return false;
        *slope = z[m_];
        return true;
      }
      rhs_.head(m_) = -R_;
      rhs_[m_] = -border;
      const VectorX dy = lu_.solve(rhs_);
      if (!dy.allFinite()) return false;
      y += dy;
      // In the scaled variables (x and Ω differ by many orders of magnitude).
      const double step =
          std::max(dy.head(m_).lpNorm<Eigen::Infinity>() / sx_, std::abs(dy[m_]) / so_);
      const double size =
          std::max(y.head(m_).lpNorm<Eigen::Infinity>() / sx_, std::abs(y[m_]) / so_);
      stagnated = step <= 1e-13 * (1.0 + size);
    }
    return false;
  }

 private:
  NhbSolver& solver_;
  const VectorX& ya_;
  const VectorX& ta_;
  double sx_, so_, tol_;
  int max_iterations_;
  int m_;
  VectorX R_, dR_;
  MatrixX J_, B_;
  VectorX rhs_;
  Eigen::PartialPivLU<MatrixX> lu_;
};

}  // namespace

FoldLocation LocateFold(NhbSolver& solver, const VectorX& ya, const VectorX& ta, const VectorX& yb,
                        double sx, double so, double residual_tolerance, double fold_tolerance,
                        int max_corrector_iterations) {
  const int m = solver.num_unknowns();
  FoldLocation out;
  out.y = ya;
  FoldSystem system(solver, ya, ta, sx, so, residual_tolerance,
                    std::max(max_corrector_iterations, 12));
  // Bracket [σ_a, σ_b] with f(σ_a), f(σ_b) of opposite sign (the ends are the accepted points,
  // re-solved only for their slopes).
  double sa = 0.0, sb = system.Sigma(yb);
  VectorX y_a = ya, y_b = yb;
  double fa = 0.0, fb = 0.0;
  if (!(sb > 0.0) || !system.Solve(sa, y_a, &fa) || !system.Solve(sb, y_b, &fb)) return out;
  out.evaluations = 2;
  if ((fa > 0) == (fb > 0)) return out;  // no sign change along t̂_A: not a simple fold
  // Illinois: the f value of an end kept twice in a row is halved (ga, gb); the slope f′ uses
  // the true values (fa, fb).
  int side = 0;
  double ga = fa, gb = fb;
  VectorX y(m + 1);
  double best_f = std::abs(fa) < std::abs(fb) ? fa : fb;
  VectorX best_y = std::abs(fa) < std::abs(fb) ? y_a : y_b;
  for (int k = 0; k < kMaxFoldIterations; ++k) {
    const double slope = (fb - fa) / (sb - sa);  // f′ from the bracket
    // The vertex of the local parabola Ω(σ) through the best iterate, and the correction size.
    const double correction = best_f * best_f / (2.0 * slope);
    out.omega = best_y[m] - correction;
    out.error = std::abs(correction);
    out.y = best_y;
    if (out.error <= fold_tolerance * std::abs(out.omega)) {
      out.converged = true;
      return out;
    }
    const double s = (sa * gb - sb * ga) / (gb - ga);
    if (!(s > sa && s < sb)) return out;  // bracket exhausted at round-off
    const double w = (s - sa) / (sb - sa);
    y = (1.0 - w) * y_a + w * y_b;
    double f = 0.0;
    ++out.evaluations;
    if (!system.Solve(s, y, &f)) return out;
    if (std::abs(f) < std::abs(best_f)) {
      best_f = f;
      best_y = y;
    }
    if ((f > 0) == (fa > 0)) {
      sa = s;
      fa = ga = f;
      y_a = y;
      if (side == -1) gb *= 0.5;
      side = -1;
    } else {
      sb = s;
      fb = gb = f;
      y_b = y;
      if (side == 1) ga *= 0.5;
      side = 1;
    }
  }
  return out;
}

}  // namespace geardyn::internal
