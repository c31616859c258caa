// Campbell diagram with gyroscopic and carrier-frame terms (campbell.hpp, speed_terms.hpp), against
// closed forms and invariants:
// * a gear on an isotropic support, decoupled from its mesh (torsional mesh level), whirls at the
//   roots of I_d ω² ∓ J Ω ω − k_t = 0 (forward and backward whirl of a spinning disc) in the fixed
//   frame, and its translations stay at √(k/m);
// * in a rotating carrier frame every inertial frequency ω_I of a decoupled central member appears
//   at |ω_I − Ω_c| (the frame shift): the sun's translations at |√(k/m) ∓ Ω_c| and its tilts at
//   the whirl roots shifted by Ω_c;
// * zero speed gives ComputeModes' frequencies (the symmetric solver);
// * the undamped gyroscopic system is stable while K̄ + s²K_2 is positive definite (gyroscopic
//   stability theorem), and a frequency reaches zero where K̄ + s²K_2 becomes singular (computed
//   here independently, from det = 0 on the full matrices);
// * a repeated pair splits at first order by s|φ₁ᵀG₁φ₂|/2π (degenerate perturbation theory with
//   ComputeModes' shapes);
// * cyclic symmetry (Cooley & Parker 2012): the rotating-carrier modes keep their planetary types;
//   with 5 planets the translational pairs split, the planet-mode pairs (central members at rest,
//   every planet the same equation) keep their multiplicity N − 3, rotational modes stay single.
#include "geardyn/analyses/campbell.hpp"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "geardyn/analyses/mean_system.hpp"
#include "geardyn/analyses/modal.hpp"
#include "geardyn/common/errors.hpp"
#include "geardyn/common/units.hpp"
#include "geardyn/models/scene/scene_reader.hpp"
#include "geardyn/models/system/scene_system.hpp"
#include "geardyn/models/system/speed_terms.hpp"
#include "models/system/planetary_scene.hpp"

