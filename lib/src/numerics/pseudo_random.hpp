/// @file
/// @brief Internal: a portable, seeded pseudo-random vector (SplitMix64), the same on every
/// platform and standard library, for start vectors and condition estimates that must be
/// reproducible run to run.
#pragma once

#include <cstdint>

#include "geardyn/common/eigen_types.hpp"

namespace geardyn::internal {

/// @brief Fills `v` (size kept) with values uniform in [−1, 1) from SplitMix64 seeded by `seed`.
inline void FillPseudoRandom(std::uint64_t seed, VectorX* v) {
  std::uint64_t state = seed;
  for (Eigen::Index i = 0; i < v->size(); ++i) {
    state += 0x9E3779B97F4A7C15ULL;
    std::uint64_t z = state;
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    z ^= z >> 31;
    // 53 random bits → [0, 1) → [−1, 1).
    (*v)(i) = 2.0 * (static_cast<double>(z >> 11) * 0x1.0p-53) - 1.0;
  }
}

}  // namespace geardyn::internal
