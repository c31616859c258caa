// The tooth-contact mesh core (contact_mesh_core.hpp).
#include "geardyn/models/contact/contact_mesh_core.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numeric>
#include <span>
#include <utility>

#include "geardyn/common/check.hpp"
#include "geardyn/models/contact/contact_presearch.hpp"
#include "geardyn/models/contact/involute_contact.hpp"
#include "geardyn/models/contact/tip_corner_contact.hpp"
#include "geardyn/models/contact/tooth_pose.hpp"

namespace geardyn {
namespace {

/// 12 body coordinates + up to 3 per tooth of each member.
constexpr int kMaxLocal = 18;
/// Smallest radius of curvature given to the line law [m]: a sharp tip corner (ρ_a = 0) would make
/// Johnson's logarithm of R meaningless; 10 µm is below any real edge radius.
constexpr double kMinCurvatureRadius = 1e-5;
/// Base angular margin of the pre-search windows [rad], on top of the tooth deflections.
constexpr double kPresearchMargin = 1e-3;

struct ContactWorkspace final : NonlinearMeshCoreWorkspace {
  std::vector<ToothPairCandidate> candidates;
  std::vector<double> drive_force, coast_force;  // per pinion tooth [N]
};

// ∂(cx, cy, φ)/∂q_k of a slice pose (mesh_kinematics.cpp): θy moves the slice centre by +θy Δz
// along X, θx by −θx Δz along Y; φ follows θz.
Eigen::Matrix<double, 3, 6> SliceJacobian(double dz) {
  Eigen::Matrix<double, 3, 6> j = Eigen::Matrix<double, 3, 6>::Zero();
  j(0, 0) = 1.0;
  j(0, 4) = dz;
  j(1, 1) = 1.0;
  j(1, 3) = -dz;
  j(2, 5) = 1.0;
  return j;
}

// The mesh cycle n ≡ tooth (mod z) nearest to `cycle` (mesh_kinematics.hpp numbering).
std::int64_t MeshCycle(int tooth, int z, std::int64_t cycle) {
  std::int64_t d = (tooth - cycle) % z;  // in (−z, z)
  if (d < 0) d += z;                     // [0, z)
  if (2 * d >= z) d -= z;                // [−z/2, z/2)
  return cycle + d;
}

}  // namespace

/// One contact with its gradients on the local coordinates (indices into x).
struct ContactMeshCore::Contact {
  int n = 0;
  std::array<int, kMaxLocal> index{};
  std::array<double, kMaxLocal> grad{};   // ∂δ/∂x
  std::array<double, kMaxLocal> slide{};  // ∂v_s/∂v
  double grad_theta = 0.0;                // ∂δ/∂θ
  double slide_theta = 0.0;               // ∂v_s/∂θ̇
  double delta = 0.0, rate = 0.0, sliding = 0.0;
  LineContactGeometry line;
  bool has_sliding = false;
  int Slot(int i) {
    for (int k = 0; k < n; ++k) {
      if (index[k] == i) return k;
    }
    index[n] = i;
    grad[n] = 0.0;
    slide[n] = 0.0;
    return n++;
  }
};

ContactMeshCore::ContactMeshCore(const GearPairGeometry& pair, const MeshFrame& frame,
                                 const ContactMeshDef& def, const ToothModifications& modifications)
    : pair_(pair),
      def_(def),
      kinematics_(pair, frame,
                  MakeToothFlankGeometry(pair, pair.pinion, 0.0, def.tip_corner_radius),
                  MakeToothFlankGeometry(pair, pair.gear, 0.0, def.tip_corner_radius),
                  def.face_slices, FlankModifications(pair, modifications)),
      modifications_(FlankModifications(pair, modifications)) {
  std::string why;
  GEARDYN_THROW_UNLESS(def.law.IsValid(&why), "def.law: " << why);
  // The law's k and c are those of a contact over the whole face: each of the N slices carries
  // 1/N of them (the line law has the slice length in its own formula).
  slice_law_ = def.law;
  if (slice_law_.kind != ContactLawKind::kLine) {
    slice_law_.stiffness /= def.face_slices;
    slice_law_.damping /= def.face_slices;
  }
  spur_ = pair.base_helix_angle == 0.0;
  GEARDYN_THROW_UNLESS(spur_ || def.teeth == ToothBodyType::kRigid,
                       "def.teeth: \"" << ToString(def.teeth)
                                       << "\" tooth bodies need a spur pair in this build (use "
                                          "teeth = \"rigid\" for a helical pair)");
  GEARDYN_THROW_UNLESS(spur_ || def.friction_coefficient == 0.0,
                       "def.friction_coefficient: friction needs a spur pair in this build, got "
                           << def.friction_coefficient << " on a helical pair");
  GEARDYN_THROW_UNLESS(spur_ || def.profile == ContactProfile::kInvolute,
                       "def.profile: \"biarc\" flanks need a spur pair in this build (use "
                       "profile = \"involute\" for a helical pair)");
  if (def.profile == ContactProfile::kBiarc) {
    GEARDYN_THROW_UNLESS(def.arcs >= 1 && def.arcs <= 1000,
                         "def.arcs: " << def.arcs << " must lie in [1, 1000]");
    for (const ToothFlankGeometry* g : {&kinematics_.pinion(), &kinematics_.gear()}) {
      for (const int eps : {-1, 1}) biarcs_.emplace_back(*g, eps, def.arcs);
    }
  }
  GEARDYN_THROW_UNLESS(def.friction_speed > 0.0,
                       "def.friction_speed: must be > 0, got " << def.friction_speed);
  const GearGeometry* members[2] = {&pair.pinion, &pair.gear};
  for (int k = 0; k < 2; ++k) {
    teeth_[k] = ResolveToothSet(def, *members[k]);
    dofs_[k] = ToothDofs(def.teeth);
    if (def.teeth == ToothBodyType::kBushing) {
      joints_[k] = ResolveBushing(def, *members[k]);
    } else {
      joints_[k].rotational_stiffness = def.bending_stiffness;
      joints_[k].rotational_damping = def.bending_damping;
    }
  }
  num_internal_ = teeth_[0].num_coordinates() + teeth_[1].num_coordinates();
  period_ = def.teeth == ToothBodyType::kRigid
                ? 1
                : std::lcm<std::int64_t>(pair.pinion.teeth, pair.gear.teeth);
}

int ContactMeshCore::ToothOffset(int member, int tooth) const {
  return 12 + (member == 0 ? 0 : teeth_[0].num_coordinates()) + tooth * dofs_[member];
}

void ContactMeshCore::ApplySymmetryShift(Eigen::Ref<VectorX> internal) const {
  double* block = internal.data();
  for (int k = 0; k < 2; ++k) {
    const int size = teeth_[k].num_coordinates();
    // Tooth z−1's coordinates go to tooth 0, every other tooth's to the next one.
    if (size > 0) std::rotate(block, block + size - dofs_[k], block + size);
    block += size;
  }
}

std::unique_ptr<NonlinearMeshCoreWorkspace> ContactMeshCore::MakeWorkspace() const {
  auto ws = std::make_unique<ContactWorkspace>();
  ws->candidates.resize(static_cast<std::size_t>(teeth_[0].teeth) * teeth_[1].teeth);
  ws->drive_force.resize(teeth_[0].teeth);
  ws->coast_force.resize(teeth_[0].teeth);
  return ws;
}

MatrixX ContactMeshCore::InternalMass() const { return AssembleToothMass(teeth_[0], teeth_[1]); }

int ContactMeshCore::num_switching_functions() const {
  return kinematics_.num_slices() * 2 * teeth_[0].teeth;
}

std::vector<std::string> ContactMeshCore::channel_names() const {
  std::vector<std::string> names;
  const char* member[2] = {"pinion", "gear"};
  for (int k = 0; k < 2; ++k) {
    for (int t = 0; t < teeth_[k].teeth; ++t) {
      names.push_back(std::string(member[k]) + ".tooth" + std::to_string(t) + ".force [N]");
    }
  }
  for (int t = 0; t < teeth_[0].teeth; ++t) {
    names.push_back("pinion.tooth" + std::to_string(t) + ".status [-]");
  }
  for (int k = 0; k < 2; ++k) {
    for (int t = 0; t < teeth_[k].teeth; ++t) {
      const std::string p = std::string(member[k]) + ".tooth" + std::to_string(t);
      if (def_.teeth == ToothBodyType::kBushing) {
        names.push_back(p + ".radial [m]");
        names.push_back(p + ".tangential [m]");
      }
      if (def_.teeth != ToothBodyType::kRigid) names.push_back(p + ".rotation [rad]");
    }
  }
  return names;
}

bool ContactMeshCore::EvalContact(const Eigen::Ref<const VectorX>& x,
                                  const Eigen::Ref<const VectorX>& v, double theta,
                                  double theta_rate, int slice,
                                  const std::pair<GearSlicePose, GearSlicePose>& slice_poses,
                                  int i1, int i2, FlankSide side, Contact* c) const {
  const Vector12 q = x.head<12>();
  c->n = 0;
  c->has_sliding = false;
  c->line.length = kinematics_.slice_width();
  if (!spur_) {  // rigid, frictionless helical teeth: the kinematics' own chain
    const Vector12 q_rate = v.head<12>();
    const SliceToothContact sc =
        kinematics_.EvalToothPair(q, theta, slice, i1, i2, side, &q_rate, theta_rate);
    if (!sc.transverse.found || !sc.transverse.valid) return false;
    for (int i = 0; i < 12; ++i) c->grad[c->Slot(i)] = sc.d_penetration(i);
    c->grad_theta = sc.d_penetration_d_phase;
    c->delta = sc.penetration;
    c->rate = sc.approach_rate;
    c->line.length = kinematics_.slice_width() / std::cos(pair_.base_helix_angle);
    c->line.radius1 = std::max(sc.transverse.roll1, kMinCurvatureRadius);
    c->line.radius2 = std::max(sc.transverse.roll2, kMinCurvatureRadius);
    return true;
  }
  const GearSlicePose* poses[2] = {&slice_poses.first, &slice_poses.second};
  const ToothFlankGeometry* geom[2] = {&kinematics_.pinion(), &kinematics_.gear()};
  const int tooth[2] = {i1, i2};
  const int eps = kinematics_.Unwind(side);
  const int s = kinematics_.frame().drive_sign;
  EffectiveBaseCircle eff[2];
  InvoluteFlankPose flank[2];
  Eigen::Matrix<double, 6, 1> defl_rate[2];
  for (int k = 0; k < 2; ++k) {
    const GearSlicePose& p = *poses[k];
    const double world =
        p.layout.first_tooth_angle + p.layout.sense * tooth[k] * geom[k]->angular_pitch();
    const double body = world - p.angle;
    ToothDeflection d;
    Eigen::Vector3d dr = Eigen::Vector3d::Zero();  // (ψ̇, τ̇_r, τ̇_t)
    if (dofs_[k] > 0) {
      const int o = ToothOffset(k, tooth[k]);
      if (dofs_[k] == 1) {
        d.rotation = x(o);
        dr(0) = v(o);
      } else {
        d.radial = x(o);
        d.tangential = x(o + 1);
        d.rotation = x(o + 2);
        dr << v(o + 2), v(o), v(o + 1);
      }
    }
    eff[k] = CalcEffectiveBaseCircle(p.center, p.angle, body, teeth_[k].inertia.pivot_radius, d);
    flank[k] = MakeFlankPose(*geom[k], eff[k].center, eff[k].angle + body, eps);
    // Rates of (c, φ, ψ, τ_r, τ_t): c and φ from the body's velocity in this slice.
    const Eigen::Matrix<double, 3, 6> sj = SliceJacobian(
        kinematics_.frame().reference_point.z() + kinematics_.slice_position(slice) -
        (k == 0 ? kinematics_.frame().pinion_center.z() : kinematics_.frame().gear_center.z()));
    const Eigen::Vector3d body_rate = sj * v.segment<6>(6 * k);
    const double nominal = (k == 0 ? s / double(geom[0]->teeth) : -s / double(geom[1]->teeth));
    defl_rate[k] << body_rate(0), body_rate(1), body_rate(2) + nominal * theta_rate, dr;
  }
  FlankContact t = CalcInvoluteContact(flank[0], flank[1]);
  if (t.found && !t.valid) {  // beyond a flank's end: the tip corner (mesh_kinematics.cpp)
    if (t.roll1 > flank[0].roll_max) {
      t = CalcTipCornerContact(flank[0], geom[0]->tip_corner_radius, flank[1]);
    } else if (t.roll2 > flank[1].roll_max) {
      t = SwapBodies(CalcTipCornerContact(flank[1], geom[1]->tip_corner_radius, flank[0]));
    }
  }
  if (!t.found || !t.valid) return false;
  if (!biarcs_.empty()) {  // Kim's biarcs near the exact contact's rolls (contact_mesh_core.hpp)
    const int f = eps > 0 ? 1 : 0;
    const double ra = t.corner == 1 ? flank[0].roll_max : t.roll1;
    const double rb = t.corner == 2 ? flank[1].roll_max : t.roll2;
    t = CalcBiarcContactNear(biarcs_[f], flank[0], ra, biarcs_[2 + f], flank[1], rb);
    if (!t.found || !t.valid) return false;
  }
  // δ = δ_t − e(ρ1, ρ2, y) (spur: cos β_b = 1) and its pose gradient.
  PoseGradient grad = t.d_penetration;
  double e = 0.0;
  if (modifications_ && !modifications_->empty()) {
    const bool coast = side == FlankSide::kCoast;
    const ReliefValue e1 = modifications_->Pinion(coast, t.roll1);
    const ReliefValue e2 = modifications_->Gear(coast, t.roll2);
    e = e1.value + e2.value + modifications_->Lead(coast, kinematics_.slice_position(slice));
    grad -= e1.slope * t.d_roll1 + e2.slope * t.d_roll2;
  }
  c->delta = t.penetration - e;
  if (c->delta <= 0.0) return true;  // open: the gap is all the caller needs
  // Sliding speed: linear in the two pose rates, so its gradient is exact from unit rates.
  PoseGradient slide = PoseGradient::Zero();
  const bool friction = def_.friction_coefficient > 0.0;
  for (int i = 0; i < 6 && friction; ++i) {
    Vector3 r1 = Vector3::Zero(), r2 = Vector3::Zero();
    (i < 3 ? r1 : r2)(i % 3) = 1.0;
    slide(i) = CalcContactRates(t, eff[0].center, r1, eff[1].center, r2).sliding;
  }
  c->has_sliding = friction;
  // Chain: pose (c′, β) ← (c, φ, ψ, τ_r, τ_t) ← (q_k, θ, tooth coordinates).
  c->grad_theta = 0.0;
  c->slide_theta = 0.0;
  c->rate = 0.0;
  c->sliding = 0.0;
  for (int k = 0; k < 2; ++k) {
    const Eigen::Matrix<double, 1, 6> h = grad.segment<3>(3 * k) * eff[k].jacobian;
    const Eigen::Matrix<double, 1, 6> w = slide.segment<3>(3 * k) * eff[k].jacobian;
    c->rate += (h * defl_rate[k])(0, 0);
    c->sliding += (w * defl_rate[k])(0, 0);
    const double dz =
        kinematics_.frame().reference_point.z() + kinematics_.slice_position(slice) -
        (k == 0 ? kinematics_.frame().pinion_center.z() : kinematics_.frame().gear_center.z());
    const Eigen::Matrix<double, 3, 6> sj = SliceJacobian(dz);
    const Eigen::Matrix<double, 1, 6> hq = h.head<3>() * sj;
    const Eigen::Matrix<double, 1, 6> wq = w.head<3>() * sj;
    for (int i = 0; i < 6; ++i) {
      const int slot = c->Slot(6 * k + i);
      c->grad[slot] += hq(i);
      c->slide[slot] += wq(i);
    }
    const double nominal = k == 0 ? s / double(geom[0]->teeth) : -s / double(geom[1]->teeth);
    c->grad_theta += h(2) * nominal;
    c->slide_theta += w(2) * nominal;
    if (dofs_[k] > 0) {
      const int o = ToothOffset(k, tooth[k]);
      // Local order of the deflection columns: ψ (3), τ_r (4), τ_t (5).
      if (dofs_[k] == 1) {
        const int slot = c->Slot(o);
        c->grad[slot] += h(3);
        c->slide[slot] += w(3);
      } else {
        const int cols[3] = {4, 5, 3};  // u_r, u_t, φ
        for (int j = 0; j < 3; ++j) {
          const int slot = c->Slot(o + j);
          c->grad[slot] += h(cols[j]);
          c->slide[slot] += w(cols[j]);
        }
      }
    }
  }
  const bool corner1 = t.corner == 1, corner2 = t.corner == 2;
  c->line.radius1 = std::max(corner1 ? geom[0]->tip_corner_radius : t.roll1, kMinCurvatureRadius);
  c->line.radius2 = std::max(corner2 ? geom[1]->tip_corner_radius : t.roll2, kMinCurvatureRadius);
  return true;
}

void ContactMeshCore::DoCalcForces(NonlinearMeshCoreWorkspace& ws_base, double theta,
                                   double theta_rate, const Eigen::Ref<const VectorX>& x,
                                   const Eigen::Ref<const VectorX>& v, bool with_jacobians,
                                   NonlinearMeshCoreOutput* out) const {
  auto& ws = static_cast<ContactWorkspace&>(ws_base);
  out->force.setZero();
  // Sparse Jacobians when the caller accepts them (NonlinearMeshCoreOutput::want_triplets): the
  // tooth joints are diagonal and each contact couples ≤ 18 coordinates, so the dense n × n
  // matrices (n = 312 for type-B teeth) would be mostly zeros that cost their clearing.
  const bool sparse = with_jacobians && out->want_triplets;
  out->has_triplets = sparse;
  if (with_jacobians && !sparse) {
    out->stiffness.setZero();
    out->damping.setZero();
  }
  auto& kt = out->stiffness_triplets;
  auto& ct = out->damping_triplets;
  // K(i, j) += value (and C): dense or appended.
  auto add_k = [&](int i, int j, double value) {
    if (sparse) {
      kt.emplace_back(i, j, value);
    } else {
      out->stiffness(i, j) += value;
    }
  };
  auto add_c = [&](int i, int j, double value) {
    if (sparse) {
      ct.emplace_back(i, j, value);
    } else {
      out->damping(i, j) += value;
    }
  };
  out->energy = 0.0;
  out->dissipation_power = 0.0;
  out->phase_power = 0.0;
  out->num_contacts = 0;
  const int z1 = teeth_[0].teeth, z2 = teeth_[1].teeth;
  const double open_gap = std::acos(-1.0) * kinematics_.pinion().base_radius / z1;
  out->switching.setConstant(open_gap);
  out->channels.setZero();
  std::fill(ws.drive_force.begin(), ws.drive_force.end(), 0.0);
  std::fill(ws.coast_force.begin(), ws.coast_force.end(), 0.0);
  // A non-finite state has no contact answer: the kernels would report "no contact" for it, so the
  // NaN is passed on (force, energy, switching) for the caller's checks to see, never a silent 0.
  if (!std::isfinite(theta) || !std::isfinite(theta_rate) || !x.allFinite() || !v.allFinite()) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    out->force.setConstant(nan);
    out->energy = out->dissipation_power = out->phase_power = nan;
    out->switching.setConstant(nan);
    return;
  }

