// Tests of the 3-D Timoshenko shaft element (shaft_beam.hpp) against independent truths:
// the shape functions integrated by quadrature, the exact static flexibility of a cantilever,
// the closed-form frequencies of uniform shafts (Euler–Bernoulli bending, axial and torsional
// rods, the Timoshenko frequency equation of a simply supported beam) reached with the
// observed order of convergence, rigid-body invariants and rotation invariance.
#include "geardyn/models/elements/shaft_beam.hpp"

#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "geardyn/common/errors.hpp"
#include "geardyn/common/units.hpp"
#include "support/expect_throws.hpp"
#include "support/matrix_compare.hpp"

namespace geardyn {
namespace {

using Matrix4 = Eigen::Matrix4d;

constexpr double kEps = std::numeric_limits<double>::epsilon();
// Element matrices are sums of a few products of O(1) coefficients: a few roundings each,
// then rotated by R (3 more products), relative to the largest entry.
constexpr double kAlgebraTol = 1e3 * kEps;

// Steel (E = 210 GPa, ν = 0.3, ρ = 7850 kg/m³).
constexpr double kE = 2.1e11;
constexpr double kNu = 0.3;
constexpr double kRho = 7850.0;

ShaftBeam MakeBeam(const Vector3& a, const Vector3& b, double d_o, double d_i = 0.0) {
  ShaftBeam beam;
  beam.node_a = a;
  beam.node_b = b;
  beam.section = {.outer_diameter = d_o, .inner_diameter = d_i};
  beam.material = ShaftMaterial::FromPoissonRatio(kE, kNu, kRho);
  return beam;
}

// An arbitrary unit axis and an arbitrary start point (no symmetry to hide sign errors).
const Vector3 kOddAxis = Vector3(0.3, -0.7, 0.55).normalized();
const Vector3 kOddStart(0.21, -0.13, 0.37);

// ---------------------------------------------------------------------------------------------
// A small assembly loop (6 DOF per node, nodes 0..n along `axis`).
struct Assembly {
  MatrixX K;
  MatrixX M;
};

Assembly AssembleShaft(const ShaftBeam& prototype, const Vector3& start, const Vector3& axis,
                       double length, int elements) {
  const int dofs = 6 * (elements + 1);
  Assembly a{MatrixX::Zero(dofs, dofs), MatrixX::Zero(dofs, dofs)};
  for (int e = 0; e < elements; ++e) {
    ShaftBeam beam = prototype;
    beam.node_a = start + axis * (length * e / elements);
    beam.node_b = start + axis * (length * (e + 1) / elements);
    a.K.block<12, 12>(6 * e, 6 * e) += CalcShaftBeamStiffness(beam);
    a.M.block<12, 12>(6 * e, 6 * e) += CalcShaftBeamMass(beam);
  }
  return a;
}

// DOFs kept: components `components` (0..5) of every node, minus the (node, component) pairs
// in `fixed` (boundary conditions by elimination). Node −1 means the last node.
std::vector<int> SelectDofs(int elements, const std::vector<int>& components,
                            const std::vector<std::pair<int, int>>& fixed) {
  std::vector<int> dofs;
  for (int node = 0; node <= elements; ++node) {
    for (int c : components) {
      const bool is_fixed = std::any_of(fixed.begin(), fixed.end(), [&](const auto& f) {
        const int fixed_node = f.first < 0 ? elements : f.first;
        return fixed_node == node && f.second == c;
      });
      if (!is_fixed) dofs.push_back(6 * node + c);
    }
  }
  return dofs;
}

// Natural frequencies ω [rad/s] of the sub-problem on `dofs`, ascending (K φ = ω² M φ).
VectorX Frequencies(const Assembly& a, const std::vector<int>& dofs) {
  const int n = static_cast<int>(dofs.size());
  MatrixX K(n, n), M(n, n);
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      K(i, j) = a.K(dofs[i], dofs[j]);
      M(i, j) = a.M(dofs[i], dofs[j]);
    }
  }
  const Eigen::GeneralizedSelfAdjointEigenSolver<MatrixX> eig(K, M, Eigen::EigenvaluesOnly);
  EXPECT_EQ(eig.info(), Eigen::Success);
  return eig.eigenvalues().cwiseMax(0.0).cwiseSqrt();
}

// Root of cos x · cosh x = s (s = +1 free–free, −1 clamped–free) in [lo, hi], by bisection on
// the bounded form cos x − s / cosh x (one sign change in the bracket).
double BeamRoot(double s, double lo, double hi) {
  auto f = [s](double x) { return std::cos(x) - s / std::cosh(x); };
  double f_lo = f(lo);
  EXPECT_LT(f_lo * f(hi), 0.0) << "bracket [" << lo << ", " << hi << "]";
  for (int it = 0; it < 200 && hi - lo > 4 * kEps * hi; ++it) {
    const double mid = 0.5 * (lo + hi);
    const double f_mid = f(mid);
    if ((f_mid < 0.0) == (f_lo < 0.0)) {
      lo = mid;
      f_lo = f_mid;
    } else {
      hi = mid;
    }
  }
  return 0.5 * (lo + hi);
}

// Relative error of the first `modes` FE frequencies (after `skip` rigid modes) for each mesh,
// and the observed orders log2(e_N / e_2N) of the worst mode.
struct Convergence {
  std::vector<int> meshes;
  std::vector<double> errors;  // max over the modes, per mesh
  std::vector<double> orders;  // between consecutive meshes (meshes double)
};

