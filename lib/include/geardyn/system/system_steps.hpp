/// @file
/// @brief The step structure of a piecewise-constant system: the intervals of the system phase
/// on which K(θ) and C(θ) are constant (spec 02 "Floquet": Φ = Π expm(A_k Δt_k) is exact there).
///
/// **Phase and period.** Mesh k's phase is θ_k = r_k θ + φ_k (SystemMesh::MeshPhase). The system
/// period is T_θ = 2π·P [rad] with P = SystemModel::period_meshes() (the lcm of the cores'
/// periods, e.g. the hunting period lcm(z1, z2) when tooth-to-tooth errors are present) when every
/// r_k = 1, and the common period of FindCommonPeriodMeshes (common_period.hpp) for meshes at
/// different frequencies (a two-stage train with r = 7/40: P = 40); a point β of mesh k's own
/// phase is at θ = (β − φ_k)/r_k.
///
/// **Breakpoints.** Each core's piecewise-constant stiffness coefficient
/// (LinearMeshCore::stiffness, or SliceMeshCore::stiffness for the all-loaded linearization of
/// workspace.hpp) jumps at its breakpoints β (mesh phase, period 2π·P_k); in system phase they are
/// (β + 2π·P_k·j − φ_k)/r_k for j = 0 … r_k P/P_k − 1, reduced modulo T_θ. The union over meshes,
/// sorted, with points closer than merge_tol·T_θ merged, gives the interval starts; b_0 = 0 is
/// always one of them (so Φ runs from θ = 0), which may split an interval into two with equal K.
/// Mean-LTI cores and constant coefficients add none. The transmission error does not change K or C
/// and adds none (it enters only the load).
#pragma once

#include <cstdint>

#include "geardyn/common/eigen_types.hpp"
#include "geardyn/system/system_model.hpp"

namespace geardyn {

/// @brief Intervals [b_k, b_{k+1}) of the system phase with constant K and C; b_0 = 0 and the
/// last interval ends at T_θ. A constant system has one interval [0, T_θ).
struct SystemSteps {
  std::int64_t period_meshes = 1;  ///< P [-]
  double period = 0.0;             ///< T_θ = 2π·P [rad]
  VectorX breakpoints;             ///< (K ≥ 1) b_k [rad], b_0 = 0, strictly increasing, < T_θ

  /// Number of intervals K.
  int num_intervals() const { return static_cast<int>(breakpoints.size()); }
  /// Start b_k [rad].
  double interval_begin(int k) const { return breakpoints[k]; }
  /// End b_{k+1}, or T_θ for the last interval [rad].
  double interval_end(int k) const;
  /// Width [rad] (the widths sum to T_θ).
  double interval_width(int k) const { return interval_end(k) - interval_begin(k); }
  /// Midpoint [rad]: evaluate K and C there (AssembleStiffness / AssembleDamping).
  double interval_midpoint(int k) const { return 0.5 * (interval_begin(k) + interval_end(k)); }
};

/// @brief Throws InvalidInput naming the first mesh whose phase ratio is not 1 (meshes at
/// different frequencies, e.g. a two-stage train, make the system quasi-periodic).
void CheckSingleMeshFrequency(const SystemModel& model, const char* analysis);

/// @brief True when every core's K2 and C2 are constant or piecewise constant in θ (also for
/// slice cores, whose all-loaded linearization is what linear analyses use).
bool HasPiecewiseConstantOperator(const SystemModel& model);

/// @brief The step structure of the model (see the @file).
/// @param[in] merge_tol relative distance below which two breakpoints are one [-], ≥ 0.
/// @throws InvalidInput if the meshes have no common period (FindCommonPeriodMeshes) or an
///   operator coefficient is smooth (Fourier or table: use a smooth-coefficient method), naming
///   the mesh.
SystemSteps CollectSystemSteps(const SystemModel& model, double merge_tol = 1e-13);

/// @brief The phases where K(θ) or C(θ) is not smooth, over one period 2π·period_meshes of the
/// system phase: the breakpoints of piecewise-constant coefficients (jumps) and the samples of
/// table coefficients (their periodic linear interpolation has a kink at every sample); constant,
/// Fourier and mean-LTI coefficients add none. Between two consecutive points K and C are
/// analytic in θ, so a time stepper whose steps end on them keeps its nominal order (Floquet's
/// kink-aware Magnus, issue 12). Same phase convention as CollectSystemSteps (θ_k = r_k θ + φ_k).
/// @param[in] period_meshes P ≥ 1 [-]: a multiple of every operator coefficient's period (e.g.
///   the operator period P_K of Floquet).
/// @param[in] merge_tol relative distance below which two points are one [-], ≥ 0.
/// @return (K ≥ 1) sorted points in [0, 2π·P) [rad], b_0 = 0 (added when no coefficient has it).
/// @throws InvalidInput if P < 1 or merge_tol < 0.
VectorX CollectSystemKinks(const SystemModel& model, std::int64_t period_meshes,
                           double merge_tol = 1e-13);

}  // namespace geardyn
