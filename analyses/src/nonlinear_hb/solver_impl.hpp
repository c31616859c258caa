/// @file
/// @brief Private state of NhbSolver: FFTW plans, AFT buffers, the condensed linear part cache
/// and the Newton scratch (all sized once in the constructor).
#pragma once

#include <fftw3.h>

#include <Eigen/LU>
#include <vector>

#include "geardyn/analyses/nonlinear_hb.hpp"

namespace geardyn {

struct NhbSolver::Impl {
  Impl(NhbProblem problem_in, const NhbOptions& options_in, int harmonics);
  ~Impl();
  Impl(const Impl&) = delete;
  Impl& operator=(const Impl&) = delete;

  NhbProblem problem;
  NhbOptions options;
  int n = 0;     ///< Nonlinear coordinates.
  int dofs = 0;  ///< N.
  int H = 0;
  int S = 0;  ///< AFT samples per base period.
  int m = 0;  ///< n(2H+1).
  int p = 1;  ///< Period multiple.

  // FFTW (plans on time_buf/freq_buf, made once).
  double* time_buf = nullptr;
  fftw_complex* freq_buf = nullptr;
  fftw_plan r2c = nullptr;
  fftw_plan c2r = nullptr;

  // AFT scratch.
  VectorX phase;               ///< Ω t_s = p·2πs/S.
  MatrixX u;                   ///< n×S.
  MatrixX g;                   ///< n×S.
  MatrixX dg;                  ///< n²×S.
  MatrixXc g_h;                ///< n×(H+1): N_k.
  std::vector<MatrixXc> dg_h;  ///< 2H+1 blocks n×n: G_j, j = 0..2H.

  // Condensed linear part, cached per Ω.
  double cached_omega;
  std::vector<MatrixXc> Z, dZ;  ///< k = 0..H.
  std::vector<VectorXc> F, dF;  ///< k = 0..H.
  double force_scale = 1.0;  ///< 1 + max ‖F̃_k‖∞ + ‖f₀‖∞ (Newton tolerance scale).

  // Newton scratch.
  MatrixX J;
  VectorX R, dx, x_trial, R_trial;
  Eigen::PartialPivLU<MatrixX> lu;

  // Contact switches (switches.cpp).
  bool has_switch_function = false;  ///< The law provides SwitchFunction.
  MatrixX sw;                        ///< n×S switching function at the samples.
  MatrixX u1, du1, sw1;              ///< One-column scratch for the root finder.
  VectorX theta1, phase1;

  /// Index of Re U_k (k ≥ 1) of coordinate i in x; U_0 at i; Im U_k right after Re U_k block.
  int Re(int k, int i) const { return k == 0 ? i : n * (2 * k - 1) + i; }
  int Im(int k, int i) const { return n * 2 * k + i; }

  void UpdateLinear(double omega);
  void Synthesize(const VectorX& x);
  void AnalyseForce();
  void AnalyseJacobian();
  /// Residual (and Jacobian, Ω-derivative when non-null) from the current x.
  void Evaluate(const VectorX& x, double omega, VectorX* residual, MatrixX* jacobian,
                VectorX* d_omega);
  /// u(θ) and du/dθ (n×T each, du may be null) at base angles θ = ωt [rad] from x.
  void SynthesizeAt(const VectorX& x, const VectorX& theta, MatrixX& uu, MatrixX* du) const;
  /// Switching function of coordinate i at base angle θ (law->SwitchFunction on one column).
  double SwitchValueAt(const VectorX& x, int i, double theta);
  /// Root of the switching function of coordinate i in [a, b] (values fa, fb of opposite
  /// sign, "positive" = fa > 0) by the Illinois method to ~1e-14 relative in θ.
  double LocateSwitch(const VectorX& x, int i, double a, double fa, double b, double fb);
  /// Adds the Euler–Maclaurin kink terms to g_h (nonlinear_hb.hpp "AFT"); needs u, dg, g_h.
  void CorrectForceAtSwitches(const VectorX& x);
  double MonodromyMaxMultiplier(const VectorX& x, double omega);
  double HillMaxMultiplier(const VectorX& x, double omega);
};

}  // namespace geardyn
