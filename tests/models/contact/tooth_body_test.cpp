// Tooth bodies (tooth_body.hpp): section moments against a polygon of the parametric involute
// outline and the annular sector in closed form; the mass block against the kinetic energy
// integrated over that polygon; the arrow mass matrix SPD with the locked-teeth limit; Kim's DOF
// counts.
#include "geardyn/models/contact/tooth_body.hpp"

#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <cmath>
#include <numbers>
#include <vector>

#include "geardyn/common/errors.hpp"
#include "support/expect_throws.hpp"
#include "support/matrix_compare.hpp"

namespace geardyn {
namespace {

constexpr double kPi = std::numbers::pi;

// The Kahraman–Blankenship rig of Kim et al. Table 4 (m = 3 mm, z = 50, α = 20°, b = 20 mm), or
// a 20-tooth pinion of the same rack (its root circle lies below the base circle).
GearPairGeometry Pair(int z1, int z2) {
  GearPairSpec spec;
  spec.normal_module = 3e-3;
  spec.normal_pressure_angle = 20.0 * kPi / 180.0;
  spec.pinion.teeth = z1;
  spec.gear.teeth = z2;
  spec.pinion.face_width = 0.02;
  spec.gear.face_width = 0.02;
  return CalcGearPairGeometry(spec);
}

struct Point {
  double x, y;
};

// The tooth outline, counter-clockwise, built from the parametric involute (independent of
// ψ(r) = ψ_b − inv α): right flank up, tip arc, left flank down, root arc.
std::vector<Point> Outline(const GearGeometry& g, int n) {
  const double rb = g.base_radius, ra = g.tip_radius, rf = g.root_radius;
  const double r = g.reference_radius;
  const double alpha = std::acos(rb / r);
  const double psi_b = g.tooth_thickness_transverse / (2 * r) + std::tan(alpha) - alpha;
  // Left flank (y > 0) unwinding from angle ψ_b: p(t) = r_b[e(ψ_b − t) + t e⊥(ψ_b − t)].
  const auto involute = [&](double t) {
    const double a = psi_b - t;
    return Point{rb * (std::cos(a) - t * std::sin(a)), rb * (std::sin(a) + t * std::cos(a))};
  };
  const double t0 = rf > rb ? std::sqrt((rf / rb) * (rf / rb) - 1) : 0.0;
  const double t1 = std::sqrt((ra / rb) * (ra / rb) - 1);
  std::vector<Point> left;  // from the root up to the tip
  if (rf < rb) {
    for (int i = 0; i < n; ++i) {
      const double rr = rf + (rb - rf) * i / n;
      left.push_back({rr * std::cos(psi_b), rr * std::sin(psi_b)});
    }
  }
  for (int i = 0; i <= n; ++i) left.push_back(involute(t0 + (t1 - t0) * i / n));
  std::vector<Point> out;
  for (const Point& p : left) out.push_back({p.x, -p.y});  // right flank, mirrored, upwards
  const double tip = std::atan2(left.back().y, left.back().x);
  for (int i = 1; i < n; ++i) {
    const double a = -tip + 2 * tip * i / n;
    out.push_back({ra * std::cos(a), ra * std::sin(a)});
  }
  for (auto it = left.rbegin(); it != left.rend(); ++it) out.push_back(*it);
  const double root = std::atan2(left.front().y, left.front().x);
  for (int i = 1; i < n; ++i) {
    const double a = root - 2 * root * i / n;
    out.push_back({rf * std::cos(a), rf * std::sin(a)});
  }
  return out;
}

// Polygon integrals ∫1, ∫x, ∫y, ∫x², ∫y², ∫xy (shoelace/Green formulas).
struct PolygonMoments {
  double a = 0, x = 0, y = 0, xx = 0, yy = 0, xy = 0;
};
PolygonMoments Integrate(const std::vector<Point>& p) {
  PolygonMoments m;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const Point& u = p[i];
    const Point& v = p[(i + 1) % p.size()];
    const double c = u.x * v.y - v.x * u.y;
    m.a += c / 2;
    m.x += c * (u.x + v.x) / 6;
    m.y += c * (u.y + v.y) / 6;
    m.xx += c * (u.x * u.x + u.x * v.x + v.x * v.x) / 12;
    m.yy += c * (u.y * u.y + u.y * v.y + v.y * v.y) / 12;
    m.xy += c * (u.x * v.y + 2 * u.x * u.y + 2 * v.x * v.y + v.x * u.y) / 24;
  }
  return m;
}

TEST(ToothBodyTest, SectorMomentsMatchClosedForm) {
  const double psi = 0.04, r0 = 0.07, r1 = 0.078;
  const ToothSection s = IntegratePolarSection([&](double) { return psi; }, r0, r1, 8);
  const double area = psi * (r1 * r1 - r0 * r0);
  EXPECT_NEAR(s.area, area, 1e-14 * area);
  const double first = 2 * std::sin(psi) * (r1 * r1 * r1 - r0 * r0 * r0) / 3;
  EXPECT_NEAR(s.centroid_radius, first / area, 1e-14 * r1);
  const double polar = psi * (std::pow(r1, 4) - std::pow(r0, 4)) / 2;
  EXPECT_NEAR(s.polar_moment, polar, 1e-14 * polar);
}

TEST(ToothBodyTest, InvoluteSectionMatchesPolygonOfTheOutline) {
  for (const auto& [z1, z2] : {std::pair{50, 50}, std::pair{20, 50}}) {
    const GearGeometry g = Pair(z1, z2).pinion;
    const ToothSection s = CalcToothSection(g);
    // A 4000-segment-per-piece polygon errs by O(n⁻²) ≈ 1e-7 relative (chords of convex arcs).
    const PolygonMoments m = Integrate(Outline(g, 4000));
    constexpr double kTol = 1e-6;
    EXPECT_NEAR(s.area, m.a, kTol * m.a) << z1;
    EXPECT_NEAR(s.centroid_radius, m.x / m.a, kTol * g.tip_radius) << z1;
    EXPECT_NEAR(m.y / m.a, 0.0, kTol * g.tip_radius);  // symmetric
    EXPECT_NEAR(s.polar_moment, m.xx + m.yy, kTol * (m.xx + m.yy)) << z1;
    EXPECT_NEAR(s.height, g.tip_radius - g.root_radius, 1e-15);
  }
}

// T = ½ ρ b ∫ |v|² dA with v(p) = θ̇ ẑ×p + u̇_r x̂ + u̇_t ŷ + φ̇ ẑ×(p − P), P = (r_p, 0) on the
// centreline (x axis), integrated with the polygon moments: equals ½ q̇ᵀ M q̇ of
// ToothCouplingMass for every q̇ (checked on the basis pairs, i.e. entry by entry).
TEST(ToothBodyTest, MassBlockIsTheKineticEnergyOfTheTooth) {
  const GearGeometry g = Pair(50, 50).pinion;
  const double rho = 7850.0, b = g.face_width;
  const ToothInertia tooth = CalcToothInertia(CalcToothSection(g), rho, b);
  const PolygonMoments m = Integrate(Outline(g, 4000));
  const double rp = tooth.pivot_radius;
  // Velocity = A q̇ with rows (v_x, v_y) linear in p: v_x = −θ̇ y + u̇_r − φ̇ y,
  // v_y = θ̇ x + u̇_t + φ̇ (x − r_p). ∫|v|² = Σ_ij q̇_i q̇_j ∫ (a_i · a_j).
  const auto field = [&](int i, const Point& p) -> Point {
    switch (i) {
      case 0:
        return {-p.y, p.x};
      case 1:
        return {1, 0};
      case 2:
        return {0, 1};
      default:
        return {-p.y, p.x - rp};
    }
  };
  // ∫ of a bilinear form in (1, x, y): expand each field as c + Cx x + Cy y.
  MatrixX expected(4, 4);
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j) {
      const Point o{0, 0}, ex{1, 0}, ey{0, 1};
      const Point ci = field(i, o), cj = field(j, o);
      const Point xi{field(i, ex).x - ci.x, field(i, ex).y - ci.y};
      const Point yi{field(i, ey).x - ci.x, field(i, ey).y - ci.y};
      const Point xj{field(j, ex).x - cj.x, field(j, ex).y - cj.y};
      const Point yj{field(j, ey).x - cj.x, field(j, ey).y - cj.y};
      const auto dot = [](const Point& u, const Point& v) { return u.x * v.x + u.y * v.y; };
      const double integral = dot(ci, cj) * m.a + (dot(ci, xj) + dot(xi, cj)) * m.x +
                              (dot(ci, yj) + dot(yi, cj)) * m.y + dot(xi, xj) * m.xx +
                              dot(yi, yj) * m.yy + (dot(xi, yj) + dot(yi, xj)) * m.xy;
      expected(i, j) = rho * b * integral;
    }
  }
  const MatrixX bushing = ToothCouplingMass(ToothBodyType::kBushing, tooth);
  EXPECT_MATRIX_NEAR(bushing, expected, 1e-6);
  const MatrixX revolute = ToothCouplingMass(ToothBodyType::kRevolute, tooth);
  MatrixX expected_a(2, 2);
  expected_a << expected(0, 0), expected(0, 3), expected(3, 0), expected(3, 3);
  EXPECT_MATRIX_NEAR(revolute, expected_a, 1e-6);
  EXPECT_EQ(ToothCouplingMass(ToothBodyType::kRigid, tooth).size(), 1);
}

