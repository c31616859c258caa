#include "geardyn/models/contact/mesh_kinematics.hpp"

#include <cmath>
#include <numbers>

#include "geardyn/common/check.hpp"

namespace geardyn {

namespace {

/// Largest slice count: 1000 slices already resolve a crowning parabola to 1e-6 of its amount.
constexpr int kMaxSlices = 1000;

using PoseJacobian = Eigen::Matrix<double, 3, 6>;  // ∂(cx, cy, β)/∂(x, y, z, θx, θy, θz)

// The pose Jacobian of the @file of mesh_kinematics.hpp, the contact point P held fixed.
PoseJacobian SliceJacobian(const GearSlicePose& pose, double dz, const Vector2& point) {
  PoseJacobian j = PoseJacobian::Zero();
  j(0, 0) = 1.0;
  j(0, 4) = dz;  // θy moves the slice centre by +θy Δz along X
  j(1, 1) = 1.0;
  j(1, 3) = -dz;  // θx moves it by −θx Δz along Y
  const double f = pose.helix_factor;
  j(2, 2) = -f;  // axial shift acts as a rotation −f z
  j(2, 3) = -f * (point.y() - pose.center.y());
  j(2, 4) = f * (point.x() - pose.center.x());
  j(2, 5) = 1.0;
  return j;
}

}  // namespace

double GearSlicePose::AngleAt(const Vector2& point) const {
  const double w =
      axial + tilt.x() * (point.y() - center.y()) - tilt.y() * (point.x() - center.x());
  return angle - helix_factor * w;
}

ContactMeshKinematics::ContactMeshKinematics(const GearPairGeometry& pair, const MeshFrame& frame,
                                             const ToothFlankGeometry& pinion,
                                             const ToothFlankGeometry& gear, int num_slices,
                                             std::optional<FlankModifications> modifications)
    : frame_(frame),
      pinion_(pinion),
      gear_(gear),
      modifications_(std::move(modifications)),
      num_slices_(num_slices),
      s_(frame.drive_sign) {
  GEARDYN_THROW_UNLESS(!pair.internal && !frame.internal,
                       "pair.internal: the contact geometry supports external pairs only");
  GEARDYN_THROW_UNLESS(num_slices >= 1 && num_slices <= kMaxSlices,
                       "num_slices: " << num_slices << " must lie in [1, " << kMaxSlices << "]");
  GEARDYN_THROW_UNLESS(
      std::abs(pinion.base_radius - frame.pinion_base_radius) <= 1e-12 * frame.pinion_base_radius,
      "pinion.base_radius: " << pinion.base_radius << " m differs from the frame's "
                             << frame.pinion_base_radius << " m");
  GEARDYN_THROW_UNLESS(
      std::abs(gear.base_radius - frame.gear_base_radius) <= 1e-12 * frame.gear_base_radius,
      "gear.base_radius: " << gear.base_radius << " m differs from the frame's "
                           << frame.gear_base_radius << " m");
  face_width_ = pair.face_width;
  cos_base_helix_ = std::cos(frame.base_helix_angle);
  // Tooth 0 of each member has its drive flank at the pitch point at θ = 0 (mid face, q = 0):
  // the drive flanks (ε = −s) lie on the tangent m = u with ρ1 = r_b1 tan α_wt,
  // ρ2 = r_b2 tan α_wt, so β1 = ∠u + s tan α_wt, β2 = ∠u + π + s tan α_wt and γ0 = β − s ψ_b.
  const double tu = std::atan2(frame.u.y(), frame.u.x());
  const double roll_angle = s_ * std::tan(frame.operating_pressure_angle);
  tooth0_pinion_ = tu + roll_angle - s_ * pinion.base_half_angle;
  tooth0_gear_ = tu + std::numbers::pi + roll_angle - s_ * gear.base_half_angle;
}

double ContactMeshKinematics::slice_position(int slice) const {
  return -0.5 * face_width_ + (slice + 0.5) * face_width_ / num_slices_;
}

std::pair<GearSlicePose, GearSlicePose> ContactMeshKinematics::SlicePoses(const Vector12& q,
                                                                          double theta,
                                                                          int slice) const {
  const double y = slice_position(slice);
  const double zs = frame_.reference_point.z() + y;
  auto make = [&](int k) {
    const Vector3& c = k == 0 ? frame_.pinion_center : frame_.gear_center;
    const ToothFlankGeometry& g = k == 0 ? pinion_ : gear_;
    const auto qk = q.segment<6>(6 * k);
    const double dz = zs - c.z();
    GearSlicePose p;
    p.center = Vector2(c.x() + qk(0) + qk(4) * dz, c.y() + qk(1) - qk(3) * dz);
    // Nominal rotation: the pinion turns by s θ/z1, the gear by −s θ/z2.
    const double nominal = k == 0 ? s_ * theta / g.teeth : -s_ * theta / g.teeth;
    p.angle = nominal + qk(5) + g.helix_factor * y;
    p.helix_factor = g.helix_factor;
    p.axial = qk(2);
    p.tilt = Vector2(qk(3), qk(4));
    p.layout.center = p.center;
    p.layout.first_tooth_angle = p.angle + (k == 0 ? tooth0_pinion_ : tooth0_gear_);
    p.layout.sense = k == 0 ? -s_ : s_;  // tooth i+1 trails tooth i in the member's rotation
    return p;
  };
  return {make(0), make(1)};
}

SliceToothContact ContactMeshKinematics::EvalToothPair(const Vector12& q, double theta, int slice,
                                                       int tooth1, int tooth2, FlankSide side,
                                                       const Vector12* q_rate,
                                                       double theta_rate) const {
  const auto [p1, p2] = SlicePoses(q, theta, slice);
  const int eps = Unwind(side);
  const double g1 =
      p1.layout.first_tooth_angle + p1.layout.sense * tooth1 * pinion_.angular_pitch();
  const double g2 = p2.layout.first_tooth_angle + p2.layout.sense * tooth2 * gear_.angular_pitch();
  InvoluteFlankPose f1 = MakeFlankPose(pinion_, p1.center, g1, eps);
  InvoluteFlankPose f2 = MakeFlankPose(gear_, p2.center, g2, eps);
  SliceToothContact out;
  out.transverse = CalcInvoluteContact(f1, f2);
  if (!out.transverse.found) return out;
  Vector2 point = out.transverse.point;
  if (p1.helix_factor != 0.0 || p2.helix_factor != 0.0) {
    // Axial displacement at the contact point acts as a rotation (helical only).
    f1.base_angle += p1.AngleAt(point) - p1.angle;
    f2.base_angle += p2.AngleAt(point) - p2.angle;
    out.transverse = CalcInvoluteContact(f1, f2);
    if (!out.transverse.found) return out;
  }
  const FlankContact& t = out.transverse;
  const double y = slice_position(slice);
  const double zs = frame_.reference_point.z() + y;
  // Normal penetration δ_n = δ_t cos β_b − e and its pose gradient.
  PoseGradient grad = cos_base_helix_ * t.d_penetration;
  if (modifications_ && !modifications_->empty()) {
    const bool coast = side == FlankSide::kCoast;
    const ReliefValue e1 = modifications_->Pinion(coast, t.roll1);
    const ReliefValue e2 = modifications_->Gear(coast, t.roll2);
    out.separation = e1.value + e2.value + modifications_->Lead(coast, y);
    grad -= e1.slope * t.d_roll1 + e2.slope * t.d_roll2;
  }
  out.penetration = cos_base_helix_ * t.penetration - out.separation;
  const PoseJacobian j1 = SliceJacobian(p1, zs - frame_.pinion_center.z(), point);
  const PoseJacobian j2 = SliceJacobian(p2, zs - frame_.gear_center.z(), point);
  out.d_penetration.head<6>() = (grad.head<3>() * j1).transpose();
  out.d_penetration.tail<6>() = (grad.tail<3>() * j2).transpose();
  const double dbeta1 = s_ / static_cast<double>(pinion_.teeth);
  const double dbeta2 = -s_ / static_cast<double>(gear_.teeth);
  out.d_penetration_d_phase = grad(2) * dbeta1 + grad(5) * dbeta2;
  out.point = Vector3(t.point.x(), t.point.y(), zs);
  out.sigma = (out.point - frame_.reference_point).dot(frame_.sigma);
  if (q_rate != nullptr) {
    out.approach_rate = out.d_penetration.dot(*q_rate) + out.d_penetration_d_phase * theta_rate;
    Vector3 r1 = j1 * q_rate->head<6>();
    Vector3 r2 = j2 * q_rate->tail<6>();
    r1.z() += dbeta1 * theta_rate;
    r2.z() += dbeta2 * theta_rate;
    out.sliding_rate = CalcContactRates(t, f1.center, r1, f2.center, r2).sliding;
  }
  return out;
}

}  // namespace geardyn
