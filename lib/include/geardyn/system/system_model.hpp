/// @file
/// @brief SystemModel: the assembled, validated, immutable linear-structure-plus-meshes model
/// that every analysis reads (architecture §3.2, §3.4; spec 01 §1, §3; spec 02).
///
/// **Equation.** With q the (num_dofs) coordinates [m, rad] of the kept DOFs (see DofMap),
/// \f[ M\ddot q + \Big(C_0 + \sum_k P_k^T G_k^T C2_k(θ_k) G_k P_k\Big)\dot q
///     + \Big(K_0 + \sum_k P_k^T G_k^T K2_k(θ_k) G_k P_k\Big) q
///     = f_0 + \sum_l \mathrm{Re}\big(F_l e^{i m_l θ}\big) + \sum_k P_k^T G_k^T K2_k(θ_k)\,ε_k(θ_k)
///     \f]
/// for the linear mesh cores (spec 01 §3; B–S Eq. 39, 41), where P_k picks the 12 coordinates
/// [q_i; q_j] of mesh k's two bodies and θ_k = r_k θ + φ_k is mesh k's phase (ratio r_k and
/// offset φ_k, SystemMesh). Slice and nonlinear cores replace the mesh term by their force
/// (geardyn/system/mesh_core.hpp); the assembly kernels of workspace.hpp use the slice cores'
/// all-loaded small-motion stiffness.
///
/// **Model parts** (units: K [N/m, N, N·m/rad], C [N·s/m, …], M [kg, kg·m, kg·m²]):
/// M (sparse, symmetric positive definite), K0 (bearings, shafts, couplings, springs), C0 (their
/// dampers + Rayleigh/modal damping), the meshes (DOF indices, fixed 2×12 G, core, resolved
/// mesh damping coefficient c_m), the constant loads f0, the harmonic loads Re(F_l e^{i m_l θ})
/// (SystemHarmonicLoad: an external force at an integer mesh order m_l ≥ 1 of the system phase θ),
/// and the element list with their DOF
/// indices and matrices (for strain-energy fractions and bearing forces).
///
/// **Structure facts** (decided once, at build time): time_dependence() (the Combine of every
/// mesh core's Classify, or kNonlinear), period_meshes() (lcm of the cores' P), blocks() (the
/// connected components of the coupling graph of M, K0, C0 and every mesh's Gᵀ·pattern(K2)·G,
/// e.g. a spur pair without anything axial splits into a torsional/transverse block and
/// axial/rocking blocks), is_symmetric() and storage_hint() (dense below kDenseDofThreshold).
///
/// **Copying** is O(1): the data is shared, immutable, and safe to read from many threads.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "geardyn/common/eigen_types.hpp"
#include "geardyn/system/coefficient.hpp"
#include "geardyn/system/dof_map.hpp"
#include "geardyn/system/mesh_core.hpp"

namespace geardyn {

/// Systems with fewer DOFs than this get StorageKind::kDense as their storage hint.
inline constexpr int kDenseDofThreshold = 200;

/// @brief Dense or sparse matrices for the analyses' operators (architecture §3.4).
enum class StorageKind { kDense, kSparse };
/// "dense" / "sparse".
const char* ToString(StorageKind kind);

/// @brief What a structural element is (for reporting and strain-energy classification only:
/// all kinds assemble the same way). kMeshPreload is the tangent (geometric) stiffness of a
/// preloaded mesh (mesh_preload_stiffness.hpp): symmetric but indefinite in general (negative
/// semi-definite for an external mesh), the only kind whose stiffness need not be PSD.
enum class ElementKind { kBearing, kShaft, kCoupling, kSpring, kMeshPreload };
/// "bearing", "shaft", "coupling", "spring", "mesh preload".
const char* ToString(ElementKind kind);

/// @brief A linear element between one body and ground or between two bodies.
///
/// Its coordinates are the six of each body in order (6 or 12 of them); `dofs[e]` is the system
/// DOF of element coordinate e, or −1 when that coordinate is held fixed in this (restricted)
/// system. Its contribution to K0 is Σ over kept (e, f) of stiffness(e, f).
struct SystemElement {
  std::string name;  ///< unique among elements
  ElementKind kind = ElementKind::kSpring;
  std::vector<BodyIndex> bodies;  ///< 1 (grounded) or 2
  std::vector<int> dofs;          ///< (6 or 12) system DOF per element coordinate, −1 if fixed
  MatrixX stiffness;  ///< (6×6 or 12×12) [N/m, N, N·m], symmetric PSD (kMeshPreload: symmetric)
  MatrixX damping;    ///< (same) [N·s/m, N·s, N·m·s], symmetric PSD
  MatrixX mass;       ///< (same) consistent mass [kg, kg·m, kg·m²], or 0×0 for none