namespace geardyn {
namespace {

struct Built {
  Scene scene;
  SceneSystem system;
  CampbellProblem problem;
  SpeedTerms terms;
};

Built Build(const std::string& text, bool undamped = true, SpeedTermsOptions terms_options = {}) {
  Built b{ParseScene(text, "t.toml"), {}, {}, {}};
  SceneSystemOptions options;
  options.transmission_error = false;
  b.system = BuildSceneSystem(b.scene, options);
  const MeanSystemMatrices mean = AssembleMeanSystemMatrices(b.system.model);
  b.problem.mass = MatrixX(mean.mass);
  b.problem.stiffness = MatrixX(mean.stiffness);
  b.problem.damping =
      undamped ? MatrixX::Zero(b.problem.mass.rows(), b.problem.mass.cols()) : MatrixX(mean.damping);
  b.terms = BuildSpeedTerms(b.scene, b.system, b.problem.stiffness, MatrixX(mean.damping),
                            terms_options);
  b.problem.gyroscopic = b.terms.gyroscopic;
  b.problem.speed_stiffness = b.terms.stiffness;
  b.problem.dofs = b.system.model.dof_map();
  return b;
}

std::vector<double> FrequenciesAt(const CampbellResult& r, std::size_t speed) {
  std::vector<double> f;
  for (const CampbellTrack& t : r.tracks) f.push_back(t.frequency_hz[speed]);
  std::sort(f.begin(), f.end());
  return f;
}

// The nearest value of `list` to `x`.
double Nearest(const std::vector<double>& list, double x) {
  double best = list.front();
  for (double v : list) {
    if (std::abs(v - x) < std::abs(best - x)) best = v;
  }
  return best;
}

// Two gears meshing through a torsional-level mesh (θz only), each on an isotropic support: the
// translations and tilts of each gear are isolated bodies on springs.
std::string DiscPairScene() {
  return R"(
[[gear]]
name = "pinion"
teeth = 20
normal_module = 0.003
face_width = 0.03
mass = 2.0
inertia = 4e-3
transverse_inertia = 2.5e-3

[[gear]]
name = "wheel"
teeth = 40
normal_module = 0.003
face_width = 0.03
mass = 6.0
inertia = 5e-2
transverse_inertia = 2.6e-2

[[mesh]]
pinion = "pinion"
gear = "wheel"
model = "torsional"

[[bearing]]
body = "pinion"
stiffness = [2e8, 2e8, 1e8, 4e5, 4e5, 0]

[[bearing]]
body = "wheel"
stiffness = [5e8, 5e8, 3e8, 3e6, 3e6, 1e5]

[operating_point]
body = "pinion"
speed_rpm = 3000
torque = 50
)";
}

// Roots ω > 0 of I_d ω² − J Ω ω − k = 0 and of I_d ω² + J Ω ω − k = 0 (forward, backward whirl of
// a disc spinning at Ω > 0 in the inertial frame; both signs of ω of the first: ω_f and −ω_b).
std::pair<double, double> Whirl(double i_d, double j, double omega, double k) {
  const double root = std::sqrt(j * j * omega * omega + 4.0 * i_d * k);
  return {(j * omega + root) / (2.0 * i_d), (-j * omega + root) / (2.0 * i_d)};
}

TEST(CampbellTest, SpinningGearsWhirlAtTheClosedFormFrequencies) {
  Built b = Build(DiscPairScene());
  CampbellOptions options;
  options.speeds = {0.0, 500.0, 2000.0, 8000.0};  // pinion [rad/s]
  const CampbellResult r = ComputeCampbell(b.problem, options);
  ASSERT_TRUE(r.summary.ok()) << r.summary.message;
  EXPECT_EQ(r.num_rigid_body_modes, 0);  // the wheel is held torsionally
  for (std::size_t si = 0; si < options.speeds.size(); ++si) {
    const double s = options.speeds[si];
    const std::vector<double> f = FrequenciesAt(r, si);
    // pinion Ω = s, wheel Ω = −s/2 (the whirl roots only depend on |Ω|).
    const std::vector<double> want = {
        Whirl(2.5e-3, 4e-3, s, 4e5).first,  Whirl(2.5e-3, 4e-3, s, 4e5).second,
        Whirl(2.6e-2, 5e-2, s / 2, 3e6).first, Whirl(2.6e-2, 5e-2, s / 2, 3e6).second,
        std::sqrt(2e8 / 2.0),                std::sqrt(5e8 / 6.0)};
    for (double w : want) {
      const double hz = w / (2.0 * kPi);
      EXPECT_NEAR(Nearest(f, hz), hz, 1e-8 * hz) << "s = " << s;
    }
    // No growth: the undamped gyroscopic system with K̄ + s²K₂ > 0 stays on the imaginary axis.
    for (const CampbellTrack& t : r.tracks) EXPECT_FALSE(t.unstable[si]);
  }
  EXPECT_TRUE(r.instabilities.empty());
  EXPECT_TRUE(r.static_critical_speeds.empty());  // spin terms add no stiffness without a frame
}

TEST(CampbellTest, ZeroSpeedIsTheModesOfTheSymmetricSolver) {
  testing::PlanetaryFixture f;
  f.planets = 4;
  Built b = Build(testing::PlanetarySceneText(f), /*undamped=*/true);
  CampbellOptions options;
  options.speeds = {0.0, 100.0};
  const CampbellResult r = ComputeCampbell(b.problem, options);
  ASSERT_TRUE(r.summary.ok()) << r.summary.message;
  ModalOptions modal;
  modal.method = ModalMethod::kDense;
  const ModalResult modes = ComputeModes(b.system.model, modal);
  ASSERT_EQ(r.tracks.size(), static_cast<std::size_t>(modes.frequencies_hz.size()));
  const std::vector<double> f0 = FrequenciesAt(r, 0);
  for (Eigen::Index k = 0; k < modes.frequencies_hz.size(); ++k) {
    EXPECT_NEAR(f0[static_cast<std::size_t>(k)], modes.frequencies_hz[k],
                1e-9 * modes.frequencies_hz[k]);
  }
}

TEST(CampbellTest, RotatingCarrierShiftsTheDecoupledSunByTheCarrierSpeed) {
  testing::PlanetaryFixture f;
  f.planets = 3;
  f.model = "torsional";  // the meshes act on θz only: the sun's x, y, θx, θy are isolated
  Built b = Build(testing::PlanetarySceneText(f));
  Scene unit = b.scene;
  unit.operating_point.speed = 1.0;
  const double a_c = unit.GearSpeed("carrier");  // Ω_c / Ω_sun = z_s/(z_s + z_r) = 1/3
  EXPECT_NEAR(a_c, 40.0 / 120.0, 1e-12);
  ASSERT_EQ(b.terms.carrier_speed_factors.size(), 1u);
  CampbellOptions options;
  options.speeds = {0.0, 300.0, 1500.0, 3000.0};  // sun [rad/s]
  const CampbellResult r = ComputeCampbell(b.problem, options);
  ASSERT_TRUE(r.summary.ok()) << r.summary.message;
  for (std::size_t si = 0; si < options.speeds.size(); ++si) {
    const double s = options.speeds[si];
    const double omega_c = a_c * s;
    const std::vector<double> hz_list = FrequenciesAt(r, si);
    const double wn = std::sqrt(5e7 / 1.0);  // sun translation
    const auto [wf, wb] = Whirl(5e-4, 8e-4, s, 5e5);  // sun tilt, inertial frame
    // Inertial frequencies +ω (forward) and −ω (backward) seen from the carrier: |ω_I − Ω_c|.
    for (double w : {std::abs(wn - omega_c), wn + omega_c, std::abs(wf - omega_c), wb + omega_c}) {
      const double hz = w / (2.0 * kPi);
      EXPECT_NEAR(Nearest(hz_list, hz), hz, 1e-8 * wn / (2.0 * kPi)) << "s = " << s;
    }
  }
}

TEST(CampbellTest, RepeatedPairSplitsAtFirstOrderByTheGyroscopicCoupling) {
  testing::PlanetaryFixture f;
  f.planets = 4;
  Built b = Build(testing::PlanetarySceneText(f));
  ModalOptions modal;
  modal.method = ModalMethod::kDense;
  modal.compute_shapes = true;
  modal.multiplicity_rel_tol = 1e-7;
  const ModalResult modes = ComputeModes(b.system.model, modal);
  const double s = 1.0;  // sun [rad/s]: small enough for first order (splits of ~1e-4 Hz)
  CampbellOptions options;
  options.speeds = {0.0, s};
  const CampbellResult r = ComputeCampbell(b.problem, options);
  ASSERT_TRUE(r.summary.ok());
  int checked = 0;
  for (const std::vector<int>& group : modes.multiplicity_groups) {
    if (group.size() != 2) continue;
    const VectorX p1 = modes.shapes.col(group[0]);
    const VectorX p2 = modes.shapes.col(group[1]);
    const double g = p1.dot(b.terms.gyroscopic * p2);
    const double f0 = modes.frequencies_hz[group[0]];
    const double split_hz = s * std::abs(g) / (2.0 * kPi);
    // The two tracks that start at f0.
    std::vector<double> at_s;
    for (const CampbellTrack& t : r.tracks) {
      if (std::abs(t.frequency_hz[0] - f0) <= 1e-6 * f0) at_s.push_back(t.frequency_hz[1]);
    }
    ASSERT_EQ(at_s.size(), 2u) << "f0 = " << f0;
    const double measured = std::abs(at_s[1] - at_s[0]);
    EXPECT_NEAR(measured, split_hz, 1e-3 * split_hz + 1e-9 * f0) << "f0 = " << f0;
    if (split_hz > 1e-7 * f0) ++checked;
  }
  EXPECT_GE(checked, 6);  // the translational pairs of a 4-planet set split
}

// The smallest s > 0 with K̄ + s² K₂ singular on the elastic subspace (an independent route:
// generalized eigenvalues of (−K₂, K̄) by Eigen's GeneralizedSelfAdjointEigenSolver on the full
// matrices, which are both symmetric and K̄ > 0 here).
double FirstSingularSpeed(const MatrixX& k_bar, const MatrixX& k2) {
  const Eigen::GeneralizedSelfAdjointEigenSolver<MatrixX> solver(-k2, k_bar);
  const double mu = solver.eigenvalues().maxCoeff();  // −K₂ v = μ K̄ v, s² = 1/μ
  return mu > 0.0 ? 1.0 / std::sqrt(mu) : 0.0;
}

TEST(CampbellTest, DivergenceWhereTheEffectiveStiffnessBecomesSingular) {
  // Soft supports and a fast carrier: the centripetal softening −m Ω_c² beats the sun's support.
  testing::PlanetaryFixture f;
  f.planets = 3;
  Built b = Build(testing::PlanetarySceneText(f));
  const double s_d = FirstSingularSpeed(b.problem.stiffness, b.problem.speed_stiffness);
  ASSERT_GT(s_d, 0.0);
  CampbellOptions options;
  for (int i = 0; i <= 60; ++i) options.speeds.push_back(s_d * (0.5 + 0.01 * i));  // 0.5 … 1.1
  const CampbellResult r = ComputeCampbell(b.problem, options);
  ASSERT_TRUE(r.summary.ok()) << r.summary.message;
  ASSERT_FALSE(r.static_critical_speeds.empty());
  EXPECT_NEAR(r.static_critical_speeds.front(), s_d, 1e-8 * s_d);
  // Below s_d: no growth anywhere (K_eff > 0).
  for (std::size_t si = 0; options.speeds[si] < 0.999 * s_d; ++si) {
    for (const CampbellTrack& t : r.tracks) EXPECT_FALSE(t.unstable[si]) << options.speeds[si];
  }
  // The lowest frequency falls to zero at s_d: its minimum over the grid is at the grid point
  // nearest s_d, and close to zero relative to its value at 0.5 s_d.
  double lowest_at_half = 1e300;
  for (const CampbellTrack& t : r.tracks) lowest_at_half = std::min(lowest_at_half, t.frequency_hz[0]);
  const std::size_t at_sd = 50;  // speeds[50] = s_d
  double lowest_at_sd = 1e300;
  for (const CampbellTrack& t : r.tracks) lowest_at_sd = std::min(lowest_at_sd, t.frequency_hz[at_sd]);
  EXPECT_LT(lowest_at_sd, 1e-3 * lowest_at_half);
  // Just above: a real positive eigenvalue (divergence) reported as an instability run, or
  // gyroscopic stabilization — the eigenvalues decide; with one negative eigenvalue of K_eff
  // (odd count) the system must diverge.
  const MatrixX k_eff = b.problem.stiffness + std::pow(1.05 * s_d, 2) * b.problem.speed_stiffness;
  const Eigen::SelfAdjointEigenSolver<MatrixX> keff(k_eff, Eigen::EigenvaluesOnly);
  const int negative = static_cast<int>((keff.eigenvalues().array() < 0.0).count());
  if (negative % 2 == 1) {
    ASSERT_FALSE(r.instabilities.empty());
    EXPECT_EQ(r.instabilities.front().kind, "divergence");
    EXPECT_GE(r.instabilities.front().speed_begin, s_d * 0.999);
    EXPECT_LE(r.instabilities.front().speed_begin, s_d * 1.02);
  }
}

TEST(CampbellTest, CarrierFrameKeepsCyclicModeTypesAndSplitsConjugatePairs) {
  testing::PlanetaryFixture f;
  f.planets = 5;
  f.planar = true;  // Lin & Parker's planar model (x, y, θz)
  Built b = Build(testing::PlanetarySceneText(f));
  CampbellOptions options;
  options.speeds = {0.0, 200.0, 400.0};  // sun [rad/s]; carrier 1/3 of it
  const CampbellResult r = ComputeCampbell(b.problem, options);
  ASSERT_TRUE(r.summary.ok()) << r.summary.message;
  int translational = 0;
  int planet = 0;
  int rotational = 0;
  for (std::size_t a = 0; a < r.tracks.size(); ++a) {
    const CampbellTrack& t = r.tracks[a];
    ASSERT_EQ(t.planetary_labels.size(), 3u);
    // Cooley & Parker: the mode types survive the gyroscopic terms.
    EXPECT_EQ(t.planetary_labels[2], t.planetary_labels[0]) << "track " << a;
    // Its partner at zero speed (the same frequency), if any.
    int partner = -1;
    for (std::size_t c = 0; c < r.tracks.size(); ++c) {
      if (c != a && std::abs(r.tracks[c].frequency_hz[0] - t.frequency_hz[0]) <=
                        1e-7 * t.frequency_hz[0]) {
        partner = static_cast<int>(c);
      }
    }
    const PlanetaryModeType type = t.planetary_labels[0];
    if (type == PlanetaryModeType::kRotational) {
      ++rotational;
      EXPECT_EQ(partner, -1);
    } else {
      ASSERT_GE(partner, 0) << "track " << a << " " << ToString(type);
      const double split =
          std::abs(t.frequency_hz[2] - r.tracks[static_cast<std::size_t>(partner)].frequency_hz[2]);
      if (type == PlanetaryModeType::kPlanet) {
        // Central members at rest: every planet obeys the same equation (its bearing and meshes
        // against fixed central members, the same Coriolis term), so the N − 3 combinations keep
        // one frequency at any carrier speed.
        EXPECT_LT(split, 1e-9 * t.frequency_hz[0]) << "planet mode at " << t.frequency_hz[0];
        ++planet;
      } else {
        // k = ±1 pairs: the Coriolis coupling of the central members' x and y splits them.
        EXPECT_GT(split, 1e-4 * t.frequency_hz[0]) << ToString(type) << " at " << t.frequency_hz[0];
        ++translational;
      }
    }
  }
  // Lin & Parker's planar structure: 6 rotational, 6 translational pairs, 3 planet frequencies of
  // multiplicity N − 3 = 2.
  EXPECT_EQ(rotational, 6);
  EXPECT_EQ(translational, 12);
  EXPECT_EQ(planet, 6);
}

TEST(CampbellTest, RejectsAnisotropicSupportsAndLateralCouplingOutOfARotatingSet) {
  testing::PlanetaryFixture f;
  f.extra = "";
  std::string text = testing::PlanetarySceneText(f);
  const std::string iso = "stiffness = [5e7, 5e7, 1e8";
  text.replace(text.find(iso), iso.size(), "stiffness = [5e7, 6e7, 1e8");
  try {
    Build(text);
    FAIL() << "anisotropic sun support accepted";
  } catch (const InvalidInput& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("sun-support"), std::string::npos) << what;
    EXPECT_NE(what.find("isotropic"), std::string::npos) << what;
  }
  // The same scene without carrier-frame terms is accepted (the check is the frame's).
  SpeedTermsOptions fixed_frame;
  fixed_frame.carrier_frame = false;
  EXPECT_NO_THROW(Build(text, true, fixed_frame));
  // A fixed carrier (star arrangement): no frame terms, no check.
  testing::PlanetaryFixture star;
  star.fixed = "carrier";
  std::string star_text = testing::PlanetarySceneText(star);
  star_text.replace(star_text.find(iso), iso.size(), "stiffness = [5e7, 6e7, 1e8");
  EXPECT_NO_THROW(Build(star_text));
}

