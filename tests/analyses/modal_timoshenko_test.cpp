// ComputeModes on a simply supported uniform Timoshenko beam made of shaft elements
// (geardyn/models/elements/shaft_beam.hpp) against the analytic Timoshenko frequencies.
//
// Truth: Timoshenko's beam equation (S. P. Timoshenko, Phil. Mag. 41 (1921) 744–746; in the form
// of Han, Benaroya & Wei, "Dynamics of transversely vibrating beams using four engineering
// theories", J. Sound Vib. 225(5) (1999) 935–988, section on the Timoshenko model):
//   EI ∂⁴w/∂s⁴ + ρA ∂²w/∂t² − ρI (1 + E/(κG)) ∂⁴w/∂s²∂t² + (ρ²I/(κG)) ∂⁴w/∂t⁴ = 0.
// A simply supported beam (w = 0 and bending moment EI ψ' = 0 at both ends) has the exact modes
// w = sin(k_n s), ψ = C cos(k_n s) with k_n = nπ/L, and substituting them gives for each n the
// quadratic in ω²
//   (ρ²I/(κG)) ω⁴ − [ρA + ρI k_n² (1 + E/(κG))] ω² + EI k_n⁴ = 0,
// whose smaller root is the n-th flexural frequency (the larger one is the shear-mode branch).
// A thick beam (L/D = 5) makes the shear and rotary-inertia corrections ≈ 10 % at n = 3, far
// above the discretization error being tested.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "geardyn/analyses/modal.hpp"
#include "geardyn/models/elements/shaft_beam.hpp"
#include "geardyn/system/system_builder.hpp"