Convergence StudyConvergence(const std::vector<int>& meshes,
                             const std::function<VectorX(int)>& fe_frequencies,
                             const std::vector<double>& exact, int skip, const char* label) {
  Convergence c;
  c.meshes = meshes;
  for (int n : meshes) {
    const VectorX w = fe_frequencies(n);
    double worst = 0.0;
    for (size_t k = 0; k < exact.size(); ++k) {
      worst = std::max(worst, std::abs(w(skip + static_cast<int>(k)) - exact[k]) / exact[k]);
    }
    c.errors.push_back(worst);
  }
  for (size_t i = 0; i + 1 < c.errors.size(); ++i) {
    c.orders.push_back(std::log2(c.errors[i] / c.errors[i + 1]));
  }
  std::printf("[ %-40s ] N:", label);
  for (int n : meshes) std::printf(" %9d", n);
  std::printf("\n[ %-40s ] err:", "");
  for (double e : c.errors) std::printf(" %9.2e", e);
  std::printf("\n[ %-40s ] order:          ", "");
  for (double p : c.orders) std::printf(" %9.3f", p);
  std::printf("\n");
  return c;
}

// ---------------------------------------------------------------------------------------------
// Independent truth for the local matrices: the interdependent cubic interpolation of a
// Timoshenko beam (shape functions that solve EIψ'' + κGA(w' − ψ) = 0, κGA(w' − ψ)' = 0 exactly;
// Reddy, "On locking-free shear deformable beam finite elements", CMAME 149 (1997) Eq. 23),
// with ξ = s/L and μ = 1/(1+Φ), integrated with 5-point Gauss–Legendre quadrature (exact for
// the degree-6 integrands).
struct ShapeFunctions {
  Eigen::RowVector4d w, psi, dw, dpsi;  // w, ψ and d/ds at ξ, order (w_a, ψ_a, w_b, ψ_b)
};

ShapeFunctions EvalShape(double xi, double L, double phi) {
  const double mu = 1.0 / (1.0 + phi);
  const double x2 = xi * xi, x3 = x2 * xi;
  ShapeFunctions N;
  N.w << mu * (2 * x3 - 3 * x2 - phi * xi + 1 + phi),
      mu * L * (x3 - (2 + phi / 2) * x2 + (1 + phi / 2) * xi), -mu * (2 * x3 - 3 * x2 - phi * xi),
      mu * L * (x3 - (1 - phi / 2) * x2 - phi / 2 * xi);
  N.psi << 6 * mu / L * (x2 - xi), mu * (3 * x2 - (4 + phi) * xi + 1 + phi),
      -6 * mu / L * (x2 - xi), mu * (3 * x2 - (2 - phi) * xi);
  N.dw << mu * (6 * x2 - 6 * xi - phi) / L, mu * (3 * x2 - (4 + phi) * xi + 1 + phi / 2),
      -mu * (6 * x2 - 6 * xi - phi) / L, mu * (3 * x2 - (2 - phi) * xi - phi / 2);
  N.dpsi << 6 * mu / (L * L) * (2 * xi - 1), mu * (6 * xi - 4 - phi) / L,
      -6 * mu / (L * L) * (2 * xi - 1), mu * (6 * xi - 2 + phi) / L;
  return N;
}

void QuadratureMatrices(double L, double EI, double kGA, double rhoA, double rhoI, double phi,
                        Matrix4* K, Matrix4* M) {
  const std::array<double, 5> x = {-0.9061798459386640, -0.5384693101056831, 0.0,
                                   0.5384693101056831, 0.9061798459386640};
  const std::array<double, 5> wt = {0.2369268850561891, 0.4786286704993665, 0.5688888888888889,
                                    0.4786286704993665, 0.2369268850561891};
  K->setZero();
  M->setZero();
  for (int q = 0; q < 5; ++q) {
    const double xi = 0.5 * (x[q] + 1.0);
    const double ds = 0.5 * wt[q] * L;
    const ShapeFunctions N = EvalShape(xi, L, phi);
    const Eigen::RowVector4d gamma = N.dw - N.psi;  // shear strain w' − ψ
    *K += ds * (EI * N.dpsi.transpose() * N.dpsi + kGA * gamma.transpose() * gamma);
    *M += ds * (rhoA * N.w.transpose() * N.w + rhoI * N.psi.transpose() * N.psi);
  }
}

Matrix4 Extract(const Matrix12& m, const std::array<int, 4>& idx, const std::array<double, 4>& s) {
  Matrix4 out;
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j) out(i, j) = s[i] * s[j] * m(idx[i], idx[j]);
  }
  return out;
}

// Rigid motion of the element's two nodes: translation t and small rotation θ about point p.
Vector12 RigidMotion(const ShaftBeam& beam, const Vector3& t, const Vector3& theta,
                     const Vector3& p) {
  Vector12 q;
  q << t + theta.cross(beam.node_a - p), theta, t + theta.cross(beam.node_b - p), theta;
  return q;
}

