#include "geardyn/models/contact/mesh_kinematics.hpp"

#include <cmath>
#include <numbers>
#include <type_traits>

#include "geardyn/common/check.hpp"
#include "geardyn/models/contact/tip_corner_contact.hpp"
#include "geardyn/models/contact/tooth_pose.hpp"

namespace geardyn {

namespace {

/// Largest slice count: 1000 slices already resolve a crowning parabola to 1e-6 of its amount.
constexpr int kMaxSlices = 1000;

using PoseJacobian = Eigen::Matrix<double, 3, 6>;  // ∂(cx, cy, β)/∂(x, y, z, θx, θy, θz)

// ∂(cx, cy, φ)/∂q_k of a slice pose without the axial term.
PoseJacobian SliceJacobian(double dz) {
  PoseJacobian j = PoseJacobian::Zero();
  j(0, 0) = 1.0;
  j(0, 4) = dz;  // θy moves the slice centre by +θy Δz along X
  j(1, 1) = 1.0;
  j(1, 3) = -dz;  // θx moves it by −θx Δz along Y
  j(2, 5) = 1.0;
  return j;
}

// Δ = −f w(P) = −f (z + θx (P_y − c_y) − θy (P_x − c_x)): its explicit gradient with respect to
// q_k (P, c held) and to P (∂Δ/∂c = −∂Δ/∂P).
Eigen::Matrix<double, 1, 6> AxialGradientQ(const GearSlicePose& pose, const Vector2& point) {
  Eigen::Matrix<double, 1, 6> g = Eigen::Matrix<double, 1, 6>::Zero();
  const double f = pose.helix_factor;
  g(2) = -f;
  g(3) = -f * (point.y() - pose.center.y());
  g(4) = f * (point.x() - pose.center.x());
  return g;
}
Eigen::Matrix<double, 1, 2> AxialGradientP(const GearSlicePose& pose) {
  return -pose.helix_factor * Eigen::Matrix<double, 1, 2>(-pose.tilt.y(), pose.tilt.x());
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
                                                       const Vector12* q_rate, double theta_rate,
                                                       const ToothPairState* teeth) const {
  // State columns: [q_pair (12), θ, pinion tooth (ψ, τ_r, τ_t), gear tooth (ψ, τ_r, τ_t)].
  using Row = Eigen::Matrix<double, 1, kStateSize>;
  using Slice = Eigen::Matrix<double, 3, kStateSize>;  // ∂(c_k, φ_k)/∂state of a slice pose
  // Named references, not a structured binding: the lambdas below capture them, which clang
  // before 16 rejects for structured bindings (the fuzz build, docs/fuzzing.md, uses clang 14).
  const std::pair<GearSlicePose, GearSlicePose> poses = SlicePoses(q, theta, slice);
  const GearSlicePose& p1 = poses.first;
  const GearSlicePose& p2 = poses.second;
  const int eps = Unwind(side);
  const double y = slice_position(slice);
  const double zs = frame_.reference_point.z() + y;
  // Tooth centre lines in the gear body frames (relative to the gears' angles).
  const double rel1 = tooth0_pinion_ + p1.layout.sense * tooth1 * pinion_.angular_pitch();
  const double rel2 = tooth0_gear_ + p2.layout.sense * tooth2 * gear_.angular_pitch();
  const ToothDeflection none;
  const ToothDeflection& d1 = teeth != nullptr ? teeth->pinion : none;
  const ToothDeflection& d2 = teeth != nullptr ? teeth->gear : none;
  // Rigid teeth (teeth == nullptr) have no tooth columns; with teeth they are filled below.
  Slice s1 = Slice::Zero(), s2 = Slice::Zero();
  s1.block<3, 6>(0, 0) = SliceJacobian(zs - frame_.pinion_center.z());
  s2.block<3, 6>(0, 6) = SliceJacobian(zs - frame_.gear_center.z());
  const double dbeta1 = s_ / static_cast<double>(pinion_.teeth);
  const double dbeta2 = -s_ / static_cast<double>(gear_.teeth);
  s1(2, 12) = dbeta1;
  s2(2, 12) = dbeta2;
  double angle1 = p1.angle, angle2 = p2.angle;
  InvoluteFlankPose f1, f2;
  Eigen::Matrix<double, 3, 6> j1, j2;  // ∂(c′, β)/∂(c, φ, ψ, τ_r, τ_t) of each tooth
  // M ∂(c′1, β1, c′2, β2)/∂state for an R×6 M, without forming the 6×19 matrix: the slice
  // columns through ∂(c′, β)/∂(c, φ) · s_k, the tooth columns directly.
  auto chain = [&](const auto& m) {
    using M = std::decay_t<decltype(m)>;
    constexpr int kRows = M::RowsAtCompileTime;
    const Eigen::Matrix<double, kRows, 3> a1 = m.template leftCols<3>() * j1.leftCols<3>();
    const Eigen::Matrix<double, kRows, 3> a2 = m.template rightCols<3>() * j2.leftCols<3>();
    Eigen::Matrix<double, kRows, kStateSize> r = a1 * s1 + a2 * s2;
    r.template middleCols<3>(13) += m.template leftCols<3>() * j1.rightCols<3>();
    r.template middleCols<3>(16) += m.template rightCols<3>() * j2.rightCols<3>();
    return r;
  };
  // Flank poses of the (deflected) teeth at the gear angles and their gradient.
  auto place = [&] {
    if (teeth == nullptr) {  // rigid teeth: c′ = c, β = φ + γ (no trigonometry)
      f1 = MakeFlankPose(pinion_, p1.center, angle1 + rel1, eps);
      f2 = MakeFlankPose(gear_, p2.center, angle2 + rel2, eps);
      j1.setZero();
      j1.leftCols<3>().setIdentity();
      j2 = j1;
      return;
    }
    const EffectiveBaseCircle e1 =
        CalcEffectiveBaseCircle(p1.center, angle1, rel1, pinion_.pivot_radius, d1);
    const EffectiveBaseCircle e2 =
        CalcEffectiveBaseCircle(p2.center, angle2, rel2, gear_.pivot_radius, d2);
    f1 = MakeFlankPose(pinion_, e1.center, e1.angle + rel1, eps);
    f2 = MakeFlankPose(gear_, e2.center, e2.angle + rel2, eps);
    j1 = e1.jacobian;
    j2 = e2.jacobian;
  };
  // Flank–flank contact, or a tip corner where the involute point lies beyond a flank's end.
  auto contact = [&] {
    const FlankContact c = CalcInvoluteContact(f1, f2);
    if (!c.found || c.valid) return c;
    if (c.roll1 > f1.roll_max) return CalcTipCornerContact(f1, pinion_.tip_corner_radius, f2);
    if (c.roll2 > f2.roll_max) {
      return SwapBodies(CalcTipCornerContact(f2, gear_.tip_corner_radius, f1));
    }
    return c;
  };
  place();
  SliceToothContact out;
  out.transverse = contact();
  if (!out.transverse.found) return out;
  if (p1.helix_factor != 0.0 || p2.helix_factor != 0.0) {
    // Axial displacement at the contact point P (of the pass without it) turns each gear's
    // section by Δ_k = −f_k w_k(P) (helical only); its gradient includes P's own dependence on
    // the state. The deflected tooth turns with its gear (Δ enters through ∂c′/∂φ).
    const Vector2 point = out.transverse.point;
    const Eigen::Matrix<double, 2, kStateSize> d_point = chain(out.transverse.d_point);
    Row dd1 = AxialGradientP(p1) * (d_point - s1.topRows<2>());
    Row dd2 = AxialGradientP(p2) * (d_point - s2.topRows<2>());
    dd1.segment<6>(0) += AxialGradientQ(p1, point);
    dd2.segment<6>(6) += AxialGradientQ(p2, point);
    s1.row(2) += dd1;
    s2.row(2) += dd2;
    angle1 = p1.AngleAt(point);
    angle2 = p2.AngleAt(point);
    place();
    out.transverse = contact();
    if (!out.transverse.found) return out;
  }
  const FlankContact& t = out.transverse;
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
  const Row full = chain(grad);
  out.d_penetration = full.head<12>().transpose();
  out.d_penetration_d_phase = full(12);
  out.d_pinion_tooth = full.segment<3>(13);
  out.d_gear_tooth = full.segment<3>(16);
  out.point = Vector3(t.point.x(), t.point.y(), zs);
  out.sigma = (out.point - frame_.reference_point).dot(frame_.sigma);
  if (q_rate != nullptr || teeth != nullptr) {
    Eigen::Matrix<double, kStateSize, 1> rate = Eigen::Matrix<double, kStateSize, 1>::Zero();
    if (q_rate != nullptr) rate.head<12>() = *q_rate;
    rate(12) = theta_rate;
    if (teeth != nullptr) {
      rate.segment<3>(13) << teeth->pinion_rate.rotation, teeth->pinion_rate.radial,
          teeth->pinion_rate.tangential;
      rate.segment<3>(16) << teeth->gear_rate.rotation, teeth->gear_rate.radial,
          teeth->gear_rate.tangential;
    }
    out.approach_rate = full.dot(rate.transpose());
    // Pose rates: ∂(c′, β)/∂(c, φ) (s_k · rate) + ∂(c′, β)/∂tooth · tooth rate.
    Eigen::Matrix<double, 6, 1> pose_rate;
    pose_rate.head<3>() = j1.leftCols<3>() * (s1 * rate) + j1.rightCols<3>() * rate.segment<3>(13);
    pose_rate.tail<3>() = j2.leftCols<3>() * (s2 * rate) + j2.rightCols<3>() * rate.segment<3>(16);
    out.sliding_rate =
        CalcContactRates(t, f1.center, pose_rate.head<3>(), f2.center, pose_rate.tail<3>()).sliding;
  } else {
    out.approach_rate = full(12) * theta_rate;
  }
  return out;
}

}  // namespace geardyn
