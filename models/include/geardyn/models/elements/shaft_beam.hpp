/// @file
/// @brief The 3-D Timoshenko shaft element: two nodes × six DOF → 12×12 stiffness and
/// consistent mass (axial, torsion and two bending planes with shear deformation and rotary
/// inertia), circular section, axis along any direction.
///
/// **Coordinates.** Node k (a or b) has q_k = [t_k; θ_k] = [x, y, z, θx, θy, θz] in inertial
/// axes [m, rad] (spec 01 §1); the element vector is [q_a; q_b]. Gears sit on nodes.
///
/// **Local frame.** e_3 = (node_b − node_a)/L is the beam axis, s ∈ [0, L] the abscissa, and
/// R = [e_1 e_2 e_3] the rotation of CalcAxisFrame (R e_z = e_3, R = I for a shaft along +Z).
/// Local coordinates are q_loc = Rᵀ q per node, and
/// \f[ K = Λᵀ K_{loc} Λ, \quad M = Λᵀ M_{loc} Λ, \quad Λ = \mathrm{diag}(Rᵀ, Rᵀ, Rᵀ, Rᵀ). \f]
/// The circular section is axisymmetric, so K and M do not depend on how e_1, e_2 are chosen
/// about e_3.
///
/// **Local matrices** (E, G, ρ; A, I, J_p from shaft_section.hpp; κ the shear coefficient):
/// * axial (u_3): K = EA/L [1 −1; −1 1], M = ρAL/6 [2 1; 1 2] (linear shape functions);
/// * torsion (θ_3): K = GJ_p/L [1 −1; −1 1], M = ρJ_pL/6 [2 1; 1 2];
/// * bending, in each plane, deflection w and section rotation ψ (ψ = dw/ds for Euler–
///   Bernoulli): the plane (e_1, e_3) has (w, ψ) = (u_1, θ_2), the plane (e_2, e_3) has
///   (w, ψ) = (u_2, −θ_1) (a rotation θ_1 about e_1 tilts the axis towards −e_2). With the
///   shear-deformation parameter
///   \f[ Φ = \frac{12 EI}{κ G A L^2}, \f]
///   the stiffness of Przemieniecki, Theory of Matrix Structural Analysis (1968) §5.6, in the
///   order (w_a, ψ_a, w_b, ψ_b):
///   \f[ K = \frac{EI}{(1+Φ)L^3}\begin{bmatrix} 12 & 6L & −12 & 6L \\ & (4+Φ)L^2 & −6L &
///   (2−Φ)L^2 \\ & & 12 & −6L \\ \mathrm{sym} & & & (4+Φ)L^2 \end{bmatrix} \f]
///   and the consistent mass M = M_ρA + M_ρI of the same cubic "interdependent interpolation"
///   (the shape functions that solve the static Timoshenko equations exactly; Przemieniecki
///   §11.8, Friedman & Kosmatka, Comput. Struct. 47 (1993) 473–481, Eqs. 20–21), with
///   μ = 1/(1+Φ)²:
///   \f[ M_{ρA} = ρAL μ \begin{bmatrix} \tfrac{13}{35}+\tfrac{7Φ}{10}+\tfrac{Φ^2}{3} &
///   (\tfrac{11}{210}+\tfrac{11Φ}{120}+\tfrac{Φ^2}{24})L & \tfrac{9}{70}+\tfrac{3Φ}{10}+
///   \tfrac{Φ^2}{6} & −(\tfrac{13}{420}+\tfrac{3Φ}{40}+\tfrac{Φ^2}{24})L \\ &
///   (\tfrac{1}{105}+\tfrac{Φ}{60}+\tfrac{Φ^2}{120})L^2 & (\tfrac{13}{420}+\tfrac{3Φ}{40}+
///   \tfrac{Φ^2}{24})L & −(\tfrac{1}{140}+\tfrac{Φ}{60}+\tfrac{Φ^2}{120})L^2 \\ & &
///   m_{11} & −m_{12} \\ \mathrm{sym} & & & m_{22} \end{bmatrix} \f]
///   \f[ M_{ρI} = \frac{ρI μ}{L} \begin{bmatrix} \tfrac65 & (\tfrac1{10}−\tfrac{Φ}{2})L &
///   −\tfrac65 & (\tfrac1{10}−\tfrac{Φ}{2})L \\ & (\tfrac2{15}+\tfrac{Φ}6+\tfrac{Φ^2}3)L^2 &
///   −(\tfrac1{10}−\tfrac{Φ}2)L & −(\tfrac1{30}+\tfrac{Φ}6−\tfrac{Φ^2}6)L^2 \\ & & \tfrac65 &
///   −(\tfrac1{10}−\tfrac{Φ}2)L \\ \mathrm{sym} & & & (\tfrac2{15}+\tfrac{Φ}6+\tfrac{Φ^2}3)L^2
///   \end{bmatrix} \f]
///   The element is free of shear locking (exact static flexibility, e.g. a cantilever's tip
///   deflection PL³/(3EI) + PL/(κGA) with one element) and reduces to the Hermite-cubic
///   Euler–Bernoulli element for Φ = 0 and ρI = 0.
///
/// Rigid motions of the element (6 of them) give zero elastic force, and the consistent mass
/// reproduces the exact rigid-body inertia of the cylinder (mass ρAL, polar ρJ_pL, transverse
/// ρAL³/12 + ρIL about the centre).
///
/// Not included: gyroscopic and centrifugal terms of a spinning shaft, axial-load (geometric)
/// stiffness, and internal damping; they belong to the assembly or to later elements.
#pragma once