namespace geardyn {
namespace {

constexpr double kE = 2.1e11;   // Young's modulus [Pa]
constexpr double kNu = 0.3;     // Poisson's ratio [-]
constexpr double kRho = 7850;   // density [kg/m³]
constexpr double kD = 0.2;      // diameter [m]
constexpr double kL = 1.0;      // span [m]
constexpr int kNumChecked = 4;  // flexural modes compared

// Cowper (1966) shear coefficient of a solid circular section, given to the element explicitly
// so that the analytic equation and the elements use the same κ.
double Kappa() { return 6.0 * (1.0 + kNu) / (7.0 + 6.0 * kNu); }

// Smaller root ω_n [rad/s] of the Timoshenko quadratic for mode n (see the file comment).
double AnalyticOmega(int n) {
  const double G = kE / (2.0 * (1.0 + kNu)), kappa = Kappa();
  const double A = M_PI * kD * kD / 4.0, I = M_PI * std::pow(kD, 4) / 64.0;
  const double k = n * M_PI / kL;
  const double a = kRho * kRho * I / (kappa * G);
  const double b = kRho * A + kRho * I * k * k * (1.0 + kE / (kappa * G));
  const double c = kE * I * std::pow(k, 4);
  // Smaller root of a x² − b x + c = 0 in the cancellation-free form 2c / (b + √(b² − 4ac)).
  const double omega2 = 2.0 * c / (b + std::sqrt(b * b - 4.0 * a * c));
  return std::sqrt(omega2);
}

// Euler–Bernoulli ω_n = (nπ/L)² √(EI/(ρA)) (the same beam without shear deformation and rotary
// inertia).
double EulerBernoulliOmega(int n) {
  const double A = M_PI * kD * kD / 4.0, I = M_PI * std::pow(kD, 4) / 64.0;
  return std::pow(n * M_PI / kL, 2) * std::sqrt(kE * I / (kRho * A));
}

// N shaft elements along Z (node bodies carry no mass of their own), restricted to the bending
// plane (x, θy) with x held at both ends: the simply supported beam in that plane.
SystemModel MakeSimplySupportedBeam(int num_elements, bool timoshenko = true) {
  const double h = kL / num_elements;
  SystemBuilder b;
  std::vector<BodyIndex> nodes;
  for (int i = 0; i <= num_elements; ++i) {
    nodes.push_back(b.AddBody("n" + std::to_string(i), Matrix6::Zero(), Vector3(0.0, 0.0, i * h)));
  }
  ShaftBeam beam;
  beam.section.outer_diameter = kD;
  beam.material = ShaftMaterial::FromPoissonRatio(kE, kNu, kRho);
  beam.shear_coefficient = Kappa();
  beam.shear_deformation = timoshenko;
  beam.rotary_inertia = timoshenko;
  beam.node_b = Vector3(0.0, 0.0, h);
  const MatrixX K = CalcShaftBeamStiffness(beam), M = CalcShaftBeamMass(beam);
  for (int i = 0; i < num_elements; ++i) {
    b.AddElement("shaft" + std::to_string(i), ElementKind::kShaft, {nodes[i], nodes[i + 1]}, K,
                 MatrixX(), M);
  }
  const SystemModel full = b.Build();
  std::vector<int> kept;
  for (int i = 0; i <= num_elements; ++i) {
    if (i > 0 && i < num_elements) kept.push_back(full.dof_map().dof(nodes[i], BodyDof::kX));
    kept.push_back(full.dof_map().dof(nodes[i], BodyDof::kThetaY));
  }
  return full.Restrict(kept);
}

ModalResult Modes(const SystemModel& model, ModalMethod method) {
  ModalOptions options;
  options.method = method;
  options.num_modes = 2 * kNumChecked;
  const ModalResult r = ComputeModes(model, options);
  EXPECT_TRUE(r.summary.ok()) << r.summary.BriefReport();
  EXPECT_EQ(r.num_rigid_body_modes, 0);
  return r;
}

// Relative errors |ω_h/ω − 1| of the first kNumChecked modes, for 4, 8, 16, 32 elements.
std::vector<std::vector<double>> Errors(bool timoshenko, double (*analytic)(int)) {
  std::vector<std::vector<double>> errors;  // [refinement][mode]
  for (const int n : {4, 8, 16, 32}) {
    const ModalResult r = Modes(MakeSimplySupportedBeam(n, timoshenko), ModalMethod::kDense);
    std::vector<double> e;
    for (int mode = 1; mode <= kNumChecked; ++mode) {
      const double omega = 2.0 * M_PI * r.frequencies_hz(mode - 1);
      e.push_back(omega / analytic(mode) - 1.0);
    }
    errors.push_back(e);
  }
  return errors;
}

TEST(ModalTimoshenkoTest, SimplySupportedBeamConvergesToTheAnalyticFrequencies) {
  // The corrections are large here: Timoshenko's ω_3 lies ≈ 10 % below Euler–Bernoulli's, far
  // above the discretization errors below.
  EXPECT_LT(AnalyticOmega(3), 0.92 * EulerBernoulliOmega(3));
  const std::vector<std::vector<double>> e = Errors(true, &AnalyticOmega);
  for (int mode = 0; mode < kNumChecked; ++mode) {
    // The interdependent-interpolation element carries a constant shear force per element, so the
    // shear strain of a vibrating beam (linear along an element) is represented to O(h) and the
    // frequencies converge from above as O(h²): halving h divides the error by ≈ 4 (3.5 asked).
    for (std::size_t level = 1; level < e.size(); ++level) {
      EXPECT_GT(e[level][mode], 0.0) << "mode " << mode + 1;  // Rayleigh–Ritz: from above
      EXPECT_GT(e[level - 1][mode] / e[level][mode], 3.5)
          << "mode " << mode + 1 << " refinement " << level;
    }
    // The limit is the analytic frequency: Richardson extrapolation of the O(h²) term from 16 and
    // 32 elements, ω ≈ (4 ω_32 − ω_16)/3, removes the leading error (≥ 50× smaller than e_32).
    const double extrapolated = (4.0 * e[3][mode] - e[2][mode]) / 3.0;
    EXPECT_LT(std::abs(extrapolated), 2e-2 * e[3][mode]) << "mode " << mode + 1;
    EXPECT_LT(e[3][mode], 4e-3) << "mode " << mode + 1;
  }
}

TEST(ModalTimoshenkoTest, EulerBernoulliLimitConvergesAtFourthOrder) {
  // Without shear deformation and rotary inertia the element is the Hermite cubic with consistent
  // mass: frequencies converge as O(h⁴) (halving h divides the error by ≈ 16; 12 asked) to
  // (nπ/L)² √(EI/(ρA)).
  const std::vector<std::vector<double>> e = Errors(false, &EulerBernoulliOmega);
  for (int mode = 0; mode < kNumChecked; ++mode) {
    for (std::size_t level = 1; level < e.size(); ++level) {
      if (e[level - 1][mode] > 1e-11) {
        EXPECT_GT(e[level - 1][mode] / e[level][mode], 12.0)
            << "mode " << mode + 1 << " refinement " << level;
      }
    }
    EXPECT_LT(std::abs(e[3][mode]), 2e-5) << "mode " << mode + 1;
  }
}

TEST(ModalTimoshenkoTest, ArpackEqualsDenseOnTheBeam) {
  const SystemModel model = MakeSimplySupportedBeam(64);  // 128 DOFs
  const ModalResult dense = Modes(model, ModalMethod::kDense);
  const ModalResult arpack = Modes(model, ModalMethod::kArpack);
  ASSERT_EQ(arpack.method_used, ModalMethod::kArpack);
  ASSERT_EQ(dense.eigenvalues.size(), arpack.eigenvalues.size());
  for (Eigen::Index k = 0; k < dense.eigenvalues.size(); ++k) {
    // Both solve the same pencil; the dense reference is accurate to ≈ ε λ_max/λ_k ≈ 1e-9 here.
    EXPECT_NEAR(arpack.eigenvalues(k) / dense.eigenvalues(k), 1.0, 1e-8) << "mode " << k;
  }
  // And the O(h²) error at 64 elements is a quarter of the 32-element one (< 4e-3 / 4).
  for (int mode = 1; mode <= kNumChecked; ++mode) {
    EXPECT_NEAR(2.0 * M_PI * arpack.frequencies_hz(mode - 1) / AnalyticOmega(mode), 1.0, 1e-3);
  }
}

}  // namespace
}  // namespace geardyn