// The arrow matrix on the rig's 6-DOF bodies: SPD with the bodies' masses; with the teeth locked
// (tooth coordinates zero) the kinetic energy is the scene's: the added 12×12 block is zero.
TEST(ToothBodyTest, ArrowMassIsSpdAndLockedTeethKeepTheSceneInertia) {
  const GearGeometry g = Pair(50, 50).pinion;
  const ToothInertia tooth = CalcToothInertia(CalcToothSection(g), 7850.0, g.face_width);
  for (const ToothBodyType type : {ToothBodyType::kRevolute, ToothBodyType::kBushing}) {
    const ToothSet set{type, 50, tooth};
    const MatrixX added = AssembleToothMass(set, set);
    const int n = 12 + 2 * set.num_coordinates();
    ASSERT_EQ(added.rows(), n);
    // Rig gear bodies: a solid steel disc r = 75 mm, b = 20 mm (m = 2.77 kg, J = m r²/2).
    const double mass = 7850.0 * kPi * 0.075 * 0.075 * 0.02, inertia = 0.5 * mass * 0.075 * 0.075;
    CheckTrunkInertia(set, mass, inertia, "gear.wheel");
    MatrixX total = added;
    for (int body = 0; body < 2; ++body) {
      const Vector6 d =
          (Vector6() << mass, mass, mass, inertia / 2, inertia / 2, inertia).finished();
      for (int k = 0; k < 6; ++k) total(6 * body + k, 6 * body + k) += d(k);
    }
    EXPECT_TRUE(added.isApprox(added.transpose(), 0.0));
    EXPECT_EQ(added.topLeftCorner(12, 12).norm(), 0.0);  // locked teeth: the scene's bodies
    Eigen::LLT<MatrixX> llt(total);
    EXPECT_EQ(llt.info(), Eigen::Success) << ToString(type);
  }
  // Kim's DOF counts (torsional rig: one θz per gear) and ours (6-DOF bodies).
  const ToothSet a{ToothBodyType::kRevolute, 50, tooth}, b{ToothBodyType::kBushing, 50, tooth};
  EXPECT_EQ(2 + 2 * a.num_coordinates(), 102);
  EXPECT_EQ(2 + 2 * b.num_coordinates(), 302);
  EXPECT_EQ(12 + 2 * a.num_coordinates(), 112);
  EXPECT_EQ(12 + 2 * b.num_coordinates(), 312);
}

TEST(ToothBodyTest, BadInputIsRejected) {
  const GearGeometry g = Pair(50, 50).pinion;
  const ToothSection s = CalcToothSection(g);
  EXPECT_THROWS_MESSAGE(CalcToothInertia(s, 0.0, 0.02), InvalidInput, "density");
  EXPECT_THROWS_MESSAGE(CalcToothInertia(s, 7850.0, -1.0), InvalidInput, "face_width");
  const ToothInertia tooth = CalcToothInertia(s, 7850.0, g.face_width);
  EXPECT_THROWS_MESSAGE(
      CheckTrunkInertia(ToothSet{ToothBodyType::kRevolute, 50, tooth}, 10.0, 1e-6, "gear.wheel"),
      InvalidInput, "gear.wheel.inertia");
  GearGeometry internal = g;
  internal.kind = GearKind::kInternal;
  EXPECT_THROWS_MESSAGE(CalcToothSection(internal), InvalidInput, "gear.kind");
}

}  // namespace
}  // namespace geardyn
