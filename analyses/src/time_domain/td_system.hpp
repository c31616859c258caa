/// @file
/// @brief The time-domain system of a SystemModel (internal to the time-domain analyses): mass,
/// constant operators and every mesh core's force, tangent, energy terms and switching
/// functions at one state (time_response.hpp gives the equation).
#pragma once

#include <Eigen/Cholesky>
#include <array>
#include <memory>
#include <string>
#include <vector>

#include "geardyn/common/eigen_types.hpp"
#include "geardyn/system/mesh_core.hpp"
#include "geardyn/system/system_model.hpp"
#include "mass_solver.hpp"

namespace geardyn::internal {

/// @brief How a θ-coefficient varies between its samples.
enum class CoefficientShape { kSmooth, kStepwise, kKinked };

/// @brief How one mesh enters the time-domain equation.
struct TdMeshTerm {
  enum class Kind { kLinear, kSlice, kNonlinear };
  Kind kind = Kind::kLinear;
  int mesh = 0;                ///< index in the model
  std::array<int, 12> dofs{};  ///< system DOF of each pair coordinate (−1: held)
  Matrix2x12 G = Matrix2x12::Zero();
  double phase_ratio = 1.0;                ///< r_k
  double phase_offset = 0.0;               ///< φ_k [rad]
  double damping_coefficient = 0.0;        ///< c_m [N·s/m] (linear cores)
  Matrix2 mean_damping = Matrix2::Zero();  ///< C̄2 (slice cores: θ-mean, all loaded)
  const LinearMeshCore* linear = nullptr;
  const SliceMeshCore* slice = nullptr;
  const NonlinearMeshCore* nonlinear = nullptr;
  int internal_offset = 0;   ///< first internal coordinate in x (nonlinear cores)
  int num_internal = 0;      ///< internal coordinates (nonlinear cores)
  int switching_offset = 0;  ///< first switching function of this mesh
  int num_switching = 0;     ///< switching functions of this mesh
  /// Shape of the stiffness and of the transmission-error (linear) / separation (slice)
  /// coefficient: stepwise ones jump (phase events with an energy jump, held in the phase
  /// power), tables have kinks at their nodes (phase events: steps end there).
  CoefficientShape stiffness_shape = CoefficientShape::kSmooth;
  CoefficientShape offset_shape = CoefficientShape::kSmooth;
  /// Break phases (jumps of stepwise coefficients, nodes of tables): per coefficient, the
  /// phases in [0, period) [rad] and the period [rad].
  std::vector<std::pair<VectorX, double>> breaks;
};

/// @brief Immutable time-domain model (built once, shared by threads).
struct TdSystem {
  explicit TdSystem(const SystemModel& model);

  SystemModel model;    ///< the assembled system (shared data)
  int num_dofs = 0;     ///< N (system DOFs)
  int n = 0;            ///< N + internal coordinates
  MatrixX mass;         ///< (n×n) M + every InternalMass() [kg, kg·m, kg·m²]
  MatrixX stiffness0;   ///< (n×n) K0 [N/m, N, N·m]
  MatrixX damping0;     ///< (n×n) C0 [N·s/m, N·s, N·m·s]
  VectorX load0;        ///< (n) f0 with its unbalanced part removed (M-consistently) [N, N·m]
  MatrixX rigid_modes;  ///< (n × r) rigid-body modes of the mean stiffness (internal rows 0)
  /// (n×n) mean stiffness with stand-in springs for nonlinear meshes (static starting guess)
  MatrixX guess_stiffness;
  double unbalanced_fraction = 0.0;  ///< relative part of f0 along the rigid modes (removed)
  std::vector<TdMeshTerm> terms;     ///< one per mesh
  int num_switching = 0;             ///< total switching functions
  std::shared_ptr<const Eigen::LDLT<MatrixX>> mass_ldlt;  ///< M factorization (dense)
  /// M⁻¹ by blocks (arrow-shaped tooth masses) or dense (mass_solver.hpp): the solve of every
  /// explicit evaluation.
  std::shared_ptr<const MassSolver> mass_solver;
  /// Sparse copies of M, K0, C0 for the products of every evaluation (K0 and C0 act on the
  /// system block only, M is an arrow matrix for tooth bodies): O(nnz) instead of O(n²).
  SparseMatrixRowMajor mass_sparse, stiffness0_sparse, damping0_sparse;
  /// True when a mesh has a NonlinearMeshCore.
  bool has_nonlinear() const;
  /// True when some mesh has a piecewise-constant coefficient.
  bool has_breaks = false;
  /// @brief The first time after t at which a piecewise-constant coefficient of some mesh jumps
  /// (θ = theta0 + omega·t), +∞ when none; *margin receives the half-width [s] of the phase
  /// gap stepped across at the jump (so that each side evaluates its own interval).
  double NextBreakTime(double t, double theta0, double omega, double* margin) const;
};

/// @brief Per-thread scratch and outputs of EvalForces.
struct TdWorkspace {
  explicit TdWorkspace(const TdSystem& sys);