// Exact inertia tensor about the centroid of the cylinder the element represents.
Matrix3 CylinderInertia(const ShaftBeam& beam, bool rotary) {
  const CircularSectionProperties s = CalcCircularSectionProperties(beam.section);
  const double L = CalcShaftBeamLength(beam);
  const Vector3 a = (beam.node_b - beam.node_a) / L;
  const double rho = beam.material.density;
  const double transverse =
      rho * s.area * L * L * L / 12.0 + (rotary ? rho * s.second_moment * L : 0.0);
  return rho * s.polar_moment * L * a * a.transpose() +
         transverse * (Matrix3::Identity() - a * a.transpose());
}

// =============================================================================================
TEST(ShaftBeamTest, LocalMatricesEqualQuadratureOfInterdependentShapeFunctions) {
  // Slender (Φ ≈ 0.03), stubby (Φ ≈ 0.5) and shear-dominated (Φ ≈ 40, as in fine meshes) elements.
  for (double d_o : {0.02, 0.08, 0.7}) {
    const ShaftBeam beam = MakeBeam(Vector3::Zero(), Vector3(0, 0, 0.1), d_o, 0.3 * d_o);
    const CircularSectionProperties s = CalcCircularSectionProperties(beam.section);
    const double kappa = CalcShaftBeamShearCoefficient(beam);
    const double phi = CalcShearDeformationParameter(beam);
    std::printf("[ %-40s ] Φ = %.4g\n", "quadrature check", phi);
    Matrix4 K_ref, M_ref;
    QuadratureMatrices(0.1, kE * s.second_moment, kappa * beam.material.shear_modulus * s.area,
                       kRho * s.area, kRho * s.second_moment, phi, &K_ref, &M_ref);
    const Matrix12 K = CalcShaftBeamStiffness(beam);
    const Matrix12 M = CalcShaftBeamMass(beam);
    // Plane x–z: (w, ψ) = (u_x, θy); plane y–z: (w, ψ) = (u_y, −θx).
    EXPECT_MATRIX_NEAR(Extract(K, {0, 4, 6, 10}, {1, 1, 1, 1}), K_ref, kAlgebraTol);
    EXPECT_MATRIX_NEAR(Extract(K, {1, 3, 7, 9}, {1, -1, 1, -1}), K_ref, kAlgebraTol);
    EXPECT_MATRIX_NEAR(Extract(M, {0, 4, 6, 10}, {1, 1, 1, 1}), M_ref, kAlgebraTol);
    EXPECT_MATRIX_NEAR(Extract(M, {1, 3, 7, 9}, {1, -1, 1, -1}), M_ref, kAlgebraTol);
  }
}

TEST(ShaftBeamTest, EulerBernoulliLimitIsTheClassicHermiteElement) {
  ShaftBeam beam = MakeBeam(Vector3::Zero(), Vector3(0, 0, 0.25), 0.04);
  beam.shear_deformation = false;
  beam.rotary_inertia = false;
  const double L = 0.25;
  const CircularSectionProperties s = CalcCircularSectionProperties(beam.section);
  Matrix4 k, m;  // e.g. Przemieniecki (1968) Eqs. 5.116 and 11.28
  k << 12, 6 * L, -12, 6 * L, 6 * L, 4 * L * L, -6 * L, 2 * L * L, -12, -6 * L, 12, -6 * L, 6 * L,
      2 * L * L, -6 * L, 4 * L * L;
  m << 156, 22 * L, 54, -13 * L, 22 * L, 4 * L * L, 13 * L, -3 * L * L, 54, 13 * L, 156, -22 * L,
      -13 * L, -3 * L * L, -22 * L, 4 * L * L;
  EXPECT_DOUBLE_EQ(CalcShearDeformationParameter(beam), 0.0);
  EXPECT_MATRIX_NEAR(Extract(CalcShaftBeamStiffness(beam), {0, 4, 6, 10}, {1, 1, 1, 1}),
                     (kE * s.second_moment / (L * L * L) * k).eval(), kAlgebraTol);
  EXPECT_MATRIX_NEAR(Extract(CalcShaftBeamMass(beam), {0, 4, 6, 10}, {1, 1, 1, 1}),
                     (kRho * s.area * L / 420.0 * m).eval(), kAlgebraTol);
}

