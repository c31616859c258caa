// Speed-dependent gyroscopic and carrier-frame terms (speed_terms.hpp).
#include "geardyn/models/system/speed_terms.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <set>
#include <sstream>
#include <string>

#include "geardyn/common/check.hpp"
#include "geardyn/common/errors.hpp"
#include "geardyn/system/dof_map.hpp"

namespace geardyn {
namespace {

// a_b = Ω_b / s: the gear's speed at a reference speed of 1 rad/s; nullopt when the gear is not
// connected to the reference gear (its speed is undefined).
std::optional<double> SpeedFactor(const Scene& unit_speed_scene, const std::string& gear) {
  try {
    return unit_speed_scene.GearSpeed(gear);
  } catch (const InvalidInput&) {
    return std::nullopt;
  }
}

std::vector<std::string> Members(const PlanetaryDef& set) {
  std::vector<std::string> names = {set.sun, set.ring, set.carrier};
  names.insert(names.end(), set.planets.begin(), set.planets.end());
  return names;
}

// Relative tolerance of the isotropy checks (the reader's rotated planet bearings are exact to
// round-off; the scene's numbers are exact).
constexpr double kIsotropyRelTol = 1e-9;

// The (x, y) and (θx, θy) blocks of a 6×6 support are isotropic: equal diagonals, no cross term
// inside the pair, and no coupling between the in-plane pair and the others except what the
// rotation leaves invariant (none is accepted: the frames of x, y and θx, θy turn).
std::string AnisotropyOf(const Matrix6& a, const char* what) {
  const double scale = std::max(a.cwiseAbs().maxCoeff(), 1e-300);
  const auto close = [&](double u, double v) {
    return std::abs(u - v) <= kIsotropyRelTol * scale;
  };
  std::ostringstream why;
  for (int p : {0, 3}) {
    if (!close(a(p, p), a(p + 1, p + 1)) || !close(a(p, p + 1), 0.0)) {
      why << what << (p == 0 ? " x/y = " : " θx/θy = ") << a(p, p) << " / " << a(p + 1, p + 1);
      if (!close(a(p, p + 1), 0.0)) why << " (cross term " << a(p, p + 1) << ")";
      return why.str();
    }
  }
  for (int i = 0; i < 6; ++i) {
    for (int j = 0; j < 6; ++j) {
      const bool same_pair = (i / 3 == j / 3 && i % 3 < 2 && j % 3 < 2) || i == j;
      if (!same_pair && (i % 3 < 2 || j % 3 < 2) && !close(a(i, j), 0.0)) {
        why << what << " couples " << ToString(static_cast<BodyDof>(i)) << " with "
            << ToString(static_cast<BodyDof>(j)) << " (" << a(i, j) << ")";
        return why.str();
      }
    }
  }
  return {};
}

bool IsLateral(BodyDof c) {
  return c == BodyDof::kX || c == BodyDof::kY || c == BodyDof::kThetaX || c == BodyDof::kThetaY;
}

// A set member coupled in x, y, θx, θy to a body outside the set (through K̄ or C̄): the carrier
// frame would turn that coupling with the carrier.
void CheckNoLateralCouplingOut(const SystemModel& model, const MatrixX& k_bar,
                               const MatrixX& c_bar, const std::set<int>& members,
                               const PlanetaryDef& set) {
  const DofMap& dofs = model.dof_map();
  const int n = dofs.num_dofs();
  const double scale = std::max(k_bar.cwiseAbs().maxCoeff(), 1e-300);
  const double c_scale = std::max(c_bar.cwiseAbs().maxCoeff(), 1e-300);
  for (int i = 0; i < n; ++i) {
    if (!members.contains(dofs.dof_body(i).value()) || !IsLateral(dofs.dof_component(i))) continue;
    for (int j = 0; j < n; ++j) {
      if (members.contains(dofs.dof_body(j).value())) continue;
      if (std::abs(k_bar(i, j)) > kIsotropyRelTol * scale ||
          std::abs(c_bar(i, j)) > kIsotropyRelTol * c_scale) {
        GEARDYN_THROW_UNLESS(false, "planetary set '"
                      << set.name << "': its carrier rotates, and member '"
                      << dofs.body_name(dofs.dof_body(i)) << "' is coupled in "
                      << ToString(dofs.dof_component(i)) << " to '"
                      << dofs.body_name(dofs.dof_body(j)) << "' ("
                      << ToString(dofs.dof_component(j))
                      << "), a body outside the set: that coupling would turn with the carrier "
                         "(time-varying in the carrier frame). Couple the set to other bodies "
                         "torsionally or axially only (stiffness [0, 0, kz, 0, 0, kθz])");
      }
    }
  }
}

void AddPair(MatrixX& g, MatrixX& k, int i, int j, double gyro, double stiff) {
  if (i < 0 || j < 0) {
    // Planar model: only x, y (both kept) or neither; a lone kept DOF gets its stiffness only.
    if (i >= 0) k(i, i) += stiff;
    if (j >= 0) k(j, j) += stiff;
    return;
  }
  g(i, j) -= gyro;
  g(j, i) += gyro;
  k(i, i) += stiff;
  k(j, j) += stiff;
}

}  // namespace

double CarrierSpeedFactor(const Scene& scene) {
  GEARDYN_THROW_UNLESS(!scene.planetaries.empty(),
                       scene.source << ": a carrier speed needs a planetary set, and this scene "
                                       "has none ([[planetary]])");
  Scene unit = scene;
  unit.operating_point.speed = 1.0;
  for (const PlanetaryDef& set : scene.planetaries) {
    const std::optional<double> a = SpeedFactor(unit, set.carrier);
    if (a && *a != 0.0) return *a;
  }
  throw InvalidInput(scene.source +
                     ": a carrier speed needs a rotating carrier, and the carrier of every "
                     "planetary set is its fixed member (fixed = \"carrier\")");
}

SpeedTerms BuildSpeedTerms(const Scene& scene, const SceneSystem& built, const MatrixX& k_bar,
                           const MatrixX& c_bar, const SpeedTermsOptions& options) {
  const SystemModel& model = built.model;
  const DofMap& dofs = model.dof_map();
  const int n = dofs.num_dofs();
  SpeedTerms terms;
  terms.gyroscopic = MatrixX::Zero(n, n);
  terms.stiffness = MatrixX::Zero(n, n);
  if (scene.oscillator) return terms;

  Scene unit = scene;
  unit.operating_point.speed = 1.0;

  // Frame speed factor per body: a_c for the members of a set with a rotating carrier.
  std::vector<double> frame(static_cast<std::size_t>(dofs.num_bodies()), 0.0);
  GEARDYN_THROW_UNLESS(k_bar.rows() == n && k_bar.cols() == n && c_bar.rows() == n &&
                           c_bar.cols() == n,
                       "BuildSpeedTerms: K̄ and C̄ must be " << n << " × " << n);
  for (const PlanetaryDef& set : scene.planetaries) {
    const double a_c = SpeedFactor(unit, set.carrier).value_or(0.0);
    terms.carrier_speed_factors.push_back(a_c);
    if (!options.carrier_frame || a_c == 0.0) continue;
    std::set<int> members;
    for (const std::string& name : Members(set)) {
      if (const auto b = dofs.FindBody(name)) {
        members.insert(b->value());
        frame[static_cast<std::size_t>(b->value())] = a_c;
      }
    }
    for (const BearingDef& bearing : scene.bearings) {
      const bool on_member =
          std::find(Members(set).begin(), Members(set).end(), bearing.body) != Members(set).end();
      if (!on_member || !bearing.other.empty()) continue;
      for (const auto& [matrix, what] : {std::pair{&bearing.stiffness, "stiffness"},
                                         std::pair{&bearing.damping, "damping"}}) {
        const std::string why = AnisotropyOf(*matrix, what);
        GEARDYN_THROW_UNLESS(why.empty(),
                             "bearing '" << bearing.name << "' of planetary set '" << set.name
                                         << "' member '" << bearing.body << "': " << why
                                         << ". The carrier of the set rotates, and a space-fixed "
                                            "support is constant in the carrier frame only "
                                            "when it is isotropic (equal x and y, equal θx and θy, "
                                            "no cross terms)");
      }
    }
    CheckNoLateralCouplingOut(model, k_bar, c_bar, members, set);
    // Geometric stiffness of the planet bearings' centrifugal preload P = m_p Ω_c² a_w (see the
    // @file): + P a_w on the carrier's θz and P a_w e_t e_tᵀ on its tilts, per planet.
    if (const auto carrier = dofs.FindBody(set.carrier)) {
      const int rz = dofs.FindDof(*carrier, BodyDof::kThetaZ);
      const int rx = dofs.FindDof(*carrier, BodyDof::kThetaX);
      const int ry = dofs.FindDof(*carrier, BodyDof::kThetaY);
      const double a_w = set.center_distance;
      for (std::size_t p = 0; p < set.planets.size(); ++p) {
        const double m_p = scene.gear(set.planets[p]).mass.value_or(0.0);
        const double k_geo = m_p * a_c * a_c * a_w * a_w;  // P a_w per unit s²
        const double psi = set.planet_angles[p];
        const double et[2] = {-std::sin(psi), std::cos(psi)};
        if (rz >= 0) terms.stiffness(rz, rz) += k_geo;
        const int tilt[2] = {rx, ry};
        for (int i = 0; i < 2; ++i) {
          for (int j = 0; j < 2; ++j) {
            if (tilt[i] >= 0 && tilt[j] >= 0) {
              terms.stiffness(tilt[i], tilt[j]) += k_geo * et[i] * et[j];
            }
          }
        }
      }
    }
    terms.notes.push_back("carrier frame of planetary set '" + set.name +
                          "': Coriolis and centripetal terms of its members (Cooley & Parker 2012)");
  }
  if (options.spin_gyroscopics) {
    terms.notes.push_back("gyroscopic moments of the spinning gears (tilts θx, θy)");
  }

  for (const GearDef& gear : scene.gears) {
    const std::optional<BodyIndex> b = dofs.FindBody(gear.name);
    if (!b) continue;
    const double a_f = frame[static_cast<std::size_t>(b->value())];
    const double a_b = options.spin_gyroscopics ? SpeedFactor(unit, gear.name).value_or(0.0) : 0.0;
    const double m = gear.mass.value_or(0.0);
    const double j = gear.inertia.value_or(0.0);
    const double i_d = gear.transverse_inertia.value_or(0.5 * j);
    const auto dof = [&](BodyDof c) { return dofs.FindDof(*b, c); };
    // m(ü + 2iΩ_f u̇ − Ω_f² u): per unit s², Ω_f = a_f s.
    if (a_f != 0.0) {
      AddPair(terms.gyroscopic, terms.stiffness, dof(BodyDof::kX), dof(BodyDof::kY),
              2.0 * m * a_f, -m * a_f * a_f);
    }
    // I_d φ̈ + i(2 I_d Ω_f − J Ω_b) φ̇ + (J Ω_b Ω_f − I_d Ω_f²) φ.
    const double tilt_gyro = 2.0 * i_d * a_f - (options.spin_gyroscopics ? j * a_b : 0.0);
    const double tilt_stiff = j * a_b * a_f - i_d * a_f * a_f;
    if (tilt_gyro != 0.0 || tilt_stiff != 0.0) {
      AddPair(terms.gyroscopic, terms.stiffness, dof(BodyDof::kThetaX), dof(BodyDof::kThetaY),
              tilt_gyro, tilt_stiff);
    }
  }
  return terms;
}

}  // namespace geardyn