  VectorX force;      ///< (n) f0 + f_h(θ) − K0x − C0v − Σ f_k [N, N·m]
  MatrixX tangent_k;  ///< (n×n) −∂force/∂x (with_jacobians)
  MatrixX tangent_c;  ///< (n×n) −∂force/∂v (with_jacobians)
  /// When set (by an implicit stepper), EvalForces(with_jacobians) fills the sparse lists below
  /// instead of the dense tangent_k / tangent_c (left untouched).
  bool sparse_tangents = false;
  /// −∂force/∂x and −∂force/∂v as triplets on the n coordinates (K0, C0 and every mesh;
  /// duplicates to be summed) when sparse_tangents.
  std::vector<Eigen::Triplet<double>> tangent_k_triplets, tangent_c_triplets;
  double mesh_energy = 0.0;           ///< Σ E_k [J]
  double mesh_dissipation = 0.0;      ///< Σ D_k [W] (mesh dampers and cores)
  double mesh_phase_power = 0.0;      ///< Σ P_k + f_h(θ)ᵀv of the harmonic loads [W]
  VectorX switching;                  ///< (num_switching) signed gaps [m]
  std::vector<char> switching_live;   ///< per switching function: watched at this state
  std::vector<double> force_eta;      ///< per mesh F_η [N] (elastic + damping; 0 nonlinear)
  std::vector<int> contacts;          ///< per mesh: loaded slices / core contacts (−1 linear)
  std::vector<Matrix2> mesh_tangent;  ///< per mesh ∂F/∂δ (linear, slice; with_jacobians)

  std::vector<std::unique_ptr<SliceMeshWorkspace>> slice;  ///< per mesh (null: not a slice)
  std::vector<std::unique_ptr<NonlinearMeshCoreWorkspace>> core_ws;  ///< per mesh (nonlinear)
  std::vector<NonlinearMeshCoreOutput> core_out;                     ///< per mesh (nonlinear)
  std::vector<VectorX> core_x, core_v;                               ///< gather buffers
  std::vector<VectorX> slice_k, slice_e;  ///< per mesh, shifted slice values (phase power)
};

/// @brief Appends scale·a as triplets to *out.
void AppendTriplets(const SparseMatrixRowMajor& a, double scale,
                    std::vector<Eigen::Triplet<double>>* out);

/// @brief Evaluates the total force at (θ, θ̇, x, v) into ws (no allocation after construction).
/// @param[in] theta system phase θ [rad]. @param[in] theta_rate θ̇ = ω_m [rad/s].
/// @param[in] with_jacobians fill tangent_k and tangent_c.
void EvalForces(const TdSystem& sys, TdWorkspace& ws, double theta, double theta_rate,
                const Eigen::Ref<const VectorX>& x, const Eigen::Ref<const VectorX>& v,
                bool with_jacobians);

/// @brief Stored energy S = ½vᵀMv + ½xᵀK0x + ΣE_k [J] (ws.mesh_energy of the last EvalForces
/// at this state).
double StoredEnergy(const TdSystem& sys, const TdWorkspace& ws, const Eigen::Ref<const VectorX>& x,
                    const Eigen::Ref<const VectorX>& v);

/// @brief vᵀC0v + ΣD_k [W] (ws of the last EvalForces at this state).
double DissipationPower(const TdSystem& sys, const TdWorkspace& ws,
                        const Eigen::Ref<const VectorX>& v);

/// @brief Largest undamped natural frequency of the linear system at the state x
/// (K0 + mesh tangents, power iteration on M⁻¹K) [rad/s].
double EstimateHighestFrequency(const TdSystem& sys, TdWorkspace& ws, double theta,
                                const VectorX& x);

/// @brief Static equilibrium at θ₀ (time_response.hpp SolveTimeDomainStatic): x, iterations,
/// success flag and message.
/// Solves [A, MV; VᵀM, 0][dx; λ] = [b; 0] (the rigid modes V bordered out) with a symmetric
/// diagonal scaling (m and rad, N/m and kg mix: unit diagonal on the coordinates, unit-norm border
/// columns) so that the rank decision of the full-pivoting LU is scale-free. False when singular
/// or not finite.
bool SolveBordered(const MatrixX& A, const MatrixX& mv, const VectorX& b, VectorX* dx);

/// The stiffness of the static start: sys.guess_stiffness (every slice loaded, the stand-in
/// springs of the nonlinear cores) with the cores' internal tangents of ws.tangent_k (their
/// internal springs; EvalForces with Jacobians at rest must have filled ws).
MatrixX RestStiffness(const TdSystem& sys, const TdWorkspace& ws);

struct TdStatic {
  VectorX x;
  int iterations = 0;
  bool ok = false;
  std::string message;
};
/// @param[in] start starting point (e.g. the previous θ sample's solution); null: the bordered
///   linear guess.
TdStatic SolveStatic(const TdSystem& sys, TdWorkspace& ws, double theta0,
                     const VectorX* start = nullptr);

}  // namespace geardyn::internal