TEST(ShaftBeamTest, CantileverStaticFlexibilityIsExactWithOneElement) {
  // Clamp node a, load node b: Timoshenko tip deflection PL³/(3EI) + PL/(κGA), tip rotation
  // PL²/(2EI); axial PL/(EA); twist TL/(GJ_p). Checked along Z and along an odd axis, where the
  // loads are applied along the local directions R e_i.
  for (const Vector3& axis : {Vector3(Vector3::UnitZ()), kOddAxis}) {
    const double L = 0.3;
    const ShaftBeam beam = MakeBeam(kOddStart, kOddStart + L * axis, 0.06, 0.02);
    const CircularSectionProperties s = CalcCircularSectionProperties(beam.section);
    const double EI = kE * s.second_moment;
    const double kGA = CalcShaftBeamShearCoefficient(beam) * beam.material.shear_modulus * s.area;
    const Matrix6 K_bb = CalcShaftBeamStiffness(beam).bottomRightCorner<6, 6>();
    const Matrix3 R = CalcAxisFrame(axis);
    const Vector3 e1 = R.col(0), e2 = R.col(1), e3 = R.col(2);
    const double P = 1e4;  // [N] or [N·m]
    const Eigen::LDLT<Matrix6> solver(K_bb);
    Vector6 f;
    // Shear force along e1: deflection along e1, rotation about e2 (ψ = θ·e2).
    f << P * e1, Vector3::Zero();
    Vector6 q = solver.solve(f);
    const double tip = P * L * L * L / (3 * EI) + P * L / kGA;
    EXPECT_NEAR(q.head<3>().dot(e1), tip, 1e-10 * tip);
    EXPECT_NEAR(q.tail<3>().dot(e2), P * L * L / (2 * EI), 1e-10 * P * L * L / (2 * EI));
    // Shear force along e2: rotation about −e1.
    f << P * e2, Vector3::Zero();
    q = solver.solve(f);
    EXPECT_NEAR(q.head<3>().dot(e2), tip, 1e-10 * tip);
    EXPECT_NEAR(q.tail<3>().dot(e1), -P * L * L / (2 * EI), 1e-10 * P * L * L / (2 * EI));
    // Axial force and torque.
    f << P * e3, Vector3::Zero();
    q = solver.solve(f);
    EXPECT_NEAR(q.head<3>().dot(e3), P * L / (kE * s.area), 1e-10 * P * L / (kE * s.area));
    f << Vector3::Zero(), P * e3;
    q = solver.solve(f);
    const double twist = P * L / (beam.material.shear_modulus * s.polar_moment);
    EXPECT_NEAR(q.tail<3>().dot(e3), twist, 1e-10 * twist);
    EXPECT_LT(q.head<3>().norm(), 1e-10 * twist * L);  // torsion does not bend the shaft
  }
}

TEST(ShaftBeamTest, StiffnessIsSymmetricPsdWithExactlySixRigidBodyModes) {
  for (const Vector3& axis : {Vector3(Vector3::UnitZ()), kOddAxis}) {
    for (double d_i : {0.0, 0.03}) {
      const ShaftBeam beam = MakeBeam(kOddStart, kOddStart + 0.12 * axis, 0.05, d_i);
      const Matrix12 K = CalcShaftBeamStiffness(beam);
      EXPECT_TRUE(K.isApprox(K.transpose(), 0.0));
      const Eigen::SelfAdjointEigenSolver<Matrix12> eig(K, Eigen::EigenvaluesOnly);
      const double largest = eig.eigenvalues().maxCoeff();
      EXPECT_GT(eig.eigenvalues().minCoeff(), -1e-12 * largest);
      const int zero = static_cast<int>((eig.eigenvalues().array() < 1e-10 * largest).count());
      EXPECT_EQ(zero, 6) << "eigenvalues " << eig.eigenvalues().transpose();
      // Every rigid motion (translation t, rotation θ about an arbitrary point p) is free.
      const Vector3 p(-0.4, 0.9, 0.25);
      for (int k = 0; k < 6; ++k) {
        const Vector3 t = k < 3 ? Vector3(Vector3::Unit(k)) : Vector3(Vector3::Zero());
        const Vector3 theta = k < 3 ? Vector3(Vector3::Zero()) : Vector3(Vector3::Unit(k - 3));
        const Vector12 q = RigidMotion(beam, t, theta, p);
        EXPECT_LT((K * q).norm(), 1e-13 * K.norm() * q.norm()) << "rigid motion " << k;
      }
      const Vector12 q = RigidMotion(beam, Vector3(0.3, -0.2, 0.5), Vector3(0.7, 0.1, -0.4), p);
      EXPECT_LT((K * q).norm(), 1e-13 * K.norm() * q.norm());
    }
  }
}

TEST(ShaftBeamTest, MassIsSpdAndReproducesTheCylindersRigidBodyInertia) {
  for (bool rotary : {true, false}) {
    for (const Vector3& axis : {Vector3(Vector3::UnitZ()), kOddAxis}) {
      ShaftBeam beam = MakeBeam(kOddStart, kOddStart + 0.15 * axis, 0.07, 0.025);
      beam.rotary_inertia = rotary;
      const Matrix12 M = CalcShaftBeamMass(beam);
      EXPECT_TRUE(M.isApprox(M.transpose(), 0.0));
      EXPECT_EQ(Eigen::LLT<Matrix12>(M).info(), Eigen::Success);
      const CircularSectionProperties s = CalcCircularSectionProperties(beam.section);
      const double mass = kRho * s.area * 0.15;
      const Vector3 centroid = 0.5 * (beam.node_a + beam.node_b);
      const Matrix3 I_c = CylinderInertia(beam, rotary);
      // Rigid translation: T = ½ m v².
      const Vector3 v(0.3, -1.1, 0.8);
      const Vector12 q_t = RigidMotion(beam, v, Vector3::Zero(), Vector3::Zero());
      EXPECT_NEAR(0.5 * q_t.dot(M * q_t), 0.5 * mass * v.squaredNorm(), 1e-13 * mass);
      // General rigid motion about an arbitrary point: T = ½ m |v_G|² + ½ ωᵀ I_G ω.
      const Vector3 p(0.5, 0.2, -0.3), w(0.4, -0.9, 1.3);
      const Vector12 q = RigidMotion(beam, v, w, p);
      const Vector3 v_g = v + w.cross(centroid - p);
      const double T_exact = 0.5 * mass * v_g.squaredNorm() + 0.5 * w.dot(I_c * w);
      EXPECT_NEAR(0.5 * q.dot(M * q), T_exact, 1e-12 * T_exact);
    }
  }
}

