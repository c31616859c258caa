/// @file
/// @brief SystemBuilder: collects bodies, elements, meshes, loads and damping, validates them
/// once and produces the immutable SystemModel (architecture §3.2, §3.7).
///
/// The builder knows no gear physics: element matrices and mesh Jacobians G come from
/// geardyn::models (or the user). Add* methods check what they can at once (sizes, names,
/// body indices, finite values) and throw InvalidInput naming the item; Build() checks the
/// whole (symmetric PSD matrices, positive-definite mass, unreferenced massless DOFs) and
/// derives the structure facts.
///
/// **Damping** (C0): element damping matrices, plus at most one of
/// * Rayleigh: C_R = α M + β K̄, with K̄ the MEAN stiffness K0 + Σ Gᵀ K̄2 G (so that the undamped
///   mean-system modes stay classical modes);
/// * modal: C_ζ = M Φ diag(2 ζ ω_r) Φᵀ M with the mass-normalized modes (Φ, ω_r) of (K̄, M)
///   (dense eigen-decomposition at build time: O(n³), meant for small and medium systems;
///   rigid-body modes undamped; AddSystemDamping, system_damping.hpp);
/// and the mesh damping of each core (B–S Eq. 39), assembled with θ by AssembleDamping.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "geardyn/common/eigen_types.hpp"
#include "geardyn/system/dof_map.hpp"
#include "geardyn/system/mesh_core.hpp"
#include "geardyn/system/system_damping.hpp"
#include "geardyn/system/system_model.hpp"

namespace geardyn {

/// @brief Collects the parts of a system; Build() validates and freezes them.
class SystemBuilder {
 public:
  SystemBuilder() = default;

  /// @brief Adds a rigid body (six DOFs).
  /// @param[in] name unique, non-empty.
  /// @param[in] mass (6×6) mass matrix about the body's reference point in the order
  ///   x, y, z, θx, θy, θz [kg, kg·m, kg·m²], symmetric PSD (PD after the elements' masses are
  ///   added, checked by Build()).
  /// @param[in] position reference point (centre) in the inertial frame [m] (reporting and
  ///   placement only: element and mesh matrices already include their geometry).
  /// @throws InvalidInput naming the body (duplicate or empty name, non-finite or asymmetric
  ///   mass).
  BodyIndex AddBody(const std::string& name, const Matrix6& mass,
                    const Vector3& position = Vector3::Zero());

  /// @brief Sets the planetary role of a body (DofMap::body_role; kOther by default). Data for
  /// the analyses' mode classification only: it changes no matrix.
  /// @throws InvalidInput on an unknown body.
  void SetBodyRole(BodyIndex body, BodyRole role);

  /// @brief Adds a linear element to ground (one body, 6×6) or between two bodies (12×12).
  /// @param[in] stiffness (6×6 or 12×12) [N/m, N, N·m], symmetric PSD (symmetric only for
  ///   ElementKind::kMeshPreload, a geometric stiffness).
  /// @param[in] damping (same size) [N·s/m, …], symmetric PSD, or 0×0 for none.
  /// @param[in] mass (same size) consistent mass [kg, …] (e.g. a shaft element), or 0×0.
  /// @throws InvalidInput naming the element: duplicate/empty name, 0 or >2 bodies, the same
  ///   body twice, unknown body, size mismatch, non-finite or asymmetric matrix.
  ElementIndex AddElement(const std::string& name, ElementKind kind,
                          const std::vector<BodyIndex>& bodies, const MatrixX& stiffness,
                          const MatrixX& damping = MatrixX(), const MatrixX& mass = MatrixX());