TEST(CampbellTest, CarrierSpeedFactorNeedsARotatingCarrier) {
  EXPECT_THROW(CarrierSpeedFactor(ParseScene(DiscPairScene(), "t.toml")), InvalidInput);
  testing::PlanetaryFixture star;
  star.fixed = "carrier";
  EXPECT_THROW(CarrierSpeedFactor(ParseScene(testing::PlanetarySceneText(star), "t.toml")),
               InvalidInput);
  testing::PlanetaryFixture f;
  EXPECT_NEAR(CarrierSpeedFactor(ParseScene(testing::PlanetarySceneText(f), "t.toml")), 1.0 / 3.0,
              1e-12);
}

TEST(CampbellTest, RejectsBadOptions) {
  Built b = Build(DiscPairScene());
  CampbellOptions options;
  EXPECT_THROW(ComputeCampbell(b.problem, options), InvalidInput);  // no speeds
  options.speeds = {0.0, 0.0};
  EXPECT_THROW(ComputeCampbell(b.problem, options), InvalidInput);  // not increasing
  options.speeds = {-1.0, 1.0};
  EXPECT_THROW(ComputeCampbell(b.problem, options), InvalidInput);
  options.speeds = {0.0, std::nan("")};
  EXPECT_THROW(ComputeCampbell(b.problem, options), InvalidInput);
}

}  // namespace
}  // namespace geardyn