TEST(ShaftBeamTest, ElementAlongAnyAxisIsTheRotatedZElement) {
  const double L = 0.11;
  const ShaftBeam z_beam = MakeBeam(Vector3::Zero(), Vector3(0, 0, L), 0.045, 0.015);
  const ShaftBeam odd_beam = MakeBeam(kOddStart, kOddStart + L * kOddAxis, 0.045, 0.015);
  const Matrix12 K_z = CalcShaftBeamStiffness(z_beam), M_z = CalcShaftBeamMass(z_beam);
  const Matrix12 K = CalcShaftBeamStiffness(odd_beam), M = CalcShaftBeamMass(odd_beam);
  // Same spectra: eig(K), eig(M) and the generalized eig(K, M).
  using Solver = Eigen::SelfAdjointEigenSolver<Matrix12>;
  const double k_scale = K_z.norm(), m_scale = M_z.norm();
  EXPECT_MATRIX_NEAR(Solver(K, Eigen::EigenvaluesOnly).eigenvalues() / k_scale,
                     Solver(K_z, Eigen::EigenvaluesOnly).eigenvalues() / k_scale, 1e-13);
  EXPECT_MATRIX_NEAR(Solver(M, Eigen::EigenvaluesOnly).eigenvalues() / m_scale,
                     Solver(M_z, Eigen::EigenvaluesOnly).eigenvalues() / m_scale, 1e-13);
  using GenSolver = Eigen::GeneralizedSelfAdjointEigenSolver<Matrix12>;
  const Vector12 w2_z = GenSolver(K_z, M_z, Eigen::EigenvaluesOnly).eigenvalues();
  const Vector12 w2 = GenSolver(K, M, Eigen::EigenvaluesOnly).eigenvalues();
  EXPECT_MATRIX_NEAR(w2 / w2_z.maxCoeff(), w2_z / w2_z.maxCoeff(), 1e-12);
  // And the matrices themselves are Λᵀ K_z Λ for ANY frame with third axis e_3: the section is
  // axisymmetric, so the twist of e_1, e_2 about e_3 must not matter.
  for (double twist : {0.0, 0.77, -2.1}) {
    const Matrix3 R = CalcAxisFrame(kOddAxis) * Eigen::AngleAxisd(twist, Vector3::UnitZ());
    Matrix12 Lambda = Matrix12::Zero();
    for (int i = 0; i < 4; ++i) Lambda.block<3, 3>(3 * i, 3 * i) = R.transpose();
    EXPECT_MATRIX_NEAR(K / k_scale, (Lambda.transpose() * K_z * Lambda / k_scale).eval(),
                       kAlgebraTol);
    EXPECT_MATRIX_NEAR(M / m_scale, (Lambda.transpose() * M_z * Lambda / m_scale).eval(),
                       kAlgebraTol);
  }
}

TEST(ShaftBeamTest, AxisFrameTakesZOntoTheAxis) {
  EXPECT_MATRIX_NEAR(CalcAxisFrame(Vector3::UnitZ()), Matrix3::Identity(), 0.0);
  for (const Vector3& axis : {kOddAxis, Vector3(-Vector3::UnitZ()), Vector3(Vector3::UnitX()),
                              Vector3(0, 1e-9, -1).normalized()}) {
    const Matrix3 R = CalcAxisFrame(axis);
    EXPECT_MATRIX_NEAR((R.transpose() * R).eval(), Matrix3::Identity(), 1e-15 * 10);
    EXPECT_NEAR(R.determinant(), 1.0, 1e-14);
    EXPECT_MATRIX_NEAR(R.col(2), axis, 1e-15 * 10);
  }
}

TEST(ShaftBeamTest, AssembledShaftAlongAnyAxisHasTheSameFreeFreeSpectrum) {
  const ShaftBeam proto = MakeBeam(Vector3::Zero(), Vector3::UnitZ(), 0.04, 0.01);
  const Assembly z = AssembleShaft(proto, Vector3::Zero(), Vector3::UnitZ(), 0.8, 8);
  const Assembly odd = AssembleShaft(proto, kOddStart, kOddAxis, 0.8, 8);
  using GenSolver = Eigen::GeneralizedSelfAdjointEigenSolver<MatrixX>;
  const VectorX w2_z = GenSolver(z.K, z.M, Eigen::EigenvaluesOnly).eigenvalues();
  const VectorX w2 = GenSolver(odd.K, odd.M, Eigen::EigenvaluesOnly).eigenvalues();
  EXPECT_MATRIX_NEAR(w2 / w2_z.maxCoeff(), w2_z / w2_z.maxCoeff(), 1e-11);
  // Six rigid-body modes of the free shaft, then the first bending pair.
  EXPECT_LT(w2_z.head<6>().cwiseAbs().maxCoeff(), 1e-9 * w2_z(6));
}

// ---------------------------------------------------------------------------------------------
// Natural frequencies against closed forms. Bending in the plane x–z of a shaft along Z uses
// the DOFs {u_x, θy} of every node, which the element decouples exactly from the others (the
// y–z plane, {u_y, θx}, gives the same frequencies).
constexpr int kUx = 0, kUy = 1, kUz = 2, kTx = 3, kTy = 4, kTz = 5;

