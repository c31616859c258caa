/// @file
/// @brief Pre-search of the contact simulator (spec 03; Kim et al. §3.4): from the two gears'
/// poses, the few tooth pairs whose angular windows can touch, in O(candidates), not O(z1·z2).
///
/// Material of gear k near the mesh lies inside its tip circle (c_k, r_ak); two teeth can touch
/// only inside the lens where the two tip disks overlap. Seen from c_k that lens spans the polar
/// angles ∠ê_k ± A_k (ê_1 = ê towards c2, ê_2 = −ê), with A_k the angle of the tip circles'
/// intersection points,
/// \f[ \cos A_1 = (C^2 + r_{a1}^2 − r_{a2}^2)/(2 C r_{a1}), \f]
/// or asin(r_a2/C) when the tangent points from c1 to circle 2 lie inside circle 1. A tooth with
/// centre line at γ occupies the polar angles γ ± ψ_b (the involute narrows outwards from the
/// base circle, where its half angle is ψ_b; the fillet below r_b is taken as no wider), widened
/// by a caller's margin for tooth deflections. Every tooth whose window meets the lens window is
/// a candidate; every pair of candidates is returned (both flanks of a pair are then checked by
/// the kernel). A pair outside this list cannot touch (tested against an all-pairs search).
#pragma once

#include <span>

#include "geardyn/common/eigen_types.hpp"
#include "geardyn/models/contact/tooth_flank.hpp"

namespace geardyn {

/// @brief Tooth layout of one gear in the world: tooth i's centre line is at
/// γ_i = first_tooth_angle + sense · i · 2π/z (i ∈ [0, z)).
struct ToothLayout {
  Vector2 center = Vector2::Zero();  ///< c, centre of the gear [m]
  double first_tooth_angle = 0.0;    ///< γ_0, world angle of tooth 0's centre line [rad]
  int sense = 1;                     ///< ±1, direction of increasing tooth index
};

/// @brief A pair of teeth that may touch.
struct ToothPairCandidate {
  int tooth1 = 0;  ///< tooth index on gear 1, in [0, z1)
  int tooth2 = 0;  ///< tooth index on gear 2, in [0, z2)
};

/// @brief The candidate pairs of the @file. Never allocates.
/// @param[in] geometry1, layout1 gear 1 (the pinion).
/// @param[in] geometry2, layout2 gear 2.
/// @param[in] margin extra angular half width of each tooth window ≥ 0 [rad] (deflections).
/// @param[out] out candidates, filled up to its size.
/// @return the number of candidates found (may exceed out.size(): then only the first out.size()
///   are written and the caller must retry with a larger buffer); 0 when the tip circles do not
///   overlap.
int FindCandidatePairs(const ToothFlankGeometry& geometry1, const ToothLayout& layout1,
                       const ToothFlankGeometry& geometry2, const ToothLayout& layout2,
                       double margin, std::span<ToothPairCandidate> out);

}  // namespace geardyn