  /// True when the element connects a body to ground.
  bool is_grounded() const { return bodies.size() == 1; }
};

/// @brief One gear mesh of the system (spec 01 §3).
struct SystemMesh {
  std::string name;            ///< unique among meshes
  BodyIndex body_i;            ///< pinion (the G columns 0–5)
  BodyIndex body_j;            ///< gear (the G columns 6–11)
  std::array<int, 12> dofs{};  ///< system DOF of [q_i; q_j] coordinate k, −1 when held fixed
  Matrix2x12 G = Matrix2x12::Zero();  ///< [δ_η, δ_ζ]ᵀ = G [q_i; q_j] [-, m] (spec 01 §3)
  MeshCore core;                      ///< θ-coefficients / slices / nonlinear hatch
  double equivalent_mass = 0.0;       ///< m_e [kg] of the mesh mode along η (damping ratios)
  double damping_coefficient = 0.0;   ///< c_m [N·s/m], resolved once (ResolveDampingCoefficient)
  /// K̄2: θ-mean of the core's 2×2 stiffness [N/m, N, N·m] (linear: exact channel means in the
  /// level's shape; slice: all-loaded mean channels; nonlinear: zero).
  Matrix2 mean_core_stiffness = Matrix2::Zero();
  double phase_ratio = 1.0;   ///< r: θ_mesh = r θ + offset [-]
  double phase_offset = 0.0;  ///< φ [rad]

  /// The mesh's own phase θ_k = r θ + φ [rad] at the system phase θ [rad].
  double MeshPhase(double theta) const { return phase_ratio * theta + phase_offset; }
};

/// @brief A constant generalized force on one body (torques and forces at its centre).
struct SystemLoad {
  std::string name;
  BodyIndex body;
  Vector6 force = Vector6::Zero();    ///< [Fx, Fy, Fz, Mx, My, Mz] [N, N·m]
  std::array<int, kBodyDofs> dofs{};  ///< system DOF of each component, −1 when held fixed
};

/// @brief A harmonic generalized force on one body: f(θ) = Re(F e^{i m θ}) with θ the system
/// phase (θ = ω_m t, the first mesh's phase) and m ≥ 1 an integer mesh order, so that it never
/// changes the period facts. F cos(mθ + φ) is amplitude = F e^{iφ}. In the Fourier convention
/// f(θ) = Σ_m f_m e^{imθ}, f_{−m} = conj(f_m) of system_harmonics.hpp it contributes F/2 at +m.
struct SystemHarmonicLoad {
  std::string name;
  BodyIndex body;
  Vector6c amplitude = Vector6c::Zero();  ///< F: [Fx, Fy, Fz, Mx, My, Mz] [N, N·m], complex
  int order = 1;                          ///< m ≥ 1 [-]: harmonic of the mesh frequency
  std::array<int, kBodyDofs> dofs{};      ///< system DOF of each component, −1 when held fixed
};

struct SystemDamping;

/// @brief The assembled system; build it with SystemBuilder (system_builder.hpp).
class SystemModel {
 public:
  /// Internal shared data (defined in the .cpp).
  struct Data;

  /// An empty model (0 DOF); use SystemBuilder::Build().
  SystemModel();
  /// Used by SystemBuilder; not for users.
  explicit SystemModel(std::shared_ptr<const Data> data);

  // ---------------------------------------------------------------- sizes and maps
  /// Number of DOFs n.
  int num_dofs() const;
  /// Number of bodies.
  int num_bodies() const;
  /// The DOF map (bodies, kinds, names).
  const DofMap& dof_map() const;
  /// Identity shared by copies; workspaces check it (IsCompatibleWith).
  std::uint64_t id() const;

  // ---------------------------------------------------------------- matrices
  /// M (n×n) [kg, kg·m, kg·m²], symmetric positive definite.
  const SparseMatrix& mass() const;
  /// K0 (n×n): supports, shafts, couplings, springs [N/m, N, N·m].
  const SparseMatrix& constant_stiffness() const;
  /// C0 (n×n): element dampers + Rayleigh/modal damping [N·s/m, N·s, N·m·s].
  const SparseMatrix& constant_damping() const;
  /// f0 (n): the constant external loads [N, N·m].
  const VectorX& constant_load() const;
  /// Dense copies for small systems (allocate; O(n²) memory).
  MatrixX DenseMass() const;
  /// Dense K0.
  MatrixX DenseConstantStiffness() const;
  /// Dense C0.
  MatrixX DenseConstantDamping() const;

