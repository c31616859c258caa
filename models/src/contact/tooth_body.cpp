// Tooth bodies: section, mass properties and the arrow mass matrix (tooth_body.hpp).
#include "geardyn/models/contact/tooth_body.hpp"

#include <gsl/gsl_integration.h>

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <utility>

#include "geardyn/common/check.hpp"

namespace geardyn {
namespace {

double Involute(double alpha) { return std::tan(alpha) - alpha; }

// Gauss–Legendre nodes of one table (GSL), freed on scope exit.
struct GlTable {
  explicit GlTable(int n) : table(gsl_integration_glfixed_table_alloc(static_cast<size_t>(n))) {
    GEARDYN_DEMAND(table != nullptr);
  }
  ~GlTable() { gsl_integration_glfixed_table_free(table); }
  GlTable(const GlTable&) = delete;
  GlTable& operator=(const GlTable&) = delete;
  gsl_integration_glfixed_table* table;
};

// Accumulates A = ∫2ψ r dr, S = ∫2 sinψ r² dr, J = ∫2ψ r³ dr over a parameter s ∈ [a, b] with
// r(s), dr/ds given.
struct Moments {
  double area = 0.0, first = 0.0, polar = 0.0;
  void Add(double psi, double r, double weight) {
    area += weight * 2.0 * psi * r;
    first += weight * 2.0 * std::sin(psi) * r * r;
    polar += weight * 2.0 * psi * r * r * r;
  }
};

constexpr int kSectionPoints = 64;  // per piece; the integrands are smooth in r and in t

}  // namespace

const char* ToString(ToothBodyType type) {
  switch (type) {
    case ToothBodyType::kRigid:
      return "rigid";
    case ToothBodyType::kRevolute:
      return "revolute";
    case ToothBodyType::kBushing:
      return "bushing";
  }
  return "rigid";
}

int ToothDofs(ToothBodyType type) {
  switch (type) {
    case ToothBodyType::kRigid:
      return 0;
    case ToothBodyType::kRevolute:
      return 1;
    case ToothBodyType::kBushing:
      return 3;
  }
  return 0;
}

ToothSection IntegratePolarSection(const std::function<double(double)>& half_angle, double r_in,
                                   double r_out, int points) {
  GEARDYN_THROW_UNLESS(r_in >= 0.0 && r_out > r_in,
                       "r_out: must be > r_in >= 0, got r_in = " << r_in << ", r_out = " << r_out);
  GEARDYN_THROW_UNLESS(points >= 2, "points: must be >= 2, got " << points);
  const GlTable gl(points);
  Moments m;
  for (int i = 0; i < points; ++i) {
    double r = 0.0, w = 0.0;
    gsl_integration_glfixed_point(r_in, r_out, static_cast<size_t>(i), &r, &w, gl.table);
    m.Add(half_angle(r), r, w);
  }
  ToothSection s;
  s.area = m.area;
  s.centroid_radius = m.first / m.area;
  s.polar_moment = m.polar;
  s.root_radius = r_in;
  s.root_thickness = 2.0 * r_in * std::sin(half_angle(r_in));
  s.height = r_out - r_in;
  return s;
}

ToothSection CalcToothSection(const GearGeometry& gear) {
  GEARDYN_THROW_UNLESS(gear.kind == GearKind::kExternal,
                       "gear.kind: tooth bodies are modelled for external gears only (an internal "
                       "gear's tooth is the gap of an external one)");
  const double rb = gear.base_radius, ra = gear.tip_radius, rf = gear.root_radius;
  const double r = gear.reference_radius;
  const double psi_b = gear.tooth_thickness_transverse / (2.0 * r) + Involute(std::acos(rb / r));
  const auto psi = [&](double radius) {
    return radius <= rb ? psi_b : psi_b - Involute(std::acos(rb / radius));
  };
  GEARDYN_THROW_UNLESS(psi(ra) > 0.0, "gear.tooth_thickness_transverse: the flanks of "
                                          << gear.tooth_thickness_transverse
                                          << " m thick teeth cross below the tip radius " << ra
                                          << " m (pointed tooth)");
  const GlTable gl(kSectionPoints);
  Moments m;
  if (rf < rb) {  // radial flanks from the root circle to the base circle
    for (int i = 0; i < kSectionPoints; ++i) {
      double x = 0.0, w = 0.0;
      gsl_integration_glfixed_point(rf, rb, static_cast<size_t>(i), &x, &w, gl.table);
      m.Add(psi_b, x, w);
    }
  }
  // Involute part in the roll angle t = tan α: r = r_b √(1 + t²), dr = r_b t/√(1 + t²) dt.
  const double r0 = std::max(rf, rb);
  const double t0 = std::sqrt(std::max(0.0, (r0 / rb) * (r0 / rb) - 1.0));
  const double t1 = std::sqrt((ra / rb) * (ra / rb) - 1.0);
  for (int i = 0; i < kSectionPoints; ++i) {
    double t = 0.0, w = 0.0;
    gsl_integration_glfixed_point(t0, t1, static_cast<size_t>(i), &t, &w, gl.table);
    const double q = std::sqrt(1.0 + t * t);
    const double radius = rb * q;
    m.Add(psi_b - (t - std::atan(t)), radius, w * rb * t / q);
  }
  ToothSection s;
  s.area = m.area;
  s.centroid_radius = m.first / m.area;
  s.polar_moment = m.polar;
  s.root_radius = rf;
  s.root_thickness = 2.0 * rf * std::sin(psi(rf));
  s.height = ra - rf;
  return s;
}

ToothInertia CalcToothInertia(const ToothSection& section, double density, double face_width) {
  GEARDYN_THROW_UNLESS(std::isfinite(density) && density > 0.0,
                       "density: must be finite and > 0 [kg/m^3], got " << density);
  GEARDYN_THROW_UNLESS(std::isfinite(face_width) && face_width > 0.0,
                       "face_width: must be finite and > 0 [m], got " << face_width);
  ToothInertia t;
  const double rho_b = density * face_width;
  t.mass = rho_b * section.area;
  t.centroid_radius = section.centroid_radius;
  t.pivot_radius = section.root_radius;
  t.centroid_inertia = rho_b * (section.polar_moment -
                                section.area * section.centroid_radius * section.centroid_radius);
  return t;
}

MatrixX ToothCouplingMass(ToothBodyType type, const ToothInertia& tooth) {
  const int n = 1 + ToothDofs(type);
  MatrixX m = MatrixX::Zero(n, n);
  if (type == ToothBodyType::kRigid) return m;
  const double mass = tooth.mass, rbar = tooth.centroid_radius, jc = tooth.centroid_inertia;
  const double d = rbar - tooth.pivot_radius;
  const int phi = n - 1;
  m(0, 0) = tooth.AxisInertia();
  m(0, phi) = m(phi, 0) = jc + mass * rbar * d;
  m(phi, phi) = tooth.PivotInertia();
  if (type == ToothBodyType::kBushing) {  // (θ, u_r, u_t, φ)
    m(1, 1) = mass;
    m(2, 2) = mass;
    m(0, 2) = m(2, 0) = mass * rbar;
    m(2, 3) = m(3, 2) = mass * d;
  }
  return m;
}

MatrixX AssembleToothMass(const ToothSet& pinion, const ToothSet& gear) {
  const int n = 12 + pinion.num_coordinates() + gear.num_coordinates();
  MatrixX out = MatrixX::Zero(n, n);
  int next = 12;
  for (const auto& [set, theta] : {std::pair{&pinion, 5}, std::pair{&gear, 11}}) {
    const int dofs = ToothDofs(set->type);
    if (dofs == 0) continue;
    const MatrixX block = ToothCouplingMass(set->type, set->inertia);
    for (int k = 0; k < set->teeth; ++k, next += dofs) {
      out.block(next, next, dofs, dofs) = block.bottomRightCorner(dofs, dofs);
      out.block(theta, next, 1, dofs) = block.block(0, 1, 1, dofs);
      out.block(next, theta, dofs, 1) = block.block(1, 0, dofs, 1);
    }
  }
  return out;
}

void CheckTrunkInertia(const ToothSet& teeth, double gear_mass, double gear_inertia,
                       const std::string& what) {
  if (teeth.type == ToothBodyType::kRigid) return;
  const double j_teeth = teeth.teeth * teeth.inertia.AxisInertia();
  const double m_teeth = teeth.teeth * teeth.inertia.mass;
  GEARDYN_THROW_UNLESS(gear_inertia > j_teeth,
                       what << ".inertia: " << gear_inertia << " kg m^2 must exceed the "
                            << teeth.teeth << " teeth's own " << j_teeth
                            << " kg m^2 (the scene gives the whole gear; its trunk would have no "
                               "inertia left)");
  GEARDYN_THROW_UNLESS(gear_mass > m_teeth, what << ".mass: " << gear_mass << " kg must exceed the "
                                                 << teeth.teeth << " teeth's own " << m_teeth
                                                 << " kg");
}

}  // namespace geardyn