  /// @brief Adds a gear mesh between body_i (pinion, G columns 0–5) and body_j (columns 6–11).
  /// @param[in] G (2×12) mesh Jacobian [-, m] (spec 01 §3).
  /// @param[in] core the mesh core (a NonlinearMeshCore reads [q_i; q_j] and then its internal
  ///   coordinates: num_coordinates() = 12 + num_internal_coordinates()).
  /// @param[in] equivalent_mass m_e [kg] of the mesh mode along η for a damping ratio; absent:
  ///   computed at Build() as 1 / (g M_pair⁻¹ gᵀ) with g = row η of G and M_pair the two
  ///   bodies' 6×6 mass blocks.
  /// @param[in] phase_ratio r, phase_offset φ: the mesh's phase θ_k = r θ + φ [rad].
  /// @throws InvalidInput naming the mesh: duplicate/empty name, unknown or equal bodies,
  ///   non-finite G, a null or mis-sized nonlinear core, m_e ≤ 0, non-finite r or φ.
  MeshIndex AddMesh(const std::string& name, BodyIndex body_i, BodyIndex body_j,
                    const Matrix2x12& G, MeshCore core,
                    std::optional<double> equivalent_mass = std::nullopt, double phase_ratio = 1.0,
                    double phase_offset = 0.0);

  /// @brief Adds a constant generalized force [Fx, Fy, Fz, Mx, My, Mz] [N, N·m] on a body's
  /// reference point. Several loads on the same body add up.
  /// @throws InvalidInput on an unknown body or non-finite values.
  void AddTorque(BodyIndex body, const Vector6& generalized_force, const std::string& name = "");

  /// @brief Adds a harmonic generalized force Re(F e^{i m θ}) on a body's reference point, θ the
  /// system phase (SystemHarmonicLoad): F cos(mθ + φ) is amplitude = F e^{iφ}.
  /// @param[in] amplitude F [Fx, Fy, Fz, Mx, My, Mz] [N, N·m], complex, finite.
  /// @param[in] order m ≥ 1: the harmonic of the mesh frequency.
  /// @throws InvalidInput naming the load on an unknown body, a non-finite amplitude or m < 1.
  void AddHarmonicLoad(BodyIndex body, const Vector6c& amplitude, int order,
                       const std::string& name = "");

  /// @brief Rayleigh damping C += α M + β K̄ (see the file comment).
  /// @param[in] alpha α ≥ 0 [1/s]. @param[in] beta β ≥ 0 [s].
  /// @throws InvalidInput on negative or non-finite values, or if modal damping was set.
  void SetRayleighDamping(double alpha, double beta);
  /// @brief Modal damping ratio ζ ∈ [0, 1) on every mode of the mean system (see file comment).
  /// @throws InvalidInput on a value out of range, or if Rayleigh damping was set.
  void SetModalDampingRatio(double zeta);
  /// @brief Rayleigh or modal system damping, including per-mode ratios (system_damping.hpp);
  /// replaces what SetRayleighDamping / SetModalDampingRatio set.
  /// @throws InvalidInput if !damping.IsValid().
  void SetSystemDamping(const SystemDamping& damping);

  /// Number of bodies added so far.
  int num_bodies() const { return static_cast<int>(bodies_.size()); }
  /// The body called `name`, if added.
  std::optional<BodyIndex> FindBody(const std::string& name) const;

  /// @brief Validates everything and builds the model (the builder can be reused).
  /// @throws InvalidInput naming the element/mesh/body and the reason: an element matrix that
  ///   is not PSD, a mass matrix that is not positive definite (naming the first DOF without
  ///   mass, and whether any element or mesh references it), no bodies.
  SystemModel Build() const;

 private:
  struct Body {
    std::string name;
    Matrix6 mass;
    Vector3 position;
    BodyRole role = BodyRole::kOther;
  };
  struct Load {
    std::string name;
    BodyIndex body;
    Vector6 force;
  };
  struct HarmonicLoad {
    std::string name;
    BodyIndex body;
    Vector6c amplitude;
    int order;
  };
  struct Mesh {
    std::string name;
    BodyIndex body_i, body_j;
    Matrix2x12 G;
    MeshCore core;
    std::optional<double> equivalent_mass;
    double phase_ratio, phase_offset;
  };
  struct Element {
    std::string name;
    ElementKind kind;
    std::vector<BodyIndex> bodies;
    MatrixX stiffness, damping, mass;
  };
  void CheckBody(BodyIndex b, const std::string& what) const;

  std::vector<Body> bodies_;
  std::vector<Element> elements_;
  std::vector<Mesh> meshes_;
  std::vector<Load> loads_;
  std::vector<HarmonicLoad> harmonic_loads_;
  SystemDamping damping_;
};

}  // namespace geardyn