  // ---------------------------------------------------------------- parts
  /// The meshes.
  const std::vector<SystemMesh>& meshes() const;
  /// Number of meshes.
  int num_meshes() const;
  /// The structural elements.
  const std::vector<SystemElement>& elements() const;
  /// The external loads.
  const std::vector<SystemLoad>& loads() const;
  /// The harmonic external loads Re(F e^{imθ}) (SystemHarmonicLoad); part of f(θ) wherever the
  /// analyses read the load (AssembleLoad, the load harmonics, the time-domain force).
  const std::vector<SystemHarmonicLoad>& harmonic_loads() const;
  /// Rayleigh coefficients (α [1/s], β [s]) applied to C0 (zero when unused).
  double rayleigh_alpha() const;
  /// See rayleigh_alpha().
  double rayleigh_beta() const;
  /// Modal damping ratio ζ [-] built into C0 (0 when unused).
  double modal_damping_ratio() const;

  // ---------------------------------------------------------------- structure facts
  /// Combine of every mesh core's Classify (kConstant without meshes); kNonlinear when a slice or
  /// nonlinear core is present.
  TimeDependence time_dependence() const;
  /// P: the lcm of the cores' period_meshes() (the system is periodic in θ with period 2π·P when
  /// every phase_ratio is 1).
  std::int64_t period_meshes() const;
  /// The decoupled DOF groups: each a strictly increasing list of DOF indices; together a
  /// partition of [0, n), ordered by their smallest DOF.
  const std::vector<std::vector<int>>& blocks() const;
  /// Number of blocks.
  int num_blocks() const;
  /// True when M, K(θ), C(θ) are symmetric (always, until gyroscopic terms arrive).
  bool is_symmetric() const;
  /// kDense when num_dofs() < kDenseDofThreshold, else kSparse.
  StorageKind storage_hint() const;

  // ---------------------------------------------------------------- restriction
  /// @brief The sub-system on the DOFs of block b (exact: blocks do not couple).
  /// @throws InvalidInput if b is out of range.
  SystemModel RestrictToBlock(int b) const;
  /// @brief The sub-system on a DOF subset, the other DOFs held fixed (q = 0 there): M, K0, C0
  /// and f0 restricted; elements, meshes, loads and harmonic loads keep their entries on the kept
  /// DOFs (the others become −1); meshes and loads that touch no kept DOF are dropped. Damping
  /// specs are not re-derived (C0 is restricted as assembled). Facts are recomputed.
  /// @param[in] dofs strictly increasing indices into this model.
  /// @throws InvalidInput on an out-of-range or non-increasing index.
  SystemModel Restrict(const std::vector<int>& dofs) const;
  /// @brief The planar sub-system: x, y and θz of every body (planar literature models).
  SystemModel RestrictToPlanar() const;
  /// @brief A copy whose mesh k has the phase ratio ratios[k] (everything else the same, a new
  /// id): the rational approximants of an incommensurate train (Floquet, issue 18).
  /// @throws InvalidInput unless ratios has one finite entry > 0 per mesh.
  SystemModel WithPhaseRatios(const std::vector<double>& ratios) const;
  /// @brief A copy with K0 += ΔK (everything else the same, facts recomputed, a new id): a
  /// stiffness no element owns (the modal strain fractions show it as "other"), e.g. the scene
  /// builder's projection of the mesh preload off the rigid-body modes.
  /// @param[in] added ΔK (n × n) [N/m, N, N·m], symmetric, finite.
  /// @throws InvalidInput on a size mismatch, a non-finite or an asymmetric ΔK.
  SystemModel WithAddedStiffness(const SparseMatrix& added) const;

 private:
  // Adds Rayleigh/modal damping to C0 (system_damping.hpp).
  friend SystemModel AddSystemDamping(const SystemModel& model, const SystemDamping& damping);

  std::shared_ptr<const Data> data_;
};

/// @brief P_K [-]: the lcm of the cores' OperatorPeriodMeshes — the period of K(θ) and C(θ) in
/// mesh cycles, which the homogeneous (Floquet) problem and the harmonic coupling of the linear
/// HB use. It divides period_meshes(), which also counts the hunting period of ε (issue 12).
std::int64_t OperatorPeriodMeshes(const SystemModel& model);

/// @brief Adds the harmonic loads Σ Re(F_l e^{i m_l θ}) at the system phase θ [rad] to `load`
/// (num_dofs) [N, N·m] on their kept DOFs. No allocation.
void AccumulateHarmonicLoads(const SystemModel& model, double theta, Eigen::Ref<VectorX> load);

}  // namespace geardyn