TEST(ShaftBeamTest, BendingPlanesAxialAndTorsionDecoupleAlongZ) {
  const Assembly a = AssembleShaft(MakeBeam(Vector3::Zero(), Vector3::UnitZ(), 0.05),
                                   Vector3::Zero(), Vector3::UnitZ(), 1.0, 3);
  const std::vector<std::vector<int>> groups = {{kUx, kTy}, {kUy, kTx}, {kUz}, {kTz}};
  for (size_t g = 0; g < groups.size(); ++g) {
    for (size_t h = 0; h < groups.size(); ++h) {
      if (g == h) continue;
      for (int i : SelectDofs(3, groups[g], {})) {
        for (int j : SelectDofs(3, groups[h], {})) {
          EXPECT_EQ(a.K(i, j), 0.0);
          EXPECT_EQ(a.M(i, j), 0.0);
        }
      }
    }
  }
}

struct EulerBernoulliCase {
  const char* name;
  std::vector<std::pair<int, int>> fixed;  // (node, component) removed, plane x–z
  int rigid_modes;
  std::function<double(int)> beta_l;  // β_n L for mode n = 1, 2, …
};

std::vector<EulerBernoulliCase> EulerBernoulliCases() {
  return {
      {"pinned-pinned", {{0, kUx}, {-1, kUx}}, 0, [](int n) { return n * kPi; }},
      {"clamped-free",
       {{0, kUx}, {0, kTy}},
       0,
       [](int n) { return BeamRoot(-1.0, (n - 0.5) * kPi - 0.5, (n - 0.5) * kPi + 0.5); }},
      {"free-free",
       {},
       2,
       [](int n) { return BeamRoot(+1.0, (n + 0.5) * kPi - 0.5, (n + 0.5) * kPi + 0.5); }},
  };
}

TEST(ShaftBeamTest, EulerBernoulliElementConvergesToClosedFormsAtOrderFour) {
  // Hermite-cubic element (Φ = 0, no rotary inertia) with consistent mass: eigenvalue error
  // O(h^{2(p+1−m)}) = O(h⁴) for p = 3, m = 2 (Strang & Fix 1973, §6.3), so ω converges at ~4.
  const double L = 1.2, d = 0.03;
  ShaftBeam proto = MakeBeam(Vector3::Zero(), Vector3::UnitZ(), d);
  proto.shear_deformation = false;
  proto.rotary_inertia = false;
  const CircularSectionProperties s = CalcCircularSectionProperties(proto.section);
  const double c = std::sqrt(kE * s.second_moment / (kRho * s.area)) / (L * L);
  for (const EulerBernoulliCase& bc : EulerBernoulliCases()) {
    std::vector<double> exact;
    for (int n = 1; n <= 4; ++n) exact.push_back(std::pow(bc.beta_l(n), 2) * c);
    const Convergence conv = StudyConvergence(
        {4, 8, 16, 32, 64},
        [&](int n) {
          return Frequencies(AssembleShaft(proto, Vector3::Zero(), Vector3::UnitZ(), L, n),
                             SelectDofs(n, {kUx, kTy}, bc.fixed));
        },
        exact, bc.rigid_modes, (std::string("EB element, ") + bc.name).c_str());
    EXPECT_LT(conv.errors.back(), 2e-6) << bc.name;
    // Asymptotic range: from N = 16 on (the first mesh pairs are pre-asymptotic for mode 4).
    for (size_t i = 2; i < conv.orders.size(); ++i) {
      EXPECT_NEAR(conv.orders[i], 4.0, 0.1)
          << bc.name << " between N = " << conv.meshes[i] << " and " << conv.meshes[i + 1];
    }
  }
}

TEST(ShaftBeamTest, SlenderTimoshenkoShaftMatchesEulerBernoulli) {
  // L/d = 1000: shear and rotary inertia lower ω_n by ≈ ½(nπ r_g/L)²(1 + E/(κG)) ≈ 1.2e-6 n²
  // (r_g² = I/A), below the 1e-5 asserted for n ≤ 2 and 4e-5 for n ≤ 4.
  const double L = 2.0, d = 0.002;
  const ShaftBeam proto = MakeBeam(Vector3::Zero(), Vector3::UnitZ(), d);
  const CircularSectionProperties s = CalcCircularSectionProperties(proto.section);
  const double c = std::sqrt(kE * s.second_moment / (kRho * s.area)) / (L * L);
  for (const EulerBernoulliCase& bc : EulerBernoulliCases()) {
    const int n_el = 64;
    const VectorX w = Frequencies(AssembleShaft(proto, Vector3::Zero(), Vector3::UnitZ(), L, n_el),
                                  SelectDofs(n_el, {kUx, kTy}, bc.fixed));
    for (int n = 1; n <= 4; ++n) {
      const double exact = std::pow(bc.beta_l(n), 2) * c;
      const double rel = (w(bc.rigid_modes + n - 1) - exact) / exact;
      EXPECT_LT(std::abs(rel), n <= 2 ? 1e-5 : 4e-5) << bc.name << " mode " << n;
      EXPECT_LT(rel, 0.0) << bc.name << " mode " << n << ": Timoshenko is softer";
      std::printf("[ %-40s ] %s mode %d: (ω − ω_EB)/ω_EB = %.3e\n", "slender Timoshenko, L/d=1000",
                  bc.name, n, rel);
    }
  }
  // The two bending planes agree.
  const Assembly a = AssembleShaft(proto, Vector3::Zero(), Vector3::UnitZ(), L, 16);
  EXPECT_MATRIX_NEAR(Frequencies(a, SelectDofs(16, {kUx, kTy}, {{0, kUx}, {-1, kUx}})),
                     Frequencies(a, SelectDofs(16, {kUy, kTx}, {{0, kUy}, {-1, kUy}})), 1e-12);
}

