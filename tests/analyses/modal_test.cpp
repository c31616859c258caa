// Tests of ComputeModes (geardyn/analyses/modal.hpp) against independent truths: closed-form
// torsional pair and spring–mass chain, ARPACK = dense on a few-thousand-DOF Timoshenko shaft,
// residuals, energy fractions, the damped SDOF oscillator, the damping classification, output
// formats and options validation. Systems are built by hand with SystemBuilder; the shaft test
// takes its element matrices from geardyn::models (tests may link models).
#include "geardyn/analyses/modal.hpp"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "geardyn/common/errors.hpp"
#include "geardyn/models/elements/shaft_beam.hpp"
#include "geardyn/system/mesh_core.hpp"
#include "geardyn/system/system_builder.hpp"
#include "geardyn/system/system_model.hpp"
#include "support/expect_throws.hpp"

namespace geardyn {
namespace {

// Closed-form frequencies of small systems: O(n) round-off in a dense solve.
constexpr double kClosedFormTol = 1e-11;
// ARPACK vs dense on the shaft: the dense eigenvalues carry an absolute error ≈ ε·λ_max·O(10), and
// λ_max/λ_min ≈ 2e6 there, so 1e-8 relative leaves a margin of ≈ 20.
constexpr double kArpackDenseTol = 1e-8;

Matrix6 DiagonalMass(double m, double transverse_inertia, double polar_inertia) {
  Vector6 d;
  d << m, m, m, transverse_inertia, transverse_inertia, polar_inertia;
  return d.asDiagonal();
}

// ---------------------------------------------------------------- 2-DOF torsional pair

struct PairParameters {
  double I1 = 2.0e-3, I2 = 7.5e-3;  // [kg·m²]
  double r1 = 0.03, r2 = 0.055;     // base radii [m]
  double k = 3.0e8;                 // mesh stiffness [N/m]
  double c_m = 0.0;                 // mesh damping [N·s/m]
};

Matrix2x12 TorsionalG(const PairParameters& p) {
  Matrix2x12 G = Matrix2x12::Zero();
  G(0, 5) = p.r1;  // δ_η = r1 θz1 + r2 θz2 (external pair, opposite rotations)
  G(0, 11) = p.r2;
  return G;
}

// The pair on its two θz coordinates (the other ten are restricted away).
SystemModel MakeTorsionalPair(const PairParameters& p, Coefficient stiffness) {
  SystemBuilder b;
  const BodyIndex pinion = b.AddBody("pinion", DiagonalMass(1.0, 1e-3, p.I1));
  const BodyIndex gear = b.AddBody("gear", DiagonalMass(2.0, 3e-3, p.I2));
  b.AddMesh("mesh", pinion, gear, TorsionalG(p),
            LinearMeshCore(MeshCoreLevel::kTorsional, std::move(stiffness), 0.01, std::nullopt,
                           MeshDamping::FromCoefficient(p.c_m)));
  const SystemModel full = b.Build();
  return full.Restrict(
      {full.dof_map().dof(pinion, BodyDof::kThetaZ), full.dof_map().dof(gear, BodyDof::kThetaZ)});
}

Coefficient ConstantStiffness(double k) {
  return ConstantCoefficient((VectorX(3) << k, 0.0, 0.0).finished());
}

double PairOmegaSquared(const PairParameters& p) {
  return p.k * (p.r1 * p.r1 / p.I1 + p.r2 * p.r2 / p.I2);  // ω² = k (r1²/I1 + r2²/I2)
}

TEST(ComputeModesTest, TorsionalPairMatchesClosedFormWithOneRigidMode) {
  const PairParameters p;
  const SystemModel model = MakeTorsionalPair(p, ConstantStiffness(p.k));
  ASSERT_EQ(model.num_dofs(), 2);
  const ModalResult r = ComputeModes(model);
  ASSERT_TRUE(r.summary.ok()) << r.summary.BriefReport();
  EXPECT_EQ(r.method_used, ModalMethod::kDense);
  ASSERT_EQ(r.frequencies_hz.size(), 2);
  EXPECT_TRUE(r.frequencies_hz.allFinite());
  EXPECT_TRUE(r.eigenvalues.allFinite());
  EXPECT_EQ(r.num_rigid_body_modes, 1);
  EXPECT_EQ(r.eigenvalues(0), 0.0);
  EXPECT_EQ(r.frequencies_hz(0), 0.0);
  EXPECT_NEAR(r.eigenvalues(1), PairOmegaSquared(p), kClosedFormTol * PairOmegaSquared(p));
  EXPECT_NEAR(r.frequencies_hz(1), std::sqrt(PairOmegaSquared(p)) / (2 * M_PI),
              kClosedFormTol * r.frequencies_hz(1));
  bool warned = false;
  for (const std::string& w : r.summary.warnings) warned |= w.find("rigid") != std::string::npos;
  EXPECT_TRUE(warned) << r.summary.BriefReport();

  // Classification: rigid mode labelled as such, no strain; flexible mode all in the mesh.
  ASSERT_EQ(r.labels.size(), 2u);
  EXPECT_EQ(r.labels[0], ModeType::kRigidBody);
  EXPECT_EQ(r.labels[1], ModeType::kRotational);
  ASSERT_EQ(r.strain_names, std::vector<std::string>{"mesh:mesh"});
  EXPECT_EQ(r.strain_fractions(0, 0), 0.0);
  EXPECT_NEAR(r.strain_fractions(1, 0), 1.0, 1e-14);
  EXPECT_NEAR(r.kinetic_fractions(1, static_cast<int>(DofKind::kRotationAxial)), 1.0, 1e-14);
  // Body kinetic energy of the flexible mode: T_i ∝ I_i θ_i² with I1θ1 r2 = I2θ2 r1 (momentum).
  const double t1 = p.r1 * p.r1 / p.I1, t2 = p.r2 * p.r2 / p.I2;
  EXPECT_NEAR(r.body_kinetic_fractions(1, 0), t1 / (t1 + t2), 1e-12);
  EXPECT_NEAR(r.body_kinetic_fractions(1, 1), t2 / (t1 + t2), 1e-12);
}

TEST(ComputeModesTest, TorsionalPairUsesTheMeanOfAVaryingMeshStiffness) {
  PairParameters p;
  // Rectangular wave between 2.0e8 and 4.0e8 N/m, half a mesh period each: K̄ = 3.0e8 N/m.
  const VectorX breakpoints = (VectorX(2) << 0.0, M_PI).finished();
  MatrixX values = MatrixX::Zero(3, 2);
  values(0, 0) = 2.0e8;
  values(0, 1) = 4.0e8;
  const SystemModel model = MakeTorsionalPair(p, PiecewiseConstantCoefficient(breakpoints, values));
  const ModalResult r = ComputeModes(model);
  ASSERT_TRUE(r.summary.ok()) << r.summary.BriefReport();
  EXPECT_NEAR(r.eigenvalues(1), PairOmegaSquared(p), kClosedFormTol * PairOmegaSquared(p));
}

TEST(ComputeModesTest, UnrestrictedPairReportsElevenRigidModesAndNoNaN) {
  const PairParameters p;
  SystemBuilder b;
  const BodyIndex pinion = b.AddBody("pinion", DiagonalMass(1.0, 1e-3, p.I1));
  const BodyIndex gear = b.AddBody("gear", DiagonalMass(2.0, 3e-3, p.I2));
  b.AddMesh("mesh", pinion, gear, TorsionalG(p),
            LinearMeshCore(MeshCoreLevel::kTorsional, ConstantStiffness(p.k), 0.01));
  const SystemModel model = b.Build();
  for (const ModalMethod method : {ModalMethod::kDense, ModalMethod::kArpack}) {
    ModalOptions options;
    options.method = method;
    options.num_modes = 12 - 3;  // ARPACK needs num_modes < n − 1
    const ModalResult r = ComputeModes(model, options);
    ASSERT_TRUE(r.summary.ok()) << ToString(method) << ": " << r.summary.BriefReport();
    EXPECT_EQ(r.method_used, method);
    EXPECT_TRUE(r.frequencies_hz.allFinite());
    EXPECT_EQ(r.num_rigid_body_modes, 9);  // all 9 requested are among the 11 zeros
    EXPECT_TRUE((r.eigenvalues.array() == 0.0).all());
  }
  const ModalResult all = ComputeModes(model);
  EXPECT_EQ(all.num_rigid_body_modes, 11);
  EXPECT_NEAR(all.eigenvalues(11), PairOmegaSquared(p), kClosedFormTol * PairOmegaSquared(p));
  ASSERT_EQ(all.multiplicity_groups.size(), 2u);
  EXPECT_EQ(all.multiplicity_groups[0].size(), 11u);
}

// ---------------------------------------------------------------- spring–mass chain

// N equal masses m on x, springs k between neighbours and to ground at both ends:
// λ_j = (2k/m)(1 − cos(jπ/(N + 1))), j = 1…N.
struct Chain {
  int num_masses = 8;
  double m = 1.5, k = 2.0e6;
};

MatrixX XSpring(double k, int num_bodies) {
  const int size = 6 * num_bodies;
  MatrixX K = MatrixX::Zero(size, size);
  if (num_bodies == 1) {
    K(0, 0) = k;
  } else {
    K(0, 0) = K(6, 6) = k;
    K(0, 6) = K(6, 0) = -k;
  }
  return K;
}

// Optional dampers: `dashpot` on the spring between bodies 0 and 1 only (non-proportional).
SystemModel MakeChain(const Chain& c, double dashpot = 0.0, double rayleigh_alpha = -1.0,
                      double rayleigh_beta = 0.0, double modal_zeta = -1.0) {
  SystemBuilder b;
  std::vector<BodyIndex> bodies;
  for (int i = 0; i < c.num_masses; ++i) {
    bodies.push_back(b.AddBody("m" + std::to_string(i), DiagonalMass(c.m, 1.0, 1.0)));
  }
  b.AddElement("ground_left", ElementKind::kSpring, {bodies.front()}, XSpring(c.k, 1));
  b.AddElement("ground_right", ElementKind::kSpring, {bodies.back()}, XSpring(c.k, 1));
  for (int i = 0; i + 1 < c.num_masses; ++i) {
    b.AddElement("s" + std::to_string(i), ElementKind::kSpring, {bodies[i], bodies[i + 1]},
                 XSpring(c.k, 2), i == 0 && dashpot > 0.0 ? XSpring(dashpot, 2) : MatrixX());
  }
  if (rayleigh_alpha >= 0.0) b.SetRayleighDamping(rayleigh_alpha, rayleigh_beta);
  if (modal_zeta >= 0.0) b.SetModalDampingRatio(modal_zeta);
  const SystemModel full = b.Build();
  std::vector<int> x_dofs;
  for (const BodyIndex body : bodies) x_dofs.push_back(full.dof_map().dof(body, BodyDof::kX));
  return full.Restrict(x_dofs);
}

VectorX ChainEigenvalues(const Chain& c) {
  VectorX lambda(c.num_masses);
  for (int j = 1; j <= c.num_masses; ++j) {
    lambda(j - 1) = 2.0 * c.k / c.m * (1.0 - std::cos(j * M_PI / (c.num_masses + 1)));
  }
  return lambda;
}

TEST(ComputeModesTest, SpringMassChainMatchesClosedForm) {
  const Chain c;
  const SystemModel model = MakeChain(c);
  const VectorX expected = ChainEigenvalues(c);
  ModalOptions options;
  options.compute_shapes = true;
  const ModalResult r = ComputeModes(model, options);
  ASSERT_TRUE(r.summary.ok()) << r.summary.BriefReport();
  EXPECT_EQ(r.num_rigid_body_modes, 0);
  EXPECT_TRUE(r.summary.warnings.empty()) << r.summary.BriefReport();
  ASSERT_EQ(r.eigenvalues.size(), c.num_masses);
  for (int j = 0; j < c.num_masses; ++j) {
    EXPECT_NEAR(r.eigenvalues(j), expected(j), kClosedFormTol * expected(c.num_masses - 1)) << j;
  }
  // Shapes: M-orthonormal, residual small, mode j ∝ sin(j i π/(N+1)).
  const MatrixX M(model.mass()), K(model.constant_stiffness());
  ASSERT_EQ(r.shapes.cols(), c.num_masses);
  EXPECT_LT(
      (r.shapes.transpose() * M * r.shapes - MatrixX::Identity(c.num_masses, c.num_masses)).norm(),
      1e-12);
  for (int j = 0; j < c.num_masses; ++j) {
    const VectorX phi = r.shapes.col(j);
    EXPECT_LT((K * phi - r.eigenvalues(j) * M * phi).norm() / (K * phi).norm(), 1e-12);
    VectorX sine(c.num_masses);
    for (int i = 0; i < c.num_masses; ++i) {
      sine(i) = std::sin((j + 1) * (i + 1) * M_PI / (c.num_masses + 1));
    }
    EXPECT_NEAR(std::abs(phi.normalized().dot(sine.normalized())), 1.0, 1e-12) << j;
  }
  EXPECT_LT(r.summary.error_estimate, 1e-12);
  EXPECT_EQ(r.dof_names.size(), static_cast<std::size_t>(c.num_masses));
  // All modes distinct: singleton groups.
  EXPECT_EQ(r.multiplicity_groups.size(), static_cast<std::size_t>(c.num_masses));
  for (const ModeType t : r.labels) EXPECT_EQ(t, ModeType::kTranslational);
}

TEST(ComputeModesTest, SpringMassChainStrainFractionsSumToOneAndAreSymmetric) {
  const Chain c;
  const ModalResult r = ComputeModes(MakeChain(c));
  ASSERT_EQ(r.strain_fractions.cols(), c.num_masses + 1);  // 2 ground springs + N − 1 springs
  EXPECT_EQ(r.strain_names.front(), "element:ground_left");
  for (int k = 0; k < c.num_masses; ++k) {
    EXPECT_NEAR(r.strain_fractions.row(k).sum(), 1.0, 1e-14);
    EXPECT_NEAR(r.kinetic_fractions.row(k).sum(), 1.0, 1e-14);
    EXPECT_NEAR(r.body_kinetic_fractions.row(k).sum(), 1.0, 1e-14);
    EXPECT_TRUE((r.strain_fractions.row(k).array() >= 0.0).all());
    // The chain is symmetric: the two ground springs store the same energy.
    EXPECT_NEAR(r.strain_fractions(k, 0), r.strain_fractions(k, 1), 1e-12);
  }
}

TEST(ComputeModesTest, ForcedArpackEqualsDenseOnTheChain) {
  const Chain c;
  const SystemModel model = MakeChain(c);
  ModalOptions dense_options, arpack_options;
  dense_options.method = ModalMethod::kDense;
  arpack_options.method = ModalMethod::kArpack;
  dense_options.num_modes = arpack_options.num_modes = 4;
  const ModalResult dense = ComputeModes(model, dense_options);
  const ModalResult arpack = ComputeModes(model, arpack_options);
  ASSERT_TRUE(arpack.summary.ok()) << arpack.summary.BriefReport();
  EXPECT_EQ(dense.method_used, ModalMethod::kDense);
  EXPECT_EQ(arpack.method_used, ModalMethod::kArpack);
  ASSERT_EQ(dense.eigenvalues.size(), 4);
  ASSERT_EQ(arpack.eigenvalues.size(), 4);
  for (int k = 0; k < 4; ++k) {
    EXPECT_NEAR(arpack.eigenvalues(k), dense.eigenvalues(k), 1e-10 * dense.eigenvalues(k));
  }
  EXPECT_LT((arpack.kinetic_fractions - dense.kinetic_fractions).norm(), 1e-8);
  EXPECT_LT((arpack.strain_fractions - dense.strain_fractions).norm(), 1e-8);
}

TEST(ComputeModesTest, DenseShiftKeepsTheModesNearestIt) {
  const Chain c;
  const VectorX expected = ChainEigenvalues(c);
  ModalOptions options;
  options.method = ModalMethod::kDense;
  options.num_modes = 2;
  options.shift = 0.5 * (expected(4) + expected(5));
  const ModalResult r = ComputeModes(MakeChain(c), options);
  ASSERT_EQ(r.eigenvalues.size(), 2);
  EXPECT_NEAR(r.eigenvalues(0), expected(4), 1e-10 * expected(4));
  EXPECT_NEAR(r.eigenvalues(1), expected(5), 1e-10 * expected(5));
}

// ---------------------------------------------------------------- method selection

TEST(SelectModalMethodTest, FollowsTheTable) {
  ModalOptions o;
  EXPECT_EQ(internal::SelectModalMethod(12, o, nullptr), ModalMethod::kDense);
  EXPECT_EQ(internal::SelectModalMethod(kDenseDofThreshold - 1, o, nullptr), ModalMethod::kDense);
  EXPECT_EQ(internal::SelectModalMethod(kDenseDofThreshold, o, nullptr), ModalMethod::kArpack);
  o.num_modes = 150;  // more than half of the modes: dense is cheaper
  EXPECT_EQ(internal::SelectModalMethod(kDenseDofThreshold + 1, o, nullptr), ModalMethod::kDense);
  o = {};
  o.dense_max_dofs = 10;
  EXPECT_EQ(internal::SelectModalMethod(100, o, nullptr), ModalMethod::kArpack);
  o.method = ModalMethod::kDense;
  EXPECT_EQ(internal::SelectModalMethod(100000, o, nullptr), ModalMethod::kDense);
  o.method = ModalMethod::kArpack;
  std::string why;
  EXPECT_EQ(internal::SelectModalMethod(12, o, &why), ModalMethod::kDense);  // 20 ≥ 12 − 1
  EXPECT_NE(why.find("kArpack"), std::string::npos);
}

TEST(ComputeModesTest, ForcedArpackOnATinySystemFallsBackWithAWarning) {
  const PairParameters p;
  ModalOptions options;
  options.method = ModalMethod::kArpack;
  const ModalResult r = ComputeModes(MakeTorsionalPair(p, ConstantStiffness(p.k)), options);
  EXPECT_TRUE(r.summary.ok());
  EXPECT_EQ(r.method_used, ModalMethod::kDense);
  ASSERT_FALSE(r.summary.warnings.empty());
  EXPECT_NE(r.summary.warnings.front().find("dense"), std::string::npos);
}

// ---------------------------------------------------------------- long Timoshenko shaft

// A free-free steel shaft along Z, num_elements Timoshenko elements, a body (zero own mass) at
// every node: 6·(num_elements + 1) DOFs, six rigid-body modes, bending modes in pairs.
SystemModel MakeShaft(int num_elements, double length = 1.0, double diameter = 0.2) {
  SystemBuilder b;
  std::vector<BodyIndex> nodes;
  const double h = length / num_elements;
  for (int i = 0; i <= num_elements; ++i) {
    nodes.push_back(b.AddBody("n" + std::to_string(i), Matrix6::Zero(), Vector3(0.0, 0.0, i * h)));
  }
  ShaftBeam beam;
  beam.section.outer_diameter = diameter;
  beam.material = ShaftMaterial::FromPoissonRatio(2.1e11, 0.3, 7850.0);
  beam.node_b = Vector3(0.0, 0.0, h);
  // Every element is the same segment translated: one matrix pair serves them all.
  const MatrixX K = CalcShaftBeamStiffness(beam), M = CalcShaftBeamMass(beam);
  for (int i = 0; i < num_elements; ++i) {
    b.AddElement("shaft" + std::to_string(i), ElementKind::kShaft, {nodes[i], nodes[i + 1]}, K,
                 MatrixX(), M);
  }
  return b.Build();
}

TEST(ComputeModesTest, ArpackEqualsDenseOnAFewThousandDofShaft) {
  const SystemModel model = MakeShaft(400);
  ASSERT_EQ(model.num_dofs(), 2406);
  ModalOptions arpack_options;
  arpack_options.num_modes = 26;  // 6 rigid-body modes + the lowest 20 flexible ones
  arpack_options.compute_shapes = true;
  const ModalResult arpack = ComputeModes(model, arpack_options);  // kAuto → ARPACK
  ASSERT_TRUE(arpack.summary.ok()) << arpack.summary.BriefReport();
  EXPECT_EQ(arpack.method_used, ModalMethod::kArpack);
  EXPECT_EQ(arpack.num_rigid_body_modes, 6);

  ModalOptions dense_options;
  dense_options.method = ModalMethod::kDense;
  dense_options.compute_energy_fractions = false;  // eigenvalues only: the O(n³) reference
  const ModalResult dense = ComputeModes(model, dense_options);
  ASSERT_TRUE(dense.summary.ok()) << dense.summary.BriefReport();
  EXPECT_EQ(dense.method_used, ModalMethod::kDense);
  EXPECT_EQ(dense.num_rigid_body_modes, 6);
  ASSERT_EQ(dense.eigenvalues.size(), 2406);
  double worst = 0.0;
  for (int k = 0; k < 26; ++k) {
    if (k >= 6) {
      worst = std::max(worst, std::abs(arpack.eigenvalues(k) / dense.eigenvalues(k) - 1.0));
    }
    if (k < 6) {
      EXPECT_EQ(arpack.eigenvalues(k), 0.0);
      EXPECT_EQ(dense.eigenvalues(k), 0.0);
    } else {
      EXPECT_NEAR(arpack.eigenvalues(k), dense.eigenvalues(k),
                  kArpackDenseTol * dense.eigenvalues(k))
          << "mode " << k;
    }
  }
  char text[64];
  std::snprintf(text, sizeof(text), "%.3e (lambda_max/lambda_7 = %.3e)", worst,
                dense.eigenvalues(2405) / dense.eigenvalues(6));
  RecordProperty("max_relative_difference", text);
  // Residual ‖K̄φ − ω²Mφ‖/‖K̄φ‖ of the ARPACK pairs, recomputed here.
  const SparseMatrix& M = model.mass();
  const SparseMatrix& K = model.constant_stiffness();
  for (int k = 6; k < 26; ++k) {
    const VectorX phi = arpack.shapes.col(k);
    const VectorX Kphi = K * phi;
    EXPECT_LT((Kphi - arpack.eigenvalues(k) * (M * phi)).norm() / Kphi.norm(), 1e-8) << k;
  }
  EXPECT_LT(arpack.summary.error_estimate, 1e-8);

  // Axisymmetric shaft: bending modes come in pairs (x–z and y–z planes).
  int pairs = 0;
  for (const std::vector<int>& g : arpack.multiplicity_groups) pairs += g.size() == 2 ? 1 : 0;
  EXPECT_GE(pairs, 5);
  // Energy fractions of a free shaft: kinetic over kinds and strain over the 400 elements.
  for (int k = 0; k < 26; ++k) {
    EXPECT_NEAR(arpack.kinetic_fractions.row(k).sum(), 1.0, 1e-12);
    if (k >= 6) {
      EXPECT_NEAR(arpack.strain_fractions.row(k).sum(), 1.0, 1e-12);
    }
  }
  // The first flexible pair is bending: mostly transverse kinetic energy.
  EXPECT_EQ(arpack.labels[6], ModeType::kTranslational);
  EXPECT_EQ(arpack.labels[7], ModeType::kTranslational);
}

TEST(ComputeModesTest, ShaftLabelsFindTorsionalAndAxialModes) {
  // Free-free shaft: the first torsional mode has λ = (π/L)² G/ρ, the first axial one
  // (π/L)² E/ρ (to the discretization error of 60 linear elements, < 0.1 %).
  const SystemModel model = MakeShaft(60, 1.0, 0.05);
  const double g_over_rho = 2.1e11 / (2.0 * 1.3) / 7850.0, e_over_rho = 2.1e11 / 7850.0;
  const double torsion = M_PI * M_PI * g_over_rho, axial = M_PI * M_PI * e_over_rho;
  ModalOptions options;
  options.method = ModalMethod::kDense;
  const ModalResult r = ComputeModes(model, options);
  ASSERT_TRUE(r.summary.ok());
  int found_torsion = -1, found_axial = -1;
  for (Eigen::Index k = 0; k < r.eigenvalues.size(); ++k) {
    if (found_torsion < 0 && r.labels[k] == ModeType::kRotational)
      found_torsion = static_cast<int>(k);
    if (found_axial < 0 && r.labels[k] == ModeType::kAxial) found_axial = static_cast<int>(k);
  }
  ASSERT_GE(found_torsion, 0);
  ASSERT_GE(found_axial, 0);
  EXPECT_NEAR(r.eigenvalues(found_torsion) / torsion, 1.0, 1e-3);
  EXPECT_NEAR(r.eigenvalues(found_axial) / axial, 1.0, 1e-3);
  EXPECT_GT(r.kinetic_fractions(found_torsion, static_cast<int>(DofKind::kRotationAxial)),
            1.0 - 1e-9);
  for (Eigen::Index k = 0; k < r.eigenvalues.size(); ++k) {
    ASSERT_NEAR(r.kinetic_fractions.row(k).sum(), 1.0, 1e-12);
    ASSERT_TRUE((r.kinetic_fractions.row(k).array() >= 0.0).all());
    if (r.eigenvalues(k) > 0.0) {
      ASSERT_NEAR(r.strain_fractions.row(k).sum(), 1.0, 1e-12);
    }
  }
}

// ---------------------------------------------------------------- damping

TEST(ComputeModesTest, SingleDofDampedOscillatorMatchesClosedForm) {
  const double m = 3.0, k = 4.0e5, zeta = 0.08;
  const double c = 2.0 * zeta * std::sqrt(k * m);
  SystemBuilder b;
  const BodyIndex body = b.AddBody("mass", DiagonalMass(m, 1.0, 1.0));
  b.AddElement("spring", ElementKind::kSpring, {body}, XSpring(k, 1), XSpring(c, 1));
  const SystemModel full = b.Build();
  const SystemModel model = full.Restrict({full.dof_map().dof(body, BodyDof::kX)});
  ModalOptions options;
  options.compute_damped = true;
  const ModalResult r = ComputeModes(model, options);
  ASSERT_TRUE(r.summary.ok()) << r.summary.BriefReport();
  const double omega_n = std::sqrt(k / m);
  ASSERT_EQ(r.damped_modes.size(), 1u);
  const DampedMode& d = r.damped_modes[0];
  EXPECT_NEAR(d.frequency_hz, omega_n * std::sqrt(1.0 - zeta * zeta) / (2 * M_PI),
              1e-12 * omega_n);  // ω_d = ω_n √(1 − ζ²)
  EXPECT_NEAR(d.natural_frequency_hz, omega_n / (2 * M_PI), 1e-12 * omega_n);
  EXPECT_NEAR(d.damping_ratio, zeta, 1e-12);
  EXPECT_NEAR(r.modal_damping_ratios(0), zeta, 1e-12);
  // One DOF: C is a multiple of M, hence Rayleigh.
  EXPECT_EQ(r.damping_kind, DampingKind::kRayleigh);
}

TEST(ComputeModesTest, OverdampedOscillatorGivesTwoRealModes) {
  const double m = 1.0, k = 100.0, zeta = 2.0;
  SystemBuilder b;
  const BodyIndex body = b.AddBody("mass", DiagonalMass(m, 1.0, 1.0));
  b.AddElement("spring", ElementKind::kSpring, {body}, XSpring(k, 1),
               XSpring(2.0 * zeta * std::sqrt(k * m), 1));
  const SystemModel full = b.Build();
  ModalOptions options;
  options.compute_damped = true;
  const ModalResult r =
      ComputeModes(full.Restrict({full.dof_map().dof(body, BodyDof::kX)}), options);
  ASSERT_EQ(r.damped_modes.size(), 2u);
  const double root = std::sqrt(zeta * zeta - 1.0);  // λ = −ω_n(ζ ∓ √(ζ² − 1))
  EXPECT_NEAR(r.damped_modes[0].eigenvalue.real(), -10.0 * (zeta - root), 1e-10);
  EXPECT_NEAR(r.damped_modes[1].eigenvalue.real(), -10.0 * (zeta + root), 1e-10);
  for (const DampedMode& d : r.damped_modes) {
    EXPECT_EQ(d.frequency_hz, 0.0);
    EXPECT_EQ(d.damping_ratio, 1.0);
  }
}

TEST(ComputeModesTest, MeshDampingOfTheTorsionalPair) {
  // Relative coordinate δ = r1θ1 + r2θ2 with m_e = 1/(r1²/I1 + r2²/I2):
  // m_e δ̈ + c_m δ̇ + k δ = 0, ζ = c_m / (2√(k m_e)).
  PairParameters p;
  const double m_e = 1.0 / (p.r1 * p.r1 / p.I1 + p.r2 * p.r2 / p.I2);
  p.c_m = 2.0 * 0.05 * std::sqrt(p.k * m_e);
  ModalOptions options;
  options.compute_damped = true;
  const ModalResult r = ComputeModes(MakeTorsionalPair(p, ConstantStiffness(p.k)), options);
  ASSERT_TRUE(r.summary.ok()) << r.summary.BriefReport();
  ASSERT_EQ(r.damped_modes.size(), 2u);
  EXPECT_EQ(r.damped_modes[0].natural_frequency_hz, 0.0);  // the free rotation
  EXPECT_NEAR(r.damped_modes[1].damping_ratio, 0.05, 1e-10);
  EXPECT_NEAR(r.modal_damping_ratios(1), 0.05, 1e-12);
  EXPECT_NE(r.damping_kind, DampingKind::kNonProportional);
}

TEST(ComputeModesTest, DetectsRayleighDampingAndRecoversItsCoefficients) {
  const Chain c;
  const double alpha = 3.0, beta = 2.0e-5;
  ModalOptions options;
  options.compute_damped = true;
  const ModalResult r = ComputeModes(MakeChain(c, 0.0, alpha, beta), options);
  ASSERT_TRUE(r.summary.ok()) << r.summary.BriefReport();
  EXPECT_EQ(r.damping_kind, DampingKind::kRayleigh);
  EXPECT_NEAR(r.rayleigh_alpha, alpha, 1e-9 * alpha);
  EXPECT_NEAR(r.rayleigh_beta, beta, 1e-9 * beta);
  // ζ_k = α/(2ω_k) + βω_k/2, and the state-space modes agree with them.
  ASSERT_EQ(r.damped_modes.size(), static_cast<std::size_t>(c.num_masses));
  for (int k = 0; k < c.num_masses; ++k) {
    const double omega = std::sqrt(r.eigenvalues(k));
    const double zeta = alpha / (2.0 * omega) + beta * omega / 2.0;
    EXPECT_NEAR(r.modal_damping_ratios(k), zeta, 1e-10);
    EXPECT_NEAR(r.damped_modes[k].damping_ratio, zeta, 1e-9);
    EXPECT_NEAR(r.damped_modes[k].natural_frequency_hz, omega / (2 * M_PI), 1e-9 * omega);
  }
}

TEST(ComputeModesTest, DetectsClassicalModalDamping) {
  Chain c;
  c.num_masses = 5;
  ModalOptions options;
  options.compute_damped = true;
  const ModalResult r = ComputeModes(MakeChain(c, 0.0, -1.0, 0.0, 0.04), options);
  ASSERT_TRUE(r.summary.ok()) << r.summary.BriefReport();
  EXPECT_EQ(r.damping_kind, DampingKind::kClassical);
  ASSERT_EQ(r.damped_modes.size(), 5u);
  for (int k = 0; k < 5; ++k) {
    EXPECT_NEAR(r.modal_damping_ratios(k), 0.04, 1e-10);
    EXPECT_NEAR(r.damped_modes[k].damping_ratio, 0.04, 1e-9);
    EXPECT_NEAR(r.damped_modes[k].frequency_hz, r.frequencies_hz(k) * std::sqrt(1.0 - 0.04 * 0.04),
                1e-9 * r.frequencies_hz(k));
  }
}

TEST(ComputeModesTest, DetectsNonProportionalDampingAndSolvesTheQuadraticProblem) {
  const Chain c;
  ModalOptions options;
  options.compute_damped = true;
  const SystemModel model = MakeChain(c, 400.0);
  const ModalResult r = ComputeModes(model, options);
  ASSERT_TRUE(r.summary.ok()) << r.summary.BriefReport();
  EXPECT_EQ(r.damping_kind, DampingKind::kNonProportional);
  bool warned = false;
  for (const std::string& w : r.summary.warnings) {
    warned |= w.find("not proportional") != std::string::npos;
  }
  EXPECT_TRUE(warned);
  ASSERT_EQ(r.damped_modes.size(), static_cast<std::size_t>(c.num_masses));
  // Independent check: λ²M + λC + K is singular at every damped eigenvalue.
  const MatrixX M(model.mass()), K(model.constant_stiffness()), C(model.constant_damping());
  for (const DampedMode& d : r.damped_modes) {
    const std::complex<double> l = d.eigenvalue;
    const Eigen::MatrixXcd Q = (l * l) * M.cast<std::complex<double>>() +
                               l * C.cast<std::complex<double>>() + K.cast<std::complex<double>>();
    const Eigen::JacobiSVD<Eigen::MatrixXcd> svd(Q);
    const VectorX s = svd.singularValues();
    EXPECT_LT(s(s.size() - 1) / s(0), 1e-10) << l;
    // Mode 3 of the chain, φ_i = sin(3πi/9), moves masses 0 and 1 alike (sin 2x = sin x at
    // x = π/3): no motion across the dashpot, λ = ±i√(k/m) and ζ = 0 exactly (it read a
    // round-off ζ > 0 before ζ was clamped at the Schur backward error); the others are damped.
    if (std::abs(l.imag() - std::sqrt(c.k / c.m)) < 1e-9 * std::sqrt(c.k / c.m)) {
      EXPECT_EQ(d.damping_ratio, 0.0) << l;
    } else {
      EXPECT_GT(d.damping_ratio, 0.0) << l;
    }
    EXPECT_LT(d.damping_ratio, 1.0);
    EXPECT_GT(d.eigenvalue.imag(), 0.0);  // conjugate pairs once
  }
}

TEST(ComputeModesTest, UndampedModelHasNoDampingAndNoDampedModesUnlessAsked) {
  const ModalResult r = ComputeModes(MakeChain(Chain{}));
  EXPECT_EQ(r.damping_kind, DampingKind::kNone);
  EXPECT_TRUE(r.damped_modes.empty());
}

// ---------------------------------------------------------------- output and options

TEST(ComputeModesTest, JsonAndCsvOutputs) {
  const PairParameters p;
  ModalOptions options;
  options.compute_shapes = true;
  const ModalResult r = ComputeModes(MakeTorsionalPair(p, ConstantStiffness(p.k)), options);
  const nlohmann::json j = nlohmann::json::parse(ModalResultToJson(r));
  EXPECT_EQ(j["method_used"], "dense");
  EXPECT_EQ(j["status"], "success");
  ASSERT_EQ(j["frequencies_hz"].size(), 2u);
  EXPECT_EQ(j["frequencies_hz"][0].get<double>(), 0.0);
  EXPECT_DOUBLE_EQ(j["frequencies_hz"][1].get<double>(), r.frequencies_hz(1));
  EXPECT_EQ(j["modes"][0]["label"], "rigid_body");
  EXPECT_EQ(j["modes"][1]["label"], "rotational");
  EXPECT_DOUBLE_EQ(j["modes"][1]["strain"]["mesh:mesh"].get<double>(), 1.0);
  EXPECT_EQ(j["shapes"].size(), 2u);
  EXPECT_EQ(j["dof_names"][0], "pinion.θz");
  EXPECT_EQ(j["num_rigid_body_modes"], 1);

  const std::string csv = ModalResultToCsv(r);
  EXPECT_EQ(csv.substr(0, csv.find('\n')),
            "mode,frequency_hz,eigenvalue,multiplicity,label,kinetic_translation_transverse,"
            "kinetic_translation_axial,kinetic_rotation_axial,kinetic_rotation_tilt,"
            "strain_mesh:mesh");
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 3);
}

TEST(ModalOptionsTest, InvalidOptionsThrowNamingTheField) {
  const PairParameters p;
  const SystemModel model = MakeTorsionalPair(p, ConstantStiffness(p.k));
  ModalOptions o;
  std::string why;
  EXPECT_TRUE(o.IsValid(&why));
  o.num_modes = -1;
  EXPECT_THROWS_MESSAGE(ComputeModes(model, o), InvalidInput, "num_modes.*-1");
  // Upper bound at its edge: n modes are all of them, n + 1 is refused naming n and the value.
  const int n = model.num_dofs();
  o = {};
  o.num_modes = n;
  EXPECT_EQ(ComputeModes(model, o).frequencies_hz.size(), n);
  o.num_modes = n + 1;
  EXPECT_THROWS_MESSAGE(ComputeModes(model, o), InvalidInput,
                        "num_modes: must be ≤ the number of DOFs " + std::to_string(n) + " .*got " +
                            std::to_string(n + 1));
  o = {};
  o.shift = std::nan("");
  EXPECT_THROWS_MESSAGE(ComputeModes(model, o), InvalidInput, "shift");
  o = {};
  o.dense_max_dofs = 0;
  EXPECT_THROWS_MESSAGE(ComputeModes(model, o), InvalidInput, "dense_max_dofs");
  o = {};
  o.multiplicity_rel_tol = 0.0;
  EXPECT_THROWS_MESSAGE(ComputeModes(model, o), InvalidInput, "multiplicity_rel_tol");
  o = {};
  o.zero_tol = -1e-3;
  EXPECT_THROWS_MESSAGE(ComputeModes(model, o), InvalidInput, "zero_tol");
  o = {};
  o.arpack_tol = 1.0;
  EXPECT_THROWS_MESSAGE(ComputeModes(model, o), InvalidInput, "arpack_tol");
  o = {};
  o.proportional_damping_tol = 0.0;
  EXPECT_THROWS_MESSAGE(ComputeModes(model, o), InvalidInput, "proportional_damping_tol");
  o = {};
  o.damped_max_dofs = 0;
  EXPECT_THROWS_MESSAGE(ComputeModes(model, o), InvalidInput, "damped_max_dofs");
  o = {};
  o.method = static_cast<ModalMethod>(7);
  EXPECT_FALSE(o.IsValid(&why));
  EXPECT_NE(why.find("method"), std::string::npos);
  EXPECT_THROWS_MESSAGE(ComputeModes(SystemModel(), ModalOptions{}), InvalidInput, "no DOFs");
}

}  // namespace
}  // namespace geardyn