  // ---- tooth joints: ½ k q² and c q̇ on every tooth coordinate; their deflection channels
  double margin = kPresearchMargin;
  int channel = 2 * z1 + z2;
  for (int k = 0; k < 2; ++k) {
    if (dofs_[k] == 0) continue;
    const BushingJoint& j = joints_[k];
    const double r_f = std::max(teeth_[k].inertia.pivot_radius, 1e-9);
    const double stiff[3] = {j.radial_stiffness, j.tangential_stiffness, j.rotational_stiffness};
    const double damp[3] = {j.radial_damping, j.tangential_damping, j.rotational_damping};
    const int first = dofs_[k] == 1 ? 2 : 0;  // revolute: the rotation only
    for (int t = 0; t < teeth_[k].teeth; ++t) {
      const int o = ToothOffset(k, t);
      for (int d = 0; d < dofs_[k]; ++d) {
        const int i = o + d, kind = first + d;
        out->force(i) -= stiff[kind] * x(i) + damp[kind] * v(i);
        out->energy += 0.5 * stiff[kind] * x(i) * x(i);
        out->dissipation_power += damp[kind] * v(i) * v(i);
        if (with_jacobians) {
          add_k(i, i, stiff[kind]);
          add_c(i, i, damp[kind]);
        }
        out->channels(channel++) = x(i);
        margin = std::max(
            margin, kPresearchMargin + 2.0 * (kind == 2 ? std::abs(x(i)) : std::abs(x(i)) / r_f));
      }
    }
  }