#include <optional>

#include "geardyn/common/eigen_types.hpp"
#include "geardyn/models/elements/shaft_section.hpp"

namespace geardyn {

/// @brief A uniform circular shaft segment between two nodes (plain aggregate; validated on
/// use).
struct ShaftBeam {
  Vector3 node_a = Vector3::Zero();  ///< position of node a [m]
  Vector3 node_b = Vector3::Zero();  ///< position of node b [m], node_b ≠ node_a
  CircularSection section;           ///< D_o, D_i [m]
  ShaftMaterial material;            ///< E, G [Pa], ρ [kg/m³]
  /// Formula for κ when shear_coefficient is empty; uses ν = E/(2G) − 1.
  ShearCoefficientFormula shear_formula = ShearCoefficientFormula::kCowper;
  std::optional<double> shear_coefficient;  ///< κ > 0 [-] overriding shear_formula
  bool shear_deformation = true;            ///< false: Φ = 0 (Euler–Bernoulli / Rayleigh beam)
  bool rotary_inertia = true;               ///< false: no ρI bending-rotation inertia (M_ρI = 0)
};

/// @brief Length L = |node_b − node_a| [m].
/// @throws InvalidInput if a node is not finite or L = 0.
double CalcShaftBeamLength(const ShaftBeam& beam);

/// @brief The shear coefficient κ used by the element [-] (the override or the formula).
/// @throws InvalidInput for invalid section, material or override.
double CalcShaftBeamShearCoefficient(const ShaftBeam& beam);

/// @brief Shear-deformation parameter Φ = 12EI/(κGAL²) [-] (0 if !shear_deformation).
/// @throws InvalidInput as CalcShaftBeamStiffness.
double CalcShearDeformationParameter(const ShaftBeam& beam);

/// @brief Rotation R = [e_1 e_2 e_3] (3×3) whose third column is the unit `axis`: the shortest
/// arc from Z to `axis` when axis·Z ≥ 0 (R = I for +Z), otherwise a half-turn about X followed
/// by the shortest arc from −Z (R = diag(1, −1, −1) for −Z). Only e_3 matters to the shaft
/// element; the twist of e_1, e_2 about it is a convention.
/// @param[in] axis unit vector [-].
/// @throws InvalidInput if axis is not a unit vector.
Matrix3 CalcAxisFrame(const Vector3& axis);

/// @brief Stiffness matrix (12×12) of the element in inertial axes.
/// @param[in] beam nodes [m], section [m], material [Pa, kg/m³], κ options.
/// @return K [N/m, N/rad, N·m/rad] on [q_a; q_b], symmetric PSD of rank 6.
/// @throws InvalidInput naming the field if a node is not finite, the nodes coincide, a
///   diameter is invalid (D_o ≤ 0, D_i < 0, D_i ≥ D_o, non-finite), E, G or ρ is not positive
///   and finite, ν = E/(2G) − 1 is outside (−1, 0.5] when κ comes from a formula, or the κ
///   override is not positive and finite.
Matrix12 CalcShaftBeamStiffness(const ShaftBeam& beam);

/// @brief Consistent mass matrix (12×12) of the element in inertial axes.
/// @param[in] beam as CalcShaftBeamStiffness.
/// @return M [kg, kg·m, kg·m²] on [q_a; q_b], symmetric positive definite.
/// @throws InvalidInput as CalcShaftBeamStiffness.
Matrix12 CalcShaftBeamMass(const ShaftBeam& beam);

}  // namespace geardyn
