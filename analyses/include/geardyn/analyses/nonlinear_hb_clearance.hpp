/// @file
/// @brief Piecewise-linear clearance law for the nonlinear harmonic balance and the
/// Blankenship & Kahraman (1995) oscillator built from it.
#pragma once

#include <limits>

#include "geardyn/analyses/nonlinear_hb.hpp"

namespace geardyn {

/// @brief Per coordinate i: g_i(u, φ) = k_i (1 + α_i cos(φ + ψ_i)) c_i(u) with the clearance
/// function c(u) = u − b for u > b (drive-side contact), 0 for −a ≤ u ≤ b (contact loss),
/// u + a for u < −a (back-side contact). b: front gap, a: back gap (+∞: single-sided, no back
/// flank). A gear mesh in δ has b = 0, a = j (the backlash, as SliceMeshCore's g(a) =
/// [a]₊ − [−a − j]₊); the B&K oscillator has a = b = 1. ∂g/∂u is k(1 + α cos) on the contact
/// pieces and 0 in the gap (the value at the kinks is that of the gap).
class NhbClearanceLaw final : public NhbNonlinearLaw {
 public:
  static constexpr double kNoBackContact = std::numeric_limits<double>::infinity();
  /// @param stiffness k_i > 0, @param modulation α_i with |α_i| < 1, @param modulation_phase
  /// ψ_i [rad], @param front_gap b_i ≥ 0 [u units], @param back_gap a_i ≥ −b_i or +∞.
  /// @throws InvalidInput naming the parameter on mismatched sizes or bad values.
  NhbClearanceLaw(VectorX stiffness, VectorX modulation, VectorX modulation_phase,
                  VectorX front_gap, VectorX back_gap);
  int num_coordinates() const override { return static_cast<int>(stiffness_.size()); }
  void Evaluate(const MatrixX& u, const VectorX& phase, MatrixX& force,
                MatrixX& jacobian) const override;
  void ContactBranch(MatrixX& stiffness, VectorX& offset) const override;
  /// (u − b)(u + a) (u − b when a = +∞): positive in contact, ≤ 0 in the gap.
  bool SwitchFunction(const MatrixX& u, const VectorX& phase, MatrixX& value) const override;
  /// κ = k(1 + α cos(φ + ψ)); c(u) = u + a − [u + a]₊ + [u − b]₊ (c(u) = [u − b]₊ when
  /// a = +∞).
  bool PiecewiseLinearForm(NhbPiecewiseLinearForm* form) const override;

 private:
  VectorX stiffness_, modulation_, modulation_phase_, front_gap_, back_gap_;
};

/// @brief Parameters of the dimensionless B&K (1995) oscillator
/// x'' + 2ζ x' + (1 + α cos(Ωt)) g(x) = F_m + F_a cos(Ωt + φ), with g(x) = x − 1 (x > 1),
/// 0 (|x| ≤ 1), x + 1 (x < −1): time in units of 1/ω_n, x in units of the half clearance b.
struct ClearanceOscillatorParameters {
  double zeta = 0.05;              ///< ζ, damping ratio.
  double alpha = 0.0;              ///< α, parametric stiffness amplitude (|α| < 1).
  double mean_force = 0.1;         ///< F_m.
  double alternating_force = 0.1;  ///< F_a.
  double force_phase = 0.0;        ///< φ [rad].
  bool back_contact = true;        ///< false: no back flank (g = 0 for x < −1 too).
};

/// @brief The B&K oscillator as an NhbProblem: N = n = 1, M = 1, C = 2ζ, K = 0, P = 1,
/// f₀ = F_m, f₁ = F_a e^{iφ}, law = NhbClearanceLaw(1, α, 0, 1, 1 or ∞).
NhbProblem MakeClearanceOscillator(const ClearanceOscillatorParameters& parameters);

}  // namespace geardyn
