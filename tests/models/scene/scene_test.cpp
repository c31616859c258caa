#include "geardyn/models/scene/scene.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "geardyn/common/errors.hpp"
#include "support/expect_throws.hpp"

namespace geardyn {
namespace {

// Scenes built by hand (no reader, no geometry): Scene's kinematics use only names, tooth
// counts, gear kinds, meshes and bearings. Expected speeds are worked out by hand from the
// pitch-line velocity rule v = Ω r with r ∝ z (equal on both sides of a mesh).

constexpr double kTol = 1e-12;  // relative; a few products of tooth-count quotients

GearDef Gear(const std::string& name, int teeth, bool internal = false) {
  GearDef g;
  g.name = name;
  g.blank.teeth = teeth;
  g.blank.kind = internal ? GearKind::kInternal : GearKind::kExternal;
  g.normal_module = 0.002;
  g.mass = 1.0;
  g.inertia = 1e-3;
  return g;
}

MeshDef Mesh(const std::string& pinion, const std::string& gear) {
  MeshDef m;
  m.name = pinion + "-" + gear;
  m.pinion = pinion;
  m.gear = gear;
  return m;
}

double RpmToRadS(double rpm) { return rpm * 2.0 * std::acos(-1.0) / 60.0; }

// A (20) drives B (40) externally; B drives C (10) externally; C drives ring R (50) internally.
Scene Chain() {
  Scene s;
  s.source = "chain";
  s.gears = {Gear("A", 20), Gear("B", 40), Gear("C", 10), Gear("R", 50, true), Gear("loose", 30)};
  s.meshes = {Mesh("A", "B"), Mesh("B", "C"), Mesh("C", "R")};
  s.operating_point.body = "A";
  s.operating_point.speed = RpmToRadS(1200.0);  // 20 rev/s
  s.operating_point.torque = 10.0;
  return s;
}

TEST(SceneTest, GearLooksUpByName) {
  const Scene s = Chain();
  EXPECT_EQ(s.gear("C").blank.teeth, 10);
  EXPECT_THROWS_MESSAGE(s.gear("D"), InvalidInput, "gear: no gear named 'D' in scene 'chain'");
}

TEST(SceneTest, SpeedsFollowTheChain) {
  const Scene s = Chain();
  const double w = RpmToRadS(1200.0);
  EXPECT_NEAR(s.GearSpeed("A"), w, kTol * w);
  // External mesh: reversed, Ω_B = −Ω_A · 20/40.
  EXPECT_NEAR(s.GearSpeed("B"), -0.5 * w, kTol * w);
  // External again: Ω_C = −Ω_B · 40/10 = +2 Ω_A.
  EXPECT_NEAR(s.GearSpeed("C"), 2.0 * w, kTol * w);
  // Internal mesh keeps the direction: Ω_R = +Ω_C · 10/50 = 0.4 Ω_A.
  EXPECT_NEAR(s.GearSpeed("R"), 0.4 * w, kTol * w);
}

TEST(SceneTest, SpeedsFromAReferenceAtTheOutput) {
  Scene s = Chain();
  s.operating_point.body = "R";
  s.operating_point.speed = 10.0;
  EXPECT_NEAR(s.GearSpeed("R"), 10.0, kTol * 10.0);
  EXPECT_NEAR(s.GearSpeed("C"), 50.0, kTol * 50.0);
  EXPECT_NEAR(s.GearSpeed("A"), 25.0, kTol * 25.0);
}

TEST(SceneTest, UnconnectedGearHasNoSpeed) {
  const Scene s = Chain();
  EXPECT_THROWS_MESSAGE(s.GearSpeed("loose"), InvalidInput,
                        "gear 'loose': not connected through meshes .* 'A'");
  EXPECT_THROWS_MESSAGE(s.GearSpeed("nope"), InvalidInput, "no gear named 'nope'");
}

TEST(SceneTest, MeshFrequencyIsRpmOver60TimesTeeth) {
  const Scene s = Chain();
  // In a simple chain the pitch-line velocity, hence the mesh frequency, is the same everywhere:
  // f = n/60 · z_A = 1200/60 · 20 = 400 Hz.
  for (const MeshDef& m : s.meshes) {
    EXPECT_NEAR(s.MeshFrequencyHz(m), 400.0, kTol * 400.0) << m.name;
  }
}

TEST(SceneTest, TorsionallyStiffBearingTiesTwoGearsOnOneShaft) {
  // Two-stage reducer: A (20) → B (40); C (15) on B's shaft; C → D (45).
  Scene s;
  s.source = "two-stage";
  s.gears = {Gear("A", 20), Gear("B", 40), Gear("C", 15), Gear("D", 45)};
  s.meshes = {Mesh("A", "B"), Mesh("C", "D")};
  BearingDef shaft;
  shaft.name = "shaft";
  shaft.body = "B";
  shaft.other = "C";
  shaft.stiffness(5, 5) = 1e6;  // torsional stiffness of the intermediate shaft [N m/rad]
  s.bearings = {shaft};
  s.operating_point.body = "A";
  s.operating_point.speed = RpmToRadS(3000.0);
  const double w = s.operating_point.speed;
  EXPECT_NEAR(s.GearSpeed("C"), -0.5 * w, kTol * w);
  EXPECT_NEAR(s.GearSpeed("D"), 0.5 * w / 3.0, kTol * w);
  // Stage 1: 3000/60 · 20 = 1000 Hz; stage 2: 1500/60 · 15 = 375 Hz.
  EXPECT_NEAR(s.MeshFrequencyHz(s.meshes[0]), 1000.0, kTol * 1000.0);
  EXPECT_NEAR(s.MeshFrequencyHz(s.meshes[1]), 375.0, kTol * 375.0);

  // Without torsional stiffness the shaft does not transmit speed.
  s.bearings[0].stiffness(5, 5) = 0.0;
  EXPECT_THROWS_MESSAGE(s.GearSpeed("D"), InvalidInput, "not connected");
}

TEST(SceneTest, ZeroSpeedGivesZeroFrequency) {
  Scene s = Chain();
  s.operating_point.speed = 0.0;
  EXPECT_EQ(s.GearSpeed("B"), 0.0);
  EXPECT_EQ(s.MeshFrequencyHz(s.meshes[0]), 0.0);
}

}  // namespace
}  // namespace geardyn
