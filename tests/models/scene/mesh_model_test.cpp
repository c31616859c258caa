#include "geardyn/models/scene/mesh_model.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numeric>
#include <string>
#include <variant>
#include <vector>

#include "geardyn/common/units.hpp"
#include "geardyn/models/gear/iso_stiffness.hpp"
#include "geardyn/models/mesh/transmission_error.hpp"
#include "geardyn/models/scene/builtin_scenes.hpp"
#include "geardyn/models/scene/scene.hpp"
#include "geardyn/models/scene/scene_reader.hpp"
#include "support/expect_throws.hpp"

namespace geardyn {
namespace {

// Tolerances: the same computation by two routes (bitwise equal in practice); a few products.
constexpr double kSameRouteTol = 1e-14;
constexpr double kProductTol = 1e-12;  // relative; sums and products of a few series terms

// A spur pair 20/40, m = 2 mm, b = 20 mm; `mesh_extra` is appended to its [[mesh]] table and
// `after_mesh` follows it (sub-tables such as [mesh.modifications]).
std::string Pair(const std::string& mesh_extra = "", const std::string& after_mesh = "",
                 int wheel_teeth = 40) {
  return R"(title = "mesh model test"

[[gear]]
name = "pinion"
teeth = 20
normal_module = 0.002
face_width = 0.02
mass = 0.5
inertia = 1e-4

[[gear]]
name = "wheel"
teeth = )" +
         std::to_string(wheel_teeth) + R"(
normal_module = 0.002
face_width = 0.02
mass = 2.0
inertia = 1.6e-3

[[mesh]]
pinion = "pinion"
gear = "wheel"
)" + mesh_extra +
         "\n" + after_mesh + R"(

[operating_point]
speed_rpm = 3000
torque = 50
)";
}

Scene Parse(const std::string& text, const std::vector<std::string>& overrides = {}) {
  return ParseScene(text, "t.toml", overrides);
}

const LinearMeshCore& Linear(const BuiltMeshCore& built) {
  return std::get<LinearMeshCore>(built.core);
}

double MaxAbs(const MatrixX& m) { return m.cwiseAbs().maxCoeff(); }

// --- reading the keys -------------------------------------------------------------------------

TEST(MeshModelReaderTest, DefaultsWhenNoModelKeyIsGiven) {
  const Scene s = Parse(Pair());
  const MeshModelDef& m = s.meshes[0].model;
  EXPECT_EQ(m.level, MeshModelLevel::kBlankenshipSingh);
  EXPECT_FALSE(m.stiffness_per_length.has_value());
  EXPECT_EQ(m.damping.kind, MeshDamping::Kind::kNone);
  EXPECT_EQ(m.core_options.coefficient.form, MeshCoefficientForm::kAuto);
  EXPECT_EQ(m.core_options.coefficient.num_samples, MeshCoefficientOptions{}.num_samples);
  EXPECT_EQ(m.core_options.coefficient.rel_tol, MeshCoefficientOptions{}.rel_tol);
  EXPECT_EQ(m.core_options.num_slices, MeshCoreOptions{}.num_slices);
  EXPECT_FALSE(m.modifications.pinion_tip_relief.is_active());
  EXPECT_EQ(m.modifications.lead_crowning, 0.0);
  EXPECT_EQ(m.errors.pinion_teeth, 20);
  EXPECT_EQ(m.errors.gear_teeth, 40);
  EXPECT_TRUE(m.errors.pinion_pitch_deviations.empty());
  EXPECT_FALSE(m.parameters.has_value());
}