  // ---- contacts: pre-search per slice, then the flanks of the candidate pairs that can mesh
  const Vector12 q = x.head<12>();
  const std::int64_t cycle = std::llround(theta / (2.0 * std::acos(-1.0)));
  Contact c;
  for (int slice = 0; slice < kinematics_.num_slices(); ++slice) {
    const std::pair<GearSlicePose, GearSlicePose> poses = kinematics_.SlicePoses(q, theta, slice);
    const int found = FindCandidatePairs(kinematics_.pinion(), poses.first.layout,
                                         kinematics_.gear(), poses.second.layout, margin,
                                         std::span<ToothPairCandidate>(ws.candidates));
    const int count = std::min<int>(found, static_cast<int>(ws.candidates.size()));
    for (int n = 0; n < count; ++n) {
      const ToothPairCandidate& pair = ws.candidates[n];
      // Pairing filter: tooth i of a member is in mesh in the cycles n ≡ i (mod z) (the numbering
      // of mesh_kinematics.hpp); the candidate teeth lie within a few cycles of the current one,
      // so each has one nearby cycle. A drive contact needs the same cycle (the pair that meshes),
      // a coast contact the neighbouring one (the mate behind or ahead); other pairs of the
      // pre-search's windows face each other a whole pitch apart and cannot touch.
      const std::int64_t cycle_gap =
          MeshCycle(pair.tooth1, z1, cycle) - MeshCycle(pair.tooth2, z2, cycle);
      for (const FlankSide side : {FlankSide::kDrive, FlankSide::kCoast}) {
        if (side == FlankSide::kDrive ? cycle_gap != 0 : (cycle_gap != 1 && cycle_gap != -1))
          continue;
        if (!EvalContact(x, v, theta, theta_rate, slice, poses, pair.tooth1, pair.tooth2, side,
                         &c)) {
          continue;
        }
        const int sw = (slice * 2 + (side == FlankSide::kCoast ? 1 : 0)) * z1 + pair.tooth1;
        out->switching(sw) = std::min(out->switching(sw), -c.delta);
        if (c.delta <= 0.0) continue;
        const ContactLawValue law = EvalContactLaw(slice_law_, c.delta, c.rate, c.line);
        out->energy += law.energy;
        out->dissipation_power += law.dissipation;
        if (law.force <= 0.0) continue;  // clamped while separating: energy and loss only
        ++out->num_contacts;
        const double f = law.force;
        for (int a = 0; a < c.n; ++a) out->force(c.index[a]) -= f * c.grad[a];
        out->phase_power += f * c.grad_theta * theta_rate;
        if (with_jacobians) {
          for (int a = 0; a < c.n; ++a) {
            for (int b = 0; b < c.n; ++b) {
              add_k(c.index[a], c.index[b], law.d_force_d_gap * c.grad[a] * c.grad[b]);
              add_c(c.index[a], c.index[b], law.d_force_d_rate * c.grad[a] * c.grad[b]);
            }
          }
        }
        if (def_.friction_coefficient > 0.0 && c.has_sliding) {
          const FrictionValue fr =
              EvalFriction(def_.friction_coefficient, f, c.sliding, def_.friction_speed);
          for (int a = 0; a < c.n; ++a) out->force(c.index[a]) += fr.force * c.slide[a];
          out->dissipation_power += fr.dissipation;
          out->phase_power -= fr.force * c.slide_theta * theta_rate;
          if (with_jacobians) {
            const double ds = fr.d_force_d_normal * law.d_force_d_gap;
            const double dv = fr.d_force_d_normal * law.d_force_d_rate;
            for (int a = 0; a < c.n; ++a) {
              for (int b = 0; b < c.n; ++b) {
                add_k(c.index[a], c.index[b], -ds * c.slide[a] * c.grad[b]);
                add_c(
                    c.index[a], c.index[b],
                    -(dv * c.slide[a] * c.grad[b] + fr.d_force_d_speed * c.slide[a] * c.slide[b]));
              }
            }
          }
        }
        out->channels(pair.tooth1) += f;
        out->channels(z1 + pair.tooth2) += f;
        (side == FlankSide::kDrive ? ws.drive_force : ws.coast_force)[pair.tooth1] += f;
      }
    }
  }
  for (int t = 0; t < z1; ++t) {
    const double d = ws.drive_force[t], b = ws.coast_force[t];
    out->channels(z1 + z2 + t) = d > 0.0 || b > 0.0 ? (d >= b ? 1.0 : -1.0) : 0.0;
  }
}

}  // namespace geardyn