TEST(ShaftBeamTest, AxialAndTorsionalFrequenciesConvergeAtOrderTwo) {
  // Clamped–free rod: ω_n = (2n−1)π/(2L) √(E/ρ) (axial), √(G/ρ) (torsion, J_p cancels).
  // Linear element with consistent mass: eigenvalue error O(h²) (p = 1, m = 1).
  const double L = 0.9;
  const ShaftBeam proto = MakeBeam(Vector3::Zero(), Vector3::UnitZ(), 0.05, 0.02);
  for (const auto& [component, speed, label] :
       {std::tuple{kUz, std::sqrt(kE / kRho), "axial, clamped-free"},
        std::tuple{kTz, std::sqrt(proto.material.shear_modulus / kRho), "torsion, clamped-free"}}) {
    std::vector<double> exact;
    for (int n = 1; n <= 3; ++n) exact.push_back((2 * n - 1) * kPi / (2 * L) * speed);
    const Convergence conv = StudyConvergence(
        {8, 16, 32, 64, 128, 256},
        [&, component = component](int n) {
          return Frequencies(AssembleShaft(proto, Vector3::Zero(), Vector3::UnitZ(), L, n),
                             SelectDofs(n, {component}, {{0, component}}));
        },
        exact, 0, label);
    EXPECT_LT(conv.errors.back(), 1e-4) << label;
    for (size_t i = 1; i < conv.orders.size(); ++i) {
      EXPECT_NEAR(conv.orders[i], 2.0, 0.05) << label;
    }
  }
}

// Timoshenko's frequency equation of a simply supported uniform beam (Timoshenko 1921; e.g.
// Han, Benaroya & Wei, J. Sound Vib. 225 (1999) 935–988, §5): with w = W sin kx,
// ψ = Ψ cos kx, k = nπ/L,
//   ρA ρI ω⁴ − [ρA(EI k² + κGA) + ρI κGA k²] ω² + κGA EI k⁴ = 0,
// whose smaller root is the bending branch, the larger the second ("shear") spectrum. n = 0
// gives the pure-rotation mode ω² = κGA/ρI of the second spectrum.
std::pair<double, double> TimoshenkoSimplySupported(double k, double EI, double kGA, double rA,
                                                    double rI) {
  const double a = rA * rI;
  const double b = -(rA * (EI * k * k + kGA) + rI * kGA * k * k);
  const double c = kGA * EI * k * k * k * k;
  const double disc = std::sqrt(b * b - 4 * a * c);
  const double big = (-b + disc) / (2 * a);
  return {std::sqrt(c / (a * big)), std::sqrt(big)};  // small root as c/(a·big): no cancellation
}

TEST(ShaftBeamTest, StubbyShaftConvergesToTimoshenkoSimplySupportedFrequencies) {
  // L/d = 4 (Φ ≈ 0.06 for one element of the whole length; shear lowers ω₁ by ≈ 5 % vs EB).
  for (double d_i : {0.0, 0.035}) {
    const double L = 0.2, d_o = 0.05;
    const ShaftBeam proto = MakeBeam(Vector3::Zero(), Vector3::UnitZ(), d_o, d_i);
    const CircularSectionProperties s = CalcCircularSectionProperties(proto.section);
    const double EI = kE * s.second_moment;
    const double kGA = CalcShaftBeamShearCoefficient(proto) * proto.material.shear_modulus * s.area;
    const double rA = kRho * s.area, rI = kRho * s.second_moment;
    std::vector<double> all;  // both branches, n = 0..20
    for (int n = 0; n <= 20; ++n) {
      const auto [bending, shear] = TimoshenkoSimplySupported(n * kPi / L, EI, kGA, rA, rI);
      if (n > 0) all.push_back(bending);
      all.push_back(shear);
    }
    std::sort(all.begin(), all.end());
    const std::vector<double> exact(all.begin(), all.begin() + 4);
    const double eb1 = std::pow(kPi / L, 2) * std::sqrt(EI / rA);
    std::printf("[ %-40s ] ω₁/ω₁(EB) = %.4f, lowest four: %.6g %.6g %.6g %.6g rad/s\n",
                d_i > 0 ? "hollow stubby shaft" : "solid stubby shaft", exact[0] / eb1, exact[0],
                exact[1], exact[2], exact[3]);
    EXPECT_LT(exact[0] / eb1, 0.97);  // the case really is shear-dominated
    const Convergence conv = StudyConvergence(
        {8, 16, 32, 64, 128, 256},
        [&](int n) {
          return Frequencies(AssembleShaft(proto, Vector3::Zero(), Vector3::UnitZ(), L, n),
                             SelectDofs(n, {kUx, kTy}, {{0, kUx}, {-1, kUx}}));
        },
        exact, 0,
        d_i > 0 ? "Timoshenko pinned-pinned, hollow L/d=4"
                : "Timoshenko pinned-pinned, solid L/d=4");
    EXPECT_LT(conv.errors.back(), 1e-4);
    for (size_t i = 1; i < conv.orders.size(); ++i) {
      EXPECT_NEAR(conv.orders[i], 2.0, 0.05)
          << "between N = " << conv.meshes[i] << " and " << conv.meshes[i + 1];
    }
  }
}