TEST(MeshModelReaderTest, ReadsEveryMeshKey) {
  const Scene s = Parse(Pair(R"(model = "slices"
slices = 12
stiffness_per_length = 1.5e10
damping_ratio = 0.05
coefficient_form = "fourier"
fourier_terms = 30
table_samples = 128
)"));
  const MeshModelDef& m = s.meshes[0].model;
  EXPECT_EQ(m.level, MeshModelLevel::kNonlinearSlices);
  EXPECT_EQ(m.core_options.level, MeshModelLevel::kNonlinearSlices);
  EXPECT_EQ(m.core_options.num_slices, 12);
  EXPECT_EQ(*m.stiffness_per_length, 1.5e10);
  EXPECT_EQ(m.damping.kind, MeshDamping::Kind::kRatio);
  EXPECT_EQ(m.damping.value, 0.05);
  EXPECT_EQ(m.core_options.coefficient.form, MeshCoefficientForm::kFourier);
  EXPECT_EQ(m.core_options.slices.form, MeshCoefficientForm::kFourier);
  EXPECT_EQ(m.core_options.coefficient.num_terms, 30);
  EXPECT_EQ(m.core_options.slices.num_terms, 30);
  EXPECT_EQ(m.core_options.coefficient.num_samples, 128);
  EXPECT_EQ(m.core_options.slices.num_samples, 128);

  const Scene t = Parse(Pair("damping = 250\nfourier_tolerance = 1e-3\n"));
  EXPECT_EQ(t.meshes[0].model.damping.kind, MeshDamping::Kind::kCoefficient);
  EXPECT_EQ(t.meshes[0].model.damping.value, 250.0);  // N s/m
  EXPECT_EQ(t.meshes[0].model.core_options.coefficient.rel_tol, 1e-3);
}

TEST(MeshModelReaderTest, EveryLevelNameParses) {
  for (const MeshModelLevel level :
       {MeshModelLevel::kBlankenshipSingh, MeshModelLevel::kCoupling4Dof, MeshModelLevel::kMeanLti,
        MeshModelLevel::kTorsional, MeshModelLevel::kNonlinearSlices}) {
    const Scene s = Parse(Pair(std::string("model = \"") + ToString(level) + "\"\n"));
    EXPECT_EQ(s.meshes[0].model.level, level) << ToString(level);
  }
}

TEST(MeshModelReaderTest, ReadsModificationsAndErrorsWithUnits) {
  std::string pitch = "[";
  for (int i = 0; i < 20; ++i) pitch += (i > 0 ? ", " : "") + std::string(i % 2 ? "-2e-6" : "2e-6");
  pitch += "]";
  const Scene s = Parse(Pair("", R"([mesh.modifications]
pinion_tip_relief = 2e-5
pinion_tip_relief_length = 2e-3
gear_tip_relief = 1.5e-5
gear_tip_relief_length = 1.8e-3
pinion_root_relief = 1e-5
pinion_root_relief_length = 1e-3
gear_root_relief = 0.5e-5
gear_root_relief_length = 0.8e-3
relief_shape = "parabolic"
lead_crowning = 5e-6
lead_slope = -3e-6

[mesh.errors]
pinion_pitch_deviations = )" + pitch +
                                     R"(
pinion_runout = 1e-5
pinion_runout_phase_deg = 90
gear_runout = 2e-5
gear_runout_phase_deg = -45
)"));
  const ToothModifications& m = s.meshes[0].model.modifications;
  EXPECT_EQ(m.pinion_tip_relief.amount, 2e-5);
  EXPECT_EQ(m.pinion_tip_relief.length, 2e-3);
  EXPECT_EQ(m.pinion_tip_relief.shape, ReliefShape::kParabolic);
  EXPECT_EQ(m.gear_tip_relief.amount, 1.5e-5);
  EXPECT_EQ(m.gear_tip_relief.length, 1.8e-3);
  EXPECT_EQ(m.pinion_root_relief.amount, 1e-5);
  EXPECT_EQ(m.pinion_root_relief.length, 1e-3);
  EXPECT_EQ(m.gear_root_relief.amount, 0.5e-5);
  EXPECT_EQ(m.gear_root_relief.length, 0.8e-3);
  EXPECT_EQ(m.gear_root_relief.shape, ReliefShape::kParabolic);
  EXPECT_EQ(m.lead_crowning, 5e-6);
  EXPECT_EQ(m.lead_slope, -3e-6);
  const ToothErrors& e = s.meshes[0].model.errors;
  ASSERT_EQ(e.pinion_pitch_deviations.size(), 20u);
  EXPECT_EQ(e.pinion_pitch_deviations[1], -2e-6);
  EXPECT_TRUE(e.gear_pitch_deviations.empty());
  EXPECT_EQ(e.pinion_runout, 1e-5);
  EXPECT_NEAR(e.pinion_runout_phase, 0.5 * kPi, 1e-15);  // degrees → rad
  EXPECT_EQ(e.gear_runout, 2e-5);
  EXPECT_NEAR(e.gear_runout_phase, -0.25 * kPi, 1e-15);
}

TEST(MeshModelReaderTest, InlineSubTablesWork) {
  const Scene s =
      Parse(Pair("modifications = { lead_crowning = 4e-6 }\n"
                 "errors = { gear_runout = 1e-5, gear_runout_phase_deg = 180 }\n"));
  EXPECT_EQ(s.meshes[0].model.modifications.lead_crowning, 4e-6);
  EXPECT_NEAR(s.meshes[0].model.errors.gear_runout_phase, kPi, 1e-15);
}

TEST(MeshModelReaderTest, OverridesReachTheNewKeys) {
  const Scene s =
      Parse(Pair(), {"mesh.pinion-wheel.model=coupling_4dof",
                     "mesh.pinion-wheel.modifications.lead_crowning=5e-6",
                     "mesh.pinion-wheel.errors.gear_runout=1e-5",
                     "mesh.pinion-wheel.damping_ratio=0.07", "mesh.0.table_samples=64"});
  const MeshModelDef& m = s.meshes[0].model;
  EXPECT_EQ(m.level, MeshModelLevel::kCoupling4Dof);
  EXPECT_EQ(m.modifications.lead_crowning, 5e-6);
  EXPECT_EQ(m.errors.gear_runout, 1e-5);
  EXPECT_EQ(m.damping.value, 0.07);
  EXPECT_EQ(m.core_options.coefficient.num_samples, 64);

  const Scene p = Parse(Pair(), {"mesh.pinion-wheel.parameters={form=\"table\", "
                                 "stiffness=[3e8, 4e8], mu=[0.4, 0.5]}",
                                 "mesh.pinion-wheel.parameters.load_centre=[0.001, -0.001]"});
  ASSERT_TRUE(p.meshes[0].model.parameters.has_value());
  const auto& table = std::get<TableCoefficient>(p.meshes[0].model.parameters->stiffness);
  EXPECT_EQ(table.samples()(1, 0), 3e8 * 0.001);  // K·h
  // A modification key overridden into a model with user parameters is rejected.
  EXPECT_THROWS_MESSAGE(Parse(Pair("parameters = { form = \"table\", stiffness = [3e8] }\n"),
                              {"mesh.pinion-wheel.modifications.lead_crowning=5e-6"}),
                        SceneError,
                        R"(^t\.toml: --set mesh\.pinion-wheel\.modifications\.lead_crowning=5e-6: )"
                        R"(mesh\.pinion-wheel\.modifications: not used with \[mesh\.parameters\])");
}

// --- user parameters ----------------------------------------------------------------------------

TEST(MeshModelReaderTest, UserTableBecomesTheChannels) {
  const Scene s = Parse(Pair("", R"([mesh.parameters]
form = "table"
stiffness = [3e8, 4e8, 5e8]
load_centre = [0.0, 1e-3, -2e-3]
mu = [0.4, 0.5, 0.6]
te_eta = [1e-6, 2e-6, 3e-6]
)"));
  const UserMeshParameters& p = *s.meshes[0].model.parameters;
  const double b = 0.01;
  const auto& k = std::get<TableCoefficient>(p.stiffness);
  ASSERT_EQ(k.num_samples(), 3);
  EXPECT_EQ(k.samples()(0, 2), 5e8);
  EXPECT_NEAR(k.samples()(1, 1), 4e8 * 1e-3, 1e-9);
  EXPECT_NEAR(k.samples()(2, 2), 5e8 * 0.6 * b * b, 1e-9);
  const auto& te = std::get<TableCoefficient>(*p.transmission_error);
  EXPECT_EQ(te.samples()(0, 1), 2e-6);
  EXPECT_EQ(te.samples()(1, 1), 0.0);  // ε_ζ defaults to 0
}

TEST(MeshModelReaderTest, UserFourierProductsAreExact) {
  // K = K0 + a1 cos θ + b1 sin θ + a2 cos 2θ, h likewise; μ defaults to κ² + 1/3.
  const Scene s = Parse(Pair("", R"([mesh.parameters]
form = "fourier"
stiffness = [4e8, 5e7, -3e7, 1e7, 0]
load_centre = [1e-3, 2e-4, 0, 0, -1e-4]
te_zeta = [0, 1e-5, 0, 0, 0]
)"));
  const UserMeshParameters& p = *s.meshes[0].model.parameters;
  const double b = 0.01;
  const auto series = [](const std::vector<double>& v, double th) {
    return v[0] + v[1] * std::cos(th) + v[2] * std::sin(th) + v[3] * std::cos(2 * th) +
           v[4] * std::sin(2 * th);
  };
  const std::vector<double> kv = {4e8, 5e7, -3e7, 1e7, 0}, hv = {1e-3, 2e-4, 0, 0, -1e-4};
  VectorX out(3), te(2);
  for (const double th : {0.0, 0.3, 1.7, 4.0}) {
    Evaluate(p.stiffness, th, out);
    const double k = series(kv, th), h = series(hv, th);
    EXPECT_NEAR(out[0], k, kProductTol * 4e8);
    EXPECT_NEAR(out[1], k * h, kProductTol * 4e8 * 1e-3);
    EXPECT_NEAR(out[2], k * (h * h + b * b / 3.0), kProductTol * 4e8 * b * b);
    Evaluate(*p.transmission_error, th, te);
    EXPECT_NEAR(te[1], 1e-5 * std::cos(th), 1e-18);
  }
}

TEST(MeshModelReaderTest, ReadsTheTwoBlankenshipSinghForms) {
  EXPECT_EQ(Parse(Pair("model = \"bs_projected\"\n")).meshes[0].model.level,
            MeshModelLevel::kBsProjected);
  EXPECT_EQ(Parse(Pair("model = \"five_dof\"\n")).meshes[0].model.level, MeshModelLevel::kFiveDof);
  EXPECT_EQ(Parse(Pair(), {"mesh.pinion-wheel.model=five_dof"}).meshes[0].model.level,
            MeshModelLevel::kFiveDof);
  EXPECT_EQ(Parse(Pair(), {"mesh.pinion-wheel.model=bs_projected"}).meshes[0].model.level,
            MeshModelLevel::kBsProjected);
  EXPECT_THROWS_MESSAGE(Parse(Pair("model = \"five_dofs\"\n")), SceneError,
                        "unknown model 'five_dofs' \\(did you mean 'five_dof'\\?\\); models: "
                        "blankenship_singh, bs_projected, five_dof, coupling_4dof");
}

// five_dof on user tables: B–S's scalar transmission error, te_zeta dropped and te_eta kept.
TEST(BuildMeshCoreTest, FiveDofDropsTheUserRockingTransmissionError) {
  const std::string params = R"([mesh.parameters]
form = "fourier"
stiffness = [4e8, 5e7, -3e7]
load_centre = [1e-3, 2e-4, 0]
te_eta = [2e-6, 0, 1e-6]
te_zeta = [0, 1e-5, 0]
)";
  const Scene bs = Parse(Pair("", params));
  const Scene five = Parse(Pair("model = \"five_dof\"\n", params));
  const LinearMeshCore a = Linear(BuildMeshCore(bs, bs.meshes[0]));
  const LinearMeshCore b = Linear(BuildMeshCore(five, five.meshes[0]));
  EXPECT_EQ(b.level(), MeshCoreLevel::kBlankenshipSingh);
  for (const double th : {0.0, 0.3, 1.7, 4.0}) {
    EXPECT_TRUE(EvalStiffnessCore(b, th).isApprox(EvalStiffnessCore(a, th), 0.0));
    const Vector2 ea = EvalTransmissionError(a, th);
    const Vector2 eb = EvalTransmissionError(b, th);
    EXPECT_NEAR(ea[0], 2e-6 + 1e-6 * std::sin(th), 1e-18);
    EXPECT_NEAR(ea[1], 1e-5 * std::cos(th), 1e-18);
    EXPECT_EQ(eb[0], ea[0]);
    EXPECT_EQ(eb[1], 0.0);
  }
}

// --- BuildMeshCore ------------------------------------------------------------------------------

TEST(BuildMeshCoreTest, EachLevelGivesItsCore) {
  const std::vector<std::pair<std::string, MeshCoreLevel>> linear = {
      {"blankenship_singh", MeshCoreLevel::kBlankenshipSingh},
      {"bs_projected", MeshCoreLevel::kBlankenshipSingh},
      {"five_dof", MeshCoreLevel::kBlankenshipSingh},
      {"coupling_4dof", MeshCoreLevel::kCoupling4Dof},
      {"torsional", MeshCoreLevel::kTorsional},
      {"lti", MeshCoreLevel::kBlankenshipSingh}};
  for (const auto& [name, core_level] : linear) {
    const Scene s = Parse(Pair("model = \"" + name + "\"\n"));
    const BuiltMeshCore built = BuildMeshCore(s, s.meshes[0]);
    ASSERT_TRUE(std::holds_alternative<LinearMeshCore>(built.core)) << name;
    EXPECT_EQ(Linear(built).level(), core_level) << name;
    EXPECT_EQ(Linear(built).is_mean_lti(), name == "lti") << name;
    EXPECT_TRUE(built.contact_lines.has_value());
    EXPECT_EQ(Classify(built.core),
              name == "lti" ? TimeDependence::kConstant : TimeDependence::kPiecewiseConstant);
  }
  const Scene s = Parse(Pair("model = \"slices\"\nslices = 8\n"));
  const BuiltMeshCore built = BuildMeshCore(s, s.meshes[0]);
  ASSERT_TRUE(std::holds_alternative<SliceMeshCore>(built.core));
  const auto& slices = std::get<SliceMeshCore>(built.core);
  EXPECT_EQ(slices.num_slices(), 8);
  EXPECT_EQ(slices.backlash(), s.meshes[0].geometry.backlash_normal);
}

TEST(BuildMeshCoreTest, AllLevelsShareTheSameData) {
  // The slice channels sum to the B–S core's K; the 4-DOF and torsional cores keep channel K.
  const Scene bs = Parse(Pair("damping = 300\n"));
  const LinearMeshCore ref = Linear(BuildMeshCore(bs, bs.meshes[0]));
  for (const char* level : {"coupling_4dof", "torsional"}) {
    const Scene s = Parse(Pair(std::string("damping = 300\nmodel = \"") + level + "\"\n"));
    const LinearMeshCore core = Linear(BuildMeshCore(s, s.meshes[0]));
    EXPECT_TRUE(Mean(core.stiffness()).isApprox(Mean(ref.stiffness()), kSameRouteTol));
    EXPECT_EQ(core.damping().value, 300.0);
  }
  const Scene sl = Parse(Pair("damping = 300\nmodel = \"slices\"\nslices = 10\n"));
  const BuiltMeshCore built = BuildMeshCore(sl, sl.meshes[0]);
  SliceMeshWorkspace ws(std::get<SliceMeshCore>(built.core));
  for (const double th : {0.1, 2.0, 5.0}) {
    const Vector3 channels = EvalSliceChannels(std::get<SliceMeshCore>(built.core), ws, th);
    EXPECT_NEAR(channels[0], EvalStiffnessCore(ref, th)(0, 0), 1e-9 * channels[0]);
  }
}

TEST(BuildMeshCoreTest, LtvWithConstantCoefficientsEqualsLti) {
  const std::string params =
      "[mesh.parameters]\nform = \"table\"\nstiffness = [4e8, 4e8, 4e8]\n"
      "load_centre = [1e-3, 1e-3, 1e-3]\nmu = [0.5, 0.5, 0.5]\n";
  const Scene ltv = Parse(Pair("", params));
  const Scene lti = Parse(Pair("model = \"lti\"\n", params));
  const BuiltMeshCore a = BuildMeshCore(ltv, ltv.meshes[0]);
  const BuiltMeshCore b = BuildMeshCore(lti, lti.meshes[0]);
  EXPECT_EQ(Classify(a.core), TimeDependence::kConstant);  // constant samples: LTI-classified
  EXPECT_FALSE(a.contact_lines.has_value());
  EXPECT_TRUE(Linear(b).is_mean_lti());
  for (const double th : {0.0, 0.7, 3.1, 6.0}) {
    const Matrix2 ka = EvalStiffnessCore(Linear(a), th), kb = EvalStiffnessCore(Linear(b), th);
    EXPECT_LE((ka - kb).cwiseAbs().maxCoeff(), kSameRouteTol * ka.cwiseAbs().maxCoeff());
  }
  // Contact lines: the LTI core holds the exact means of the LTV core's channels.
  const Scene hel = LoadScene("builtin:helical-pair");
  const Scene hel_lti = LoadScene("builtin:helical-pair", {"mesh.pinion-wheel.model=lti"});
  const LinearMeshCore ltv_core = Linear(BuildMeshCore(hel, hel.meshes[0]));
  const LinearMeshCore lti_core = Linear(BuildMeshCore(hel_lti, hel_lti.meshes[0]));
  EXPECT_TRUE(Mean(lti_core.stiffness()).isApprox(Mean(ltv_core.stiffness()), kSameRouteTol));
  EXPECT_EQ(Classify(lti_core), TimeDependence::kConstant);
}

TEST(BuildMeshCoreTest, IsoDefaultMeanStiffnessIsCGammaAlphaTimesFaceWidth) {
  for (const char* name : {"builtin:helical-pair", "builtin:kahraman-blankenship-rig"}) {
    const Scene s = LoadScene(name);
    const MeshDef& mesh = s.meshes[0];
    IsoStiffnessOptions iso;
    iso.line_load = MeshLineLoad(s, mesh);
    ASSERT_TRUE(iso.line_load.has_value());
    const double c_gamma_alpha = CalcIsoMeshStiffness(mesh.geometry, iso).mesh_alpha;
    const LinearMeshCore core = Linear(BuildMeshCore(s, mesh));
    EXPECT_NEAR(Mean(core.stiffness())[0], c_gamma_alpha * mesh.geometry.face_width,
                1e-9 * c_gamma_alpha * mesh.geometry.face_width)
        << name;
  }
}

TEST(BuildMeshCoreTest, GivenStiffnessPerLengthTimesMeanLineLength) {
  const Scene s = Parse(Pair("stiffness_per_length = 1.2e10\n"));
  const BuiltMeshCore built = BuildMeshCore(s, s.meshes[0]);
  const double mean_length = s.meshes[0].geometry.mean_contact_line_length;  // b ε_α / cos β_b
  EXPECT_NEAR(Mean(Linear(built).stiffness())[0], 1.2e10 * mean_length, 1e-9 * 1.2e10 * 0.02);
}

TEST(BuildMeshCoreTest, MeshLineLoadFromTheOperatingPoint) {
  const Scene s = Parse(Pair());
  const GearPairGeometry& g = s.meshes[0].geometry;
  EXPECT_NEAR(*MeshLineLoad(s, s.meshes[0]), 50.0 / g.pinion.reference_radius / g.face_width, 1e-9);
  const Scene w = Parse(Pair(), {"operating_point.body=wheel", "operating_point.torque=-80"});
  EXPECT_NEAR(*MeshLineLoad(w, w.meshes[0]), 80.0 / g.gear.reference_radius / g.face_width, 1e-9);
}

TEST(BuildMeshCoreTest, DriveSignFollowsTheTransmittedTorque) {
  const Scene pos = Parse(Pair());
  EXPECT_EQ(BuildMeshCore(pos, pos.meshes[0]).drive_sign, 1);
  EXPECT_TRUE(BuildMeshCore(pos, pos.meshes[0]).warnings.empty());
  const Scene neg = Parse(Pair(), {"operating_point.torque=-50"});
  EXPECT_EQ(MeshDriveSign(neg, neg.meshes[0]), -1);
  // Reference on the wheel, positive torque: the wheel drives, the pinion turns backwards and
  // takes a positive torque T_p = -T / (Ω_p/Ω_w) = T z_p/z_w > 0.
  const Scene wheel = Parse(Pair(), {"operating_point.body=wheel"});
  EXPECT_EQ(MeshDriveSign(wheel, wheel.meshes[0]), 1);
  const Scene wheel_neg =
      Parse(Pair(), {"operating_point.body=wheel", "operating_point.torque=-5"});
  EXPECT_EQ(MeshDriveSign(wheel_neg, wheel_neg.meshes[0]), -1);
  // Zero torque: +1 with a warning.
  const Scene zero = Parse(Pair(), {"operating_point.torque=0"});
  const BuiltMeshCore z = BuildMeshCore(zero, zero.meshes[0]);
  EXPECT_EQ(z.drive_sign, 1);
  ASSERT_FALSE(z.warnings.empty());
  EXPECT_NE(z.warnings[0].find("drive sign +1 assumed"), std::string::npos) << z.warnings[0];
  // The drive sign reaches the zone of action.
  const BuiltMeshCore n = BuildMeshCore(neg, neg.meshes[0]);
  EXPECT_EQ(n.drive_sign, -1);
  EXPECT_EQ(n.contact_lines->zone().drive_sign, -1);
}

// Issue 12 (tryout): on a spur pair coefficient_form = "auto" stores the exact stiffness steps,
// so fourier_terms/fourier_tolerance cannot change the core, and table_samples cannot either
// when no transmission error is sampled; the keys were silently ignored. Truth that they have
// no effect: the core built with and without the key is the same at every θ. Each gets a warning
// naming the key; where the key does act (form "fourier"; a TE from a tip relief) none.
TEST(BuildMeshCoreTest, CoefficientKeysWithoutEffectAreWarned) {
  const auto warned = [](const BuiltMeshCore& b, const std::string& key) {
    for (const std::string& w : b.warnings) {
      if (w.find("mesh.") == 0 && w.find(key) != std::string::npos &&
          w.find("no effect") != std::string::npos) {
        return true;
      }
    }
    return false;
  };
  const Scene plain = Parse(Pair());
  const LinearMeshCore ref = Linear(BuildMeshCore(plain, plain.meshes[0]));
  for (const std::string& key :
       {std::string("fourier_terms = 12\n"), std::string("fourier_tolerance = 1e-3\n"),
        std::string("table_samples = 64\n")}) {
    const Scene s = Parse(Pair(key));
    const BuiltMeshCore b = BuildMeshCore(s, s.meshes[0]);
    for (const double th : {0.05, 1.3, 2.9, 4.4, 6.1}) {
      EXPECT_EQ(EvalStiffnessCore(Linear(b), th), EvalStiffnessCore(ref, th)) << key;
    }
    const std::string name = key.substr(0, key.find(' '));
    EXPECT_TRUE(warned(b, name)) << key;
  }
  // The keys act: a Fourier form takes fourier_terms, and a tip relief's TE is sampled at
  // table_samples per mesh cycle.
  const Scene fourier = Parse(Pair("coefficient_form = \"fourier\"\nfourier_terms = 12\n"));
  EXPECT_FALSE(warned(BuildMeshCore(fourier, fourier.meshes[0]), "fourier_terms"));
  const Scene relief = Parse(
      Pair("table_samples = 64\n",
           "[mesh.modifications]\npinion_tip_relief = 2e-5\npinion_tip_relief_length = 2e-3\n"));
  EXPECT_FALSE(warned(BuildMeshCore(relief, relief.meshes[0]), "table_samples"));
}

TEST(BuildMeshCoreTest, DriveSignDownATrain) {
  // pinion (20) → idler (30) → wheel (40), +50 N m on the pinion: the idler turns backwards and
  // drives the wheel with T_idler = 50 / (−20/30) < 0.
  std::string text = Pair();
  text.replace(text.find("[[mesh]]"), 8, R"([[gear]]
name = "idler"
teeth = 30
normal_module = 0.002
face_width = 0.02
mass = 1.0
inertia = 5e-4

[[mesh]]
pinion = "idler"
gear = "wheel"

[[mesh]])");
  text.replace(text.find("gear = \"wheel\"\n\n\n"), 14, "gear = \"idler\"");
  const Scene s = Parse(text, {"operating_point.body=pinion"});
  ASSERT_EQ(s.meshes.size(), 2u);
  EXPECT_EQ(s.meshes[0].name, "idler-wheel");
  EXPECT_EQ(MeshDriveSign(s, s.meshes[1]), 1);             // pinion-idler
  EXPECT_EQ(MeshDriveSign(s, s.meshes[0]), -1);            // idler-wheel
  EXPECT_FALSE(MeshLineLoad(s, s.meshes[0]).has_value());  // the reference is not in the mesh
}

TEST(BuildMeshCoreTest, DisconnectedMeshFallsBackWithAWarning) {
  std::string text = Pair();
  text.replace(text.find("[operating_point]"), 17, R"([[gear]]
name = "c1"
teeth = 25
normal_module = 0.002
face_width = 0.02
mass = 0.5
inertia = 1e-4

[[gear]]
name = "c2"
teeth = 35
normal_module = 0.002
face_width = 0.02
mass = 0.5
inertia = 1e-4

[[mesh]]
pinion = "c1"
gear = "c2"

[operating_point])");
  const Scene s = Parse(text);
  ASSERT_EQ(s.meshes.size(), 2u);
  const BuiltMeshCore built = BuildMeshCore(s, s.meshes[1]);
  EXPECT_EQ(built.drive_sign, 1);
  ASSERT_FALSE(built.warnings.empty());
  EXPECT_NE(built.warnings[0].find("mesh.c1-c2: drive sign +1 assumed (not connected"),
            std::string::npos)
      << built.warnings[0];
  EXPECT_FALSE(MeshLineLoad(s, s.meshes[1]).has_value());
}

TEST(BuildMeshCoreTest, UserParametersServeEveryLinearLevel) {
  const std::string params =
      "[mesh.parameters]\nform = \"fourier\"\nstiffness = [4e8, 1e8, 0]\n"
      "te_eta = [0, 2e-6, 0]\n";
  for (const char* level : {"blankenship_singh", "coupling_4dof", "lti", "torsional"}) {
    const Scene s = Parse(Pair(std::string("model = \"") + level + "\"\ndamping = 100\n", params));
    const BuiltMeshCore built = BuildMeshCore(s, s.meshes[0]);
    const LinearMeshCore& core = Linear(built);
    EXPECT_NEAR(Mean(core.stiffness())[0], 4e8, 1e-6) << level;
    EXPECT_EQ(core.damping().value, 100.0);
    ASSERT_TRUE(core.transmission_error().has_value());
    EXPECT_NEAR(EvalTransmissionError(core, 0.0)[0], 2e-6, 1e-18);
    EXPECT_EQ(Classify(core), std::string(level) == "lti" ? TimeDependence::kConstant
                                                          : TimeDependence::kSmoothPeriodic);
  }
  // μ below κ² somewhere in a series is rejected with the check point.
  EXPECT_THROWS_MESSAGE(
      Parse(Pair("",
                 "[mesh.parameters]\nform = \"fourier\"\nstiffness = [4e8, 0, 0]\n"
                 "load_centre = [0, 0.009, 0]\nmu = [0.5, 0, 0]\n")),
      SceneError,
      R"(mesh\.pinion-wheel\.parameters\.mu: at check point 0 of 64 \(theta = 0 rad\): )"
      R"(mu = 0\.5 is below kappa\^2)");
}

TEST(BuildMeshCoreTest, UserParametersWithSlicesAreRejected) {
  Scene s = Parse(Pair("", "[mesh.parameters]\nform = \"table\"\nstiffness = [4e8]\n"));
  s.meshes[0].model.level = MeshModelLevel::kNonlinearSlices;
  EXPECT_THROWS_MESSAGE(BuildMeshCore(s, s.meshes[0]), InvalidInput,
                        "mesh.pinion-wheel.parameters: user parameters cannot make the slice");
}

// --- transmission error -------------------------------------------------------------------------

TEST(BuildMeshCoreTest, ModificationsGiveTheBuildersTransmissionError) {
  const std::string mods =
      "[mesh.modifications]\npinion_tip_relief = 2e-5\npinion_tip_relief_length = 2e-3\n"
      "gear_tip_relief = 1e-5\ngear_tip_relief_length = 1.5e-3\nlead_crowning = 5e-6\n";
  for (const char* form : {"table", "fourier"}) {
    const bool fourier = std::string(form) == "fourier";
    const Scene s =
        Parse(Pair(std::string("coefficient_form = \"") + form + "\"\ntable_samples = 64\n" +
                       (fourier ? "fourier_terms = 20\n" : ""),
                   mods));
    const MeshDef& mesh = s.meshes[0];
    const BuiltMeshCore built = BuildMeshCore(s, mesh);
    ASSERT_TRUE(Linear(built).transmission_error().has_value());

    // The same numbers through the builders directly.
    IsoStiffnessSource iso;
    iso.options.line_load = MeshLineLoad(s, mesh);
    const MeshCoreSource source = MakeMeshCoreSource(mesh.geometry, iso, 1);
    ToothModifications m;
    m.pinion_tip_relief = {2e-5, 2e-3, ReliefShape::kLinear};
    m.gear_tip_relief = {1e-5, 1.5e-3, ReliefShape::kLinear};
    m.lead_crowning = 5e-6;
    const TransmissionErrorModel te(source.contact_lines, m);
    const Coefficient& got = *Linear(built).transmission_error();
    if (!fourier) {
      const TableCoefficient want = MakeTransmissionErrorTableCoefficient(te, 64);
      const MatrixX& samples = std::get<TableCoefficient>(got).samples();
      ASSERT_EQ(samples.cols(), want.samples().cols());
      EXPECT_LE(MaxAbs(samples - want.samples()), kSameRouteTol * MaxAbs(want.samples()));
    } else {
      const FourierCoefficient want = MakeTransmissionErrorFourierCoefficient(te, 20, 64);
      const auto& f = std::get<FourierCoefficient>(got);
      ASSERT_EQ(f.num_terms(), 20);
      EXPECT_LE((f.harmonics() - want.harmonics()).cwiseAbs().maxCoeff(),
                kSameRouteTol * want.harmonics().cwiseAbs().maxCoeff());
      EXPECT_LE(MaxAbs(f.mean() - want.mean()), kSameRouteTol * MaxAbs(want.mean()));
    }
    EXPECT_EQ(PeriodMeshes(built.core), 1);
  }
}

TEST(BuildMeshCoreTest, ToothErrorsSpanTheHuntingPeriod) {
  // Pinion 20 teeth, wheel 41 (coprime): the pattern repeats after lcm = 820 mesh cycles.
  std::string pitch = "[";
  for (int i = 0; i < 20; ++i) {
    pitch += (i > 0 ? ", " : "") + std::string(i == 3 ? "3e-6" : (i == 11 ? "-3e-6" : "0"));
  }
  pitch += "]";
  const Scene s = Parse(Pair("table_samples = 8\n",
                             "[mesh.errors]\npinion_pitch_deviations = " + pitch +
                                 "\ngear_runout = 1e-5\ngear_runout_phase_deg = 30\n",
                             41));
  const MeshDef& mesh = s.meshes[0];
  EXPECT_EQ(mesh.geometry.hunting_period_meshes, 820);
  const BuiltMeshCore built = BuildMeshCore(s, mesh);
  EXPECT_EQ(PeriodMeshes(built.core), std::lcm(20, 41));
  const auto& te = std::get<TableCoefficient>(*Linear(built).transmission_error());
  EXPECT_EQ(te.period_meshes(), 820);
  EXPECT_EQ(te.num_samples(), 8 * 820);
  // The same numbers through the builders directly.
  ToothErrors e;
  e.pinion_teeth = 20;
  e.gear_teeth = 41;
  e.pinion_pitch_deviations.assign(20, 0.0);
  e.pinion_pitch_deviations[3] = 3e-6;
  e.pinion_pitch_deviations[11] = -3e-6;
  e.gear_runout = 1e-5;
  e.gear_runout_phase = DegToRad(30.0);
  IsoStiffnessSource iso;
  iso.options.line_load = MeshLineLoad(s, mesh);
  const TransmissionErrorModel model(MakeMeshCoreSource(mesh.geometry, iso, 1).contact_lines, {},
                                     e);
  const TableCoefficient want = MakeTransmissionErrorTableCoefficient(model, 8);
  EXPECT_LE(MaxAbs(te.samples() - want.samples()), kSameRouteTol * MaxAbs(want.samples()));
}

// --- built-in scenes ----------------------------------------------------------------------------

TEST(BuildMeshCoreTest, BuiltinScenesLoadAndBuildEveryLevel) {
  for (const std::string& name : BuiltinSceneNames()) {
    if (LoadScene("builtin:" + name).oscillator) continue;  // no [[mesh]] (oscillator scenes)
    for (const char* level : {"blankenship_singh", "coupling_4dof", "lti", "torsional", "slices"}) {
      const Scene s = LoadScene("builtin:" + name, {std::string("mesh.0.model=") + level});
      for (const MeshDef& mesh : s.meshes) {
        const BuiltMeshCore built = BuildMeshCore(s, mesh);
        // Planetary ring meshes run with the opposite sign to the sun meshes (planetary.hpp).
        if (s.FindPlanetaryMesh(mesh.name)) {
          EXPECT_EQ(std::abs(built.drive_sign), 1) << name;
        } else {
          EXPECT_EQ(built.drive_sign, 1) << name;
        }
        // `mesh.0.model` sets the first [[mesh]] (in a planetary scene: the sun–planet template and
        // its copies); the others keep their own level.
        EXPECT_EQ(std::holds_alternative<SliceMeshCore>(built.core),
                  mesh.model.level == MeshModelLevel::kNonlinearSlices)
            << name << " " << level << " " << mesh.name;
        if (&mesh == &s.meshes.front()) {
          EXPECT_EQ(mesh.model.level == MeshModelLevel::kNonlinearSlices,
                    std::string(level) == "slices");
        }
      }
    }
  }
}

}  // namespace
}  // namespace geardyn
