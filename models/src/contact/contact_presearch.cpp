#include "geardyn/models/contact/contact_presearch.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace geardyn {

namespace {

// Half angle A of the lens of the two tip disks seen from the centre of the first one.
double LensHalfAngle(double c, double ra_own, double ra_mate) {
  if (ra_mate >= c) return std::numbers::pi;  // own centre inside the mate's disk
  if (c * c - ra_mate * ra_mate <= ra_own * ra_own) {
    return std::asin(std::min(1.0, ra_mate / c));  // tangent points inside the own disk
  }
  const double cos_a = (c * c + ra_own * ra_own - ra_mate * ra_mate) / (2.0 * c * ra_own);
  return std::acos(std::clamp(cos_a, -1.0, 1.0));
}

// Range [j0, j1] of signed tooth steps j (γ = γ0 + j Δ) whose windows meet [a − w, a + w].
void StepRange(double first, double pitch, double a, double w, long long* j0, long long* j1) {
  *j0 = static_cast<long long>(std::ceil((a - w - first) / pitch));
  *j1 = static_cast<long long>(std::floor((a + w - first) / pitch));
}

int Wrap(long long j, int z) { return static_cast<int>(((j % z) + z) % z); }

}  // namespace

int FindCandidatePairs(const ToothFlankGeometry& geometry1, const ToothLayout& layout1,
                       const ToothFlankGeometry& geometry2, const ToothLayout& layout2,
                       double margin, std::span<ToothPairCandidate> out) {
  const Vector2 d = layout2.center - layout1.center;
  const double c = d.norm();
  if (!(c < geometry1.tip_radius + geometry2.tip_radius)) return 0;
  const double a1 = std::atan2(d.y(), d.x());
  const double a2 = a1 + std::numbers::pi;
  const double w1 = LensHalfAngle(c, geometry1.tip_radius, geometry2.tip_radius) +
                    geometry1.base_half_angle + margin;
  const double w2 = LensHalfAngle(c, geometry2.tip_radius, geometry1.tip_radius) +
                    geometry2.base_half_angle + margin;
  const double p1 = geometry1.angular_pitch(), p2 = geometry2.angular_pitch();
  long long j10 = 0, j11 = 0, j20 = 0, j21 = 0;
  StepRange(layout1.first_tooth_angle, p1, a1, w1, &j10, &j11);
  StepRange(layout2.first_tooth_angle, p2, a2, w2, &j20, &j21);
  // A window wider than the circle holds every tooth once.
  j11 = std::min(j11, j10 + geometry1.teeth - 1);
  j21 = std::min(j21, j20 + geometry2.teeth - 1);
  int count = 0;
  const int capacity = static_cast<int>(out.size());
  for (long long j1 = j10; j1 <= j11; ++j1) {
    const int i1 = Wrap(layout1.sense * j1, geometry1.teeth);
    for (long long j2 = j20; j2 <= j21; ++j2) {
      if (count < capacity) out[count] = {i1, Wrap(layout2.sense * j2, geometry2.teeth)};
      ++count;
    }
  }
  return count;
}

}  // namespace geardyn
