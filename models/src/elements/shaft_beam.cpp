// The 3-D Timoshenko shaft element (see shaft_beam.hpp for the matrices and their sources).
#include "geardyn/models/elements/shaft_beam.hpp"

#include <Eigen/Geometry>
#include <array>
#include <cmath>

#include "elements/element_checks.hpp"
#include "geardyn/common/check.hpp"
#include "geardyn/common/units.hpp"

namespace geardyn {
namespace {

using Matrix4 = Eigen::Matrix4d;

// Everything the local matrices need, validated once.
struct BeamData {
  double length = 0.0;  // L [m]
  Vector3 axis;         // e_3 [-]
  CircularSectionProperties section;
  double E = 0.0, G = 0.0, rho = 0.0;  // [Pa, Pa, kg/m³]
  double kappa = 0.0;                  // κ [-]
  double phi = 0.0;                    // Φ [-]
};

void CheckMaterial(const ShaftMaterial& material) {
  internal::CheckPositive(material.youngs_modulus, "youngs_modulus", "Pa");
  internal::CheckPositive(material.shear_modulus, "shear_modulus", "Pa");
  internal::CheckPositive(material.density, "density", "kg/m^3");
}

BeamData Prepare(const ShaftBeam& beam) {
  BeamData d;
  d.length = CalcShaftBeamLength(beam);
  d.axis = (beam.node_b - beam.node_a) / d.length;
  d.section = CalcCircularSectionProperties(beam.section);
  CheckMaterial(beam.material);
  d.E = beam.material.youngs_modulus;
  d.G = beam.material.shear_modulus;
  d.rho = beam.material.density;
  d.kappa = CalcShaftBeamShearCoefficient(beam);
  // Φ = 12EI/(κGAL²): the ratio of shear to bending flexibility.
  d.phi = beam.shear_deformation ? 12.0 * d.E * d.section.second_moment /
                                       (d.kappa * d.G * d.section.area * d.length * d.length)
                                 : 0.0;
  return d;
}

// Bending stiffness in one plane, order (w_a, ψ_a, w_b, ψ_b) (Przemieniecki 1968 §5.6).
Matrix4 BendingStiffness(double EI, double L, double phi) {
  const double c = EI / ((1.0 + phi) * L * L * L);
  const double L2 = L * L;
  Matrix4 k;
  k << 12.0, 6.0 * L, -12.0, 6.0 * L,                         //
      6.0 * L, (4.0 + phi) * L2, -6.0 * L, (2.0 - phi) * L2,  //
      -12.0, -6.0 * L, 12.0, -6.0 * L,                        //
      6.0 * L, (2.0 - phi) * L2, -6.0 * L, (4.0 + phi) * L2;
  return c * k;
}

// Consistent bending mass in one plane, order (w_a, ψ_a, w_b, ψ_b), of the interdependent
// cubic interpolation (Przemieniecki 1968 §11.8; Friedman & Kosmatka 1993 Eqs. 20–21).
Matrix4 BendingMass(double rho_a, double rho_i, double L, double phi) {
  const double p = phi, p2 = phi * phi, L2 = L * L;
  const double mu = 1.0 / ((1.0 + p) * (1.0 + p));
  // Translational inertia ρA.
  const double m11 = 13.0 / 35.0 + 7.0 * p / 10.0 + p2 / 3.0;
  const double m12 = (11.0 / 210.0 + 11.0 * p / 120.0 + p2 / 24.0) * L;
  const double m13 = 9.0 / 70.0 + 3.0 * p / 10.0 + p2 / 6.0;
  const double m14 = -(13.0 / 420.0 + 3.0 * p / 40.0 + p2 / 24.0) * L;
  const double m22 = (1.0 / 105.0 + p / 60.0 + p2 / 120.0) * L2;
  const double m24 = -(1.0 / 140.0 + p / 60.0 + p2 / 120.0) * L2;
  Matrix4 mt;
  mt << m11, m12, m13, m14,  //
      m12, m22, -m14, m24,   //
      m13, -m14, m11, -m12,  //
      m14, m24, -m12, m22;
  // Rotary inertia ρI.
  const double r11 = 6.0 / 5.0;
  const double r12 = (1.0 / 10.0 - p / 2.0) * L;
  const double r22 = (2.0 / 15.0 + p / 6.0 + p2 / 3.0) * L2;
  const double r24 = -(1.0 / 30.0 + p / 6.0 - p2 / 6.0) * L2;
  Matrix4 mr;
  mr << r11, r12, -r11, r12,  //
      r12, r22, -r12, r24,    //
      -r11, -r12, r11, -r12,  //
      r12, r24, -r12, r22;
  return (rho_a * L * mu) * mt + (rho_i * mu / L) * mr;
}

// Two-node bar: c [1 −1; −1 1] (stiffness) or c/6 [2 1; 1 2] (mass).
Eigen::Matrix2d BarStiffness(double c) {
  return c * (Eigen::Matrix2d() << 1, -1, -1, 1).finished();
}
Eigen::Matrix2d BarMass(double c) { return c / 6.0 * (Eigen::Matrix2d() << 2, 1, 1, 2).finished(); }

// Local DOF layout per node: [u_1, u_2, u_3, θ_1, θ_2, θ_3]; node b adds 6.
constexpr std::array<int, 4> kPlane13 = {0, 4, 6, 10};  // (w, ψ) = (u_1, θ_2)
constexpr std::array<int, 4> kPlane23 = {1, 3, 7, 9};   // (w, ψ) = (u_2, −θ_1)
constexpr std::array<double, 4> kSign13 = {1.0, 1.0, 1.0, 1.0};
constexpr std::array<double, 4> kSign23 = {1.0, -1.0, 1.0, -1.0};
constexpr std::array<int, 2> kAxial = {2, 8};
constexpr std::array<int, 2> kTorsion = {5, 11};

template <int N>
void Scatter(const Eigen::Matrix<double, N, N>& block, const std::array<int, N>& index,
             const std::array<double, N>& sign, Matrix12* local) {
  for (int i = 0; i < N; ++i) {
    for (int j = 0; j < N; ++j) (*local)(index[i], index[j]) += sign[i] * sign[j] * block(i, j);
  }
}

template <int N>
void Scatter(const Eigen::Matrix<double, N, N>& block, const std::array<int, N>& index,
             Matrix12* local) {
  std::array<double, N> ones;
  ones.fill(1.0);
  Scatter<N>(block, index, ones, local);
}

// K = Λᵀ K_loc Λ with Λ = diag(Rᵀ, Rᵀ, Rᵀ, Rᵀ): each 3×3 block becomes R B Rᵀ.
Matrix12 ToGlobal(const Matrix12& local, const Matrix3& R) {
  Matrix12 global;
  for (int I = 0; I < 4; ++I) {
    for (int J = 0; J < 4; ++J) {
      global.block<3, 3>(3 * I, 3 * J).noalias() =
          R * local.block<3, 3>(3 * I, 3 * J) * R.transpose();
    }
  }
  return 0.5 * (global + global.transpose());  // exact symmetry despite rounding
}

}  // namespace

double CalcShaftBeamLength(const ShaftBeam& beam) {
  internal::CheckFinite(beam.node_a, "node_a", "m");
  internal::CheckFinite(beam.node_b, "node_b", "m");
  const double length = (beam.node_b - beam.node_a).norm();
  GEARDYN_THROW_UNLESS(length > 0.0, "node_b: must differ from node_a (zero-length element), got "
                                         << "node_a = node_b = (" << beam.node_a.x() << ", "
                                         << beam.node_a.y() << ", " << beam.node_a.z() << ") m");
  return length;
}

double CalcShaftBeamShearCoefficient(const ShaftBeam& beam) {
  if (beam.shear_coefficient.has_value()) {
    internal::CheckPositive(*beam.shear_coefficient, "shear_coefficient", "");
    return *beam.shear_coefficient;
  }
  CheckMaterial(beam.material);
  return CalcShearCoefficient(beam.section, beam.material.PoissonRatio(), beam.shear_formula);
}

double CalcShearDeformationParameter(const ShaftBeam& beam) { return Prepare(beam).phi; }

Matrix3 CalcAxisFrame(const Vector3& axis) {
  internal::CheckUnitAxis(axis, "axis");
  const Vector3 a = axis.normalized();
  if (a.z() >= 0.0) {
    return Eigen::Quaterniond::FromTwoVectors(Vector3::UnitZ(), a).toRotationMatrix();
  }
  // Lower hemisphere: a half-turn about X (Z → −Z), then the shortest arc from −Z to a, which
  // stays well conditioned as a → −Z (the arc from +Z would be nearly a half-turn).
  const Matrix3 half_turn = Eigen::AngleAxisd(kPi, Vector3::UnitX()).toRotationMatrix();
  return Eigen::Quaterniond::FromTwoVectors(-Vector3::UnitZ(), a).toRotationMatrix() * half_turn;
}

Matrix12 CalcShaftBeamStiffness(const ShaftBeam& beam) {
  const BeamData d = Prepare(beam);
  const double EI = d.E * d.section.second_moment;
  Matrix12 local = Matrix12::Zero();
  const Matrix4 bending = BendingStiffness(EI, d.length, d.phi);
  Scatter<4>(bending, kPlane13, kSign13, &local);
  Scatter<4>(bending, kPlane23, kSign23, &local);
  Scatter<2>(BarStiffness(d.E * d.section.area / d.length), kAxial, &local);
  Scatter<2>(BarStiffness(d.G * d.section.polar_moment / d.length), kTorsion, &local);
  return ToGlobal(local, CalcAxisFrame(d.axis));
}

Matrix12 CalcShaftBeamMass(const ShaftBeam& beam) {
  const BeamData d = Prepare(beam);
  const double rho_a = d.rho * d.section.area;
  const double rho_i = beam.rotary_inertia ? d.rho * d.section.second_moment : 0.0;
  Matrix12 local = Matrix12::Zero();
  const Matrix4 bending = BendingMass(rho_a, rho_i, d.length, d.phi);
  Scatter<4>(bending, kPlane13, kSign13, &local);
  Scatter<4>(bending, kPlane23, kSign23, &local);
  Scatter<2>(BarMass(rho_a * d.length), kAxial, &local);
  Scatter<2>(BarMass(d.rho * d.section.polar_moment * d.length), kTorsion, &local);
  return ToGlobal(local, CalcAxisFrame(d.axis));
}

}  // namespace geardyn
