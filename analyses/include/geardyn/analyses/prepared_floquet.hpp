/// @file
/// @brief A SystemModel prepared once for many ComputeFloquet calls that differ only in the mesh
/// frequency and the tolerance (a stability chart's row over speed).
///
/// **What is prepared.** ComputeFloquet(model, options) with kMagnus rebuilds, on every call, the
/// scaled first-order system (mass factor, rigid-mode deflation, 16 samples of K and C) and
/// assembles A(t) = [[0, ω_s I], [−BᵀK(θ)B/ω_s, −BᵀC(θ)B]] from the model at every Magnus node
/// (K(θ), C(θ) and two congruences per node: ≈ 25 % of a chart's CPU). None of it depends on the
/// mesh frequency: A is a function of the phase θ = ω_m t alone, and the state basis B, ω_s and
/// the rigid modes come from θ-samples. So they are built once here, and A(θ) is stored as its
/// Fourier series in φ = θ/P_K (P_K the operator period in mesh cycles):
///   A(θ) = A₀ + Σ_{m=1..M} (A_m^c cos mφ + A_m^s sin mφ),
/// from S = 64 equispaced samples of the ordinary A(θ) (the DFT, exact for a trigonometric
/// polynomial of degree M < S/2: a Fourier-form mesh stiffness with smooth or constant other
/// channels). Harmonics whose entries are all below 1e-15·max|A| are dropped.
///
/// **Proof of sameness, per model.** The series is accepted only when it reproduces the ordinary
/// A(θ) at the 64 midpoints between the samples (points the DFT never saw) to
/// kPreparedFitTolerance·max|A|; otherwise (tables, steps, kinks, harmonics above S/2) the
/// prepared object calls ComputeFloquet(model, options) unchanged. It is also used only where
/// ComputeFloquet would run kMagnus on the whole model whatever the frequency (method kMagnus, or
/// kAuto on a smooth model too small for a modal projection: internal::FrequencyIndependentMethod),
/// per DOF block as ComputeFloquet splits them (a block that does not qualify, e.g. a constant
/// one, runs ComputeFloquet's own path), with a nonzero stiffness (ω_s then does not depend on the
/// period). The result then
/// equals ComputeFloquet(model, options) to round-off: the same Magnus step counts, estimates
/// and verdicts, max|λ| within ≈ 1e-13 (tests/analyses/floquet/prepared_floquet_test.cpp).
#pragma once

#include <memory>
#include <vector>

#include "geardyn/analyses/floquet.hpp"

namespace geardyn {

/// Largest error of the prepared Fourier series of A(θ) at the check points, relative to
/// max|A_ij| over the samples [-] (a few hundred ulps; the DFT of a trigonometric polynomial
/// reproduces it to ≈ 1e-16).
inline constexpr double kPreparedFitTolerance = 1e-13;

/// @brief See the @file. Thread-safe: Compute is const and shares only immutable data.
class PreparedFloquet {
 public:
  /// @brief Prepares `model` for calls with these options (mesh_frequency_hz and tolerance
  /// ignored here). Never throws for a model or options ComputeFloquet refuses: Compute then
  /// throws what ComputeFloquet throws.
  PreparedFloquet(std::shared_ptr<const SystemModel> model, const FloquetOptions& options);

  /// @brief ComputeFloquet(model(), options) (see the @file: the prepared form when `options`
  /// has the prepared method, rigid-mode and block settings, else the ordinary call).
  /// @throws InvalidInput as ComputeFloquet.
  FloquetResult Compute(const FloquetOptions& options) const;

  /// True when Compute uses the prepared form (for at least one DOF block) for the options given
  /// at construction.
  bool prepared() const { return !blocks_.empty(); }
  /// M: the highest harmonic of A's series over the prepared blocks (0: A constant), −1 when
  /// not prepared.
  int harmonics() const;
  /// The largest relative error of the series at the check points over the blocks tried (NaN
  /// when not prepared) [-].
  double fit_error() const { return fit_error_; }
  const SystemModel& model() const { return *model_; }

  struct Impl;

 private:
  // One DOF block as ComputeFloquet splits them; impl null: that block runs the ordinary path
  // (e.g. a block without a mesh: constant, exact steps).
  struct Block {
    std::shared_ptr<const SystemModel> model;
    std::shared_ptr<const Impl> impl;
  };
  static std::shared_ptr<const Impl> Prepare(const SystemModel& model,
                                             const FloquetOptions& options, double* fit_error);
  static FloquetResult Solve(const Block& block, const FloquetOptions& options);

  std::shared_ptr<const SystemModel> model_;
  FloquetOptions options_;
  std::vector<Block> blocks_;  // empty: not prepared
  double fit_error_;
};

}  // namespace geardyn