// ---------------------------------------------------------------------------------------------
TEST(ShaftBeamTest, ShearCoefficientOverrideAndFormulaAreUsed) {
  ShaftBeam beam = MakeBeam(Vector3::Zero(), Vector3(0, 0, 0.1), 0.05);
  EXPECT_DOUBLE_EQ(CalcShaftBeamShearCoefficient(beam), 6 * 1.3 / (7 + 6 * 0.3));  // Cowper
  beam.shear_formula = ShearCoefficientFormula::kHutchinson;
  EXPECT_NEAR(CalcShaftBeamShearCoefficient(beam), 6 * 1.69 / (7 + 12 * 0.3 + 4 * 0.09), 1e-15);
  beam.shear_coefficient = 0.75;
  EXPECT_DOUBLE_EQ(CalcShaftBeamShearCoefficient(beam), 0.75);
  const CircularSectionProperties s = CalcCircularSectionProperties(beam.section);
  EXPECT_NEAR(CalcShearDeformationParameter(beam),
              12 * kE * s.second_moment / (0.75 * beam.material.shear_modulus * s.area * 0.01),
              1e-14);
}

TEST(ShaftBeamTest, InvalidInputsThrowNamingTheArgument) {
  const ShaftBeam good = MakeBeam(Vector3::Zero(), Vector3(0, 0, 0.1), 0.05, 0.01);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  struct Case {
    std::function<void(ShaftBeam&)> mutate;
    std::string regex;
  };
  const std::vector<Case> cases = {
      {[](ShaftBeam& b) { b.node_b = b.node_a; }, "zero-length element"},
      {[&](ShaftBeam& b) { b.node_a.x() = nan; }, "^node_a: must be finite, got \\(nan"},
      {[&](ShaftBeam& b) { b.node_b.z() = inf; }, "^node_b: must be finite"},
      {[](ShaftBeam& b) { b.section.outer_diameter = 0.0; },
       "^outer_diameter: must be positive and finite, got 0 m"},
      {[](ShaftBeam& b) { b.section.outer_diameter = -0.05; }, "^outer_diameter: .* got -0.05 m"},
      {[&](ShaftBeam& b) { b.section.outer_diameter = nan; }, "^outer_diameter: .* got nan m"},
      {[](ShaftBeam& b) { b.section.inner_diameter = -0.01; },
       "^inner_diameter: must be non-negative and finite, got -0.01 m"},
      {[](ShaftBeam& b) { b.section.inner_diameter = 0.05; },
       "^inner_diameter: must be smaller than outer_diameter = 0.05 m, got 0.05 m"},
      {[](ShaftBeam& b) { b.section.inner_diameter = 0.06; }, "^inner_diameter: .* got 0.06 m"},
      {[](ShaftBeam& b) { b.material.youngs_modulus = 0.0; },
       "^youngs_modulus: must be positive and finite, got 0 Pa"},
      {[&](ShaftBeam& b) { b.material.youngs_modulus = inf; }, "^youngs_modulus: .* got inf Pa"},
      {[](ShaftBeam& b) { b.material.shear_modulus = -8e10; },
       "^shear_modulus: .* got -8e\\+10 Pa"},
      {[](ShaftBeam& b) { b.material.density = 0.0; },
       "^density: must be positive and finite, got 0 kg/m\\^3"},
      {[](ShaftBeam& b) { b.material.shear_modulus = 0.3 * b.material.youngs_modulus; },
       "^poisson_ratio: must lie in \\(-1, 0.5\\], got 0.66"},
      {[](ShaftBeam& b) { b.shear_coefficient = 0.0; },
       "^shear_coefficient: must be positive and finite, got 0"},
      {[&](ShaftBeam& b) { b.shear_coefficient = nan; }, "^shear_coefficient: .* got nan"},
  };
  for (const Case& c : cases) {
    ShaftBeam beam = good;
    c.mutate(beam);
    SCOPED_TRACE(c.regex);
    EXPECT_THROWS_MESSAGE(CalcShaftBeamStiffness(beam), InvalidInput, c.regex);
    EXPECT_THROWS_MESSAGE(CalcShaftBeamMass(beam), InvalidInput, c.regex);
  }
  // With an explicit κ the Poisson ratio is not needed (an orthotropic shaft's G is allowed).
  ShaftBeam orthotropic = good;
  orthotropic.material.shear_modulus = 0.3 * orthotropic.material.youngs_modulus;
  orthotropic.shear_coefficient = 0.8;
  EXPECT_NO_THROW(CalcShaftBeamStiffness(orthotropic));
  // The frame needs a unit axis.
  EXPECT_THROWS_MESSAGE(CalcAxisFrame(Vector3::Zero()), InvalidInput,
                        "^axis: must be a unit vector, got \\(0, 0, 0\\) with norm 0");
  EXPECT_THROWS_MESSAGE(CalcAxisFrame(Vector3(0, 0, 2)), InvalidInput, "with norm 2");
}

}  // namespace
}  // namespace geardyn
