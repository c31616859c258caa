/// @file
/// @brief The mesh-force law of the system nonlinear harmonic balance (system_nonlinear_hb.hpp):
/// per mesh k, g̃_k(u_k, θ) = F_k(u_k, θ_k) − K̄2_k u_k on its nonlinear coordinates u_k (δ_η, and
/// δ_ζ when used), F_k the slice force (contact loss, back flank) or the linear core force
/// K2(θ_k) δ − K2 ε(θ_k).
#pragma once

#include <mutex>
#include <vector>

#include "geardyn/analyses/nonlinear_hb.hpp"
#include "geardyn/system/system_model.hpp"

namespace geardyn::internal {

/// @brief The nonlinear coordinates of one mesh.
struct MeshForceTerm {
  int mesh = 0;                       ///< mesh index in the model
  int first = 0;                      ///< index of its δ_η in u
  int count = 1;                      ///< 1 (δ_η only) or 2 (δ_η, δ_ζ)
  Matrix2 mean_k2 = Matrix2::Zero();  ///< K̄2 (only the count × count corner is used)
};

/// @brief The mesh forces at S samples of (u, θ): what the outputs need besides g̃.
struct MeshForceSamples {
  MatrixX force_eta;     ///< (meshes × S) F_η [N]
  MatrixX te_eta;        ///< (meshes × S) ε_η subtracted in the DTE [m] (0 for slice cores)
  MatrixX drive_loaded;  ///< (meshes × S) 1 when the drive flank carries load, else 0
  MatrixX back_loaded;   ///< (meshes × S) 1 when the back flank carries load, else 0
};

/// @brief g̃ of every mesh term (see the file comment). Thread-safe (the per-phase cache of the
/// core coefficients is guarded by a mutex).
class MeshForceLaw final : public NhbNonlinearLaw {
 public:
  /// @param[in] model the system (copied: O(1), shared data).
  /// @param[in] terms the mesh terms, contiguous in u in this order.
  MeshForceLaw(const SystemModel& model, std::vector<MeshForceTerm> terms);

  int num_coordinates() const override { return n_; }
  void Evaluate(const MatrixX& u, const VectorX& phase, MatrixX& force,
                MatrixX& jacobian) const override;
  void ContactBranch(MatrixX& stiffness, VectorX& offset) const override;
  /// Exact projected form (nonlinear_hb.hpp, "Exact integration of projected laws") when every
  /// mesh is a slice core without separation whose stiffness is constant or piecewise constant
  /// (spur: exact steps) and repeats a whole number of times over the base period; else false.
  /// One term per slice: w = [1, −σ_s] on (δ_η, δ_ζ), weight k_s(θ), ramps [v]₊ and, with a
  /// back flank, −[−v − j]₊; L = −K̄2.
  bool ProjectedForm(int period_multiple, NhbProjectedForm* form) const override;

  /// @brief F_η, ε_η and the contact state of every mesh at S samples (phase = θ_s [rad]).
  MeshForceSamples SampleMeshForces(const MatrixX& u, const VectorX& phase) const;

  const std::vector<MeshForceTerm>& terms() const { return terms_; }

 private:
  /// Per term: its deflection δ (from column s of u), full force pair F and Jacobian J at
  /// sample s (from the cached values), and its loaded drive/back slices.
  void TermForce(int t, int s, const MatrixX& u, Vector2* delta, Vector2* force, Matrix2* jacobian,
                 int* drive, int* back) const;
  /// Fills the per-sample core values for `phase` unless cached.
  void UpdateCache(const VectorX& phase) const;

  SystemModel model_;
  std::vector<MeshForceTerm> terms_;
  int n_ = 0;
  VectorX contact_offset_;  ///< ContactBranch offset: θ-mean of g̃ at u = 0

  mutable std::mutex mutex_;
  mutable VectorX cached_phase_;
  // Per term: linear cores K2(θ_s), K2 ε(θ_s), ε(θ_s); slice cores k_s(θ_s), e_s(θ_s) (N × S).
  mutable std::vector<std::vector<Matrix2>> k2_;
  mutable std::vector<std::vector<Vector2>> load_, eps_;
  mutable std::vector<MatrixX> slice_k_, slice_e_;
};

}  // namespace geardyn::internal
