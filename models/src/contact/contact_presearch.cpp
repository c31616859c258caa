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

// Range of h = ρ sin φ (signed distance from the line of centres) over ρ ∈ [lo, hi] and
// φ ∈ [a − w, a + w] (|φ| < π/2 on the lens; outside, the whole range [−hi, hi]).
void OffsetRange(double a, double w, double lo, double hi, double* h0, double* h1) {
  const double p0 = a - w, p1 = a + w;
  if (p0 <= -0.5 * std::numbers::pi || p1 >= 0.5 * std::numbers::pi) {
    *h0 = -hi;
    *h1 = hi;
    return;
  }
  const double s0 = std::sin(p0), s1 = std::sin(p1);
  *h0 = std::min({lo * s0, hi * s0});
  *h1 = std::max({lo * s1, hi * s1});
}

constexpr int kMaxWindowTeeth = 64;

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
  // Pair only teeth whose offsets h from the line of centres can coincide: a common point X
  // has ρ1 sin φ1 = −ρ2 sin φ2 (φ_k its polar angle from ê resp. −ê), ρ_k ∈ [C − r_a,mate, r_ak].
  const long long n1 = j11 - j10 + 1, n2 = j21 - j20 + 1;
  const bool filter = n1 <= kMaxWindowTeeth && n2 <= kMaxWindowTeeth;
  double h2lo[kMaxWindowTeeth], h2hi[kMaxWindowTeeth];
  const double lo1 = std::max(0.0, c - geometry2.tip_radius);
  const double lo2 = std::max(0.0, c - geometry1.tip_radius);
  const double half1 = geometry1.base_half_angle + margin;
  const double half2 = geometry2.base_half_angle + margin;
  if (filter) {
    for (long long j2 = j20; j2 <= j21; ++j2) {
      const double phi = std::remainder(
          layout2.first_tooth_angle + static_cast<double>(j2) * p2 - a2, 2.0 * std::numbers::pi);
      double h0 = 0.0, h1 = 0.0;
      OffsetRange(phi, half2, lo2, geometry2.tip_radius, &h0, &h1);
      h2lo[j2 - j20] = -h1;  // h = −ρ2 sin φ2
      h2hi[j2 - j20] = -h0;
    }
  }
  int count = 0;
  const int capacity = static_cast<int>(out.size());
  for (long long j1 = j10; j1 <= j11; ++j1) {
    const int i1 = Wrap(layout1.sense * j1, geometry1.teeth);
    double h0 = 0.0, h1 = 0.0;
    if (filter) {
      const double phi = std::remainder(
          layout1.first_tooth_angle + static_cast<double>(j1) * p1 - a1, 2.0 * std::numbers::pi);
      OffsetRange(phi, half1, lo1, geometry1.tip_radius, &h0, &h1);
    }
    for (long long j2 = j20; j2 <= j21; ++j2) {
      if (filter && (h2hi[j2 - j20] < h0 || h2lo[j2 - j20] > h1)) continue;
      if (count < capacity) out[count] = {i1, Wrap(layout2.sense * j2, geometry2.teeth)};
      ++count;
    }
  }
  return count;
}

}  // namespace geardyn
