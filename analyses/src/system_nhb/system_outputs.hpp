/// @file
/// @brief From an engine point (harmonics of the nonlinear coordinates u) to the system outputs
/// of system_nonlinear_hb.hpp: DTE and mesh-force statistics from time samples, and the element
/// forces from the recovered response q_k = T D_k⁻¹ (F_k − P_zᵀ N_k).
#pragma once

#include <memory>

#include "geardyn/analyses/system_nonlinear_hb.hpp"
#include "system_nhb/mesh_force_law.hpp"

namespace geardyn::internal {

/// @brief Describes engine points of one SystemNhbProblem (tables sized once per H).
class SystemPointDescriber {
 public:
  /// @param[in] options the engine options (p = period_multiple: the base frequency is Ω/p; the
  ///   outputs sample u at the engine's AFT points, so that the recovered response solves the
  ///   same discrete equations).
  SystemPointDescriber(const SystemModel& model, const SystemNhbProblem& problem,
                       const NhbOptions& options, bool element_forces, bool keep_response);
  /// @brief The system outputs of `point` (its omega is Ω = 2π f_m [rad/s]).
  SystemNhbPoint Describe(const NhbPoint& point);
  /// @brief The one-sided harmonics Q_k (N × (H+1)) [m, rad] of q recovered from `point`.
  MatrixXc RecoverResponse(const NhbPoint& point);

 private:
  void Sample(const NhbPoint& point);  ///< u_, phase_ at S_ samples per base period
  /// N_k (n × (H+1)) of `point` as the engine computes them.
  MatrixXc ForceHarmonics(const NhbPoint& point);
  /// The engine for H (made once per H).
  NhbSolver& Solver(int H);

  const SystemModel& model_;
  const SystemNhbProblem& problem_;
  const MeshForceLaw& law_;
  NhbOptions options_;  ///< the engine's (period multiple p, AFT samples)
  int p_ = 1;
  bool element_forces_ = true;
  bool keep_response_ = false;
  bool exact_ = false;  ///< the engine integrates the law exactly (N_k exact)
  int H_ = -1, S_ = 0;
  MatrixX cos_, sin_;  ///< (H+1) × S: cos/sin(2πks/S)
  MatrixX u_;          ///< n × S
  VectorX phase_;      ///< S: θ_s = p·2πs/S
  /// The engine for H_: N_k of the recovered response exactly as the engine computed them
  /// (exact integration or AFT), so that q solves the same discrete equations.
  std::unique_ptr<NhbSolver> solver_;
};

}  // namespace geardyn::internal
