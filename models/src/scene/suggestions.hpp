/// @file
/// @brief "Did you mean" hints and name lists for scene error messages (internal to the scene
/// reader).
#pragma once

#include <algorithm>
#include <cstddef>
#include <limits>
#include <string>
#include <string_view>

namespace geardyn::internal {

/// @brief Levenshtein distance between `a` and `b` (insertions, deletions, substitutions).
std::size_t EditDistance(std::string_view a, std::string_view b);

/// @brief The candidate closest to `word` by edit distance (or by a prefix relation, as in
/// "speed" → "speed_rpm") if it is close enough to be a plausible typo; empty otherwise.
/// @param[in] candidates a range of strings convertible to std::string_view
template <typename Range>
std::string Closest(std::string_view word, const Range& candidates) {
  std::string best;
  std::size_t best_distance = std::numeric_limits<std::size_t>::max();
  for (const auto& candidate_ref : candidates) {
    const std::string_view candidate(candidate_ref);
    std::size_t d = EditDistance(word, candidate);
    const std::size_t limit = std::max<std::size_t>(2, word.size() / 3);
    const bool prefix = word.size() >= 3 && (candidate.substr(0, word.size()) == word ||
                                             word.substr(0, candidate.size()) == candidate);
    if (d > limit && !prefix) continue;
    if (prefix) d = std::min<std::size_t>(d, limit);
    if (d < best_distance) {
      best_distance = d;
      best = std::string(candidate);
    }
  }
  return best;
}

/// @brief " (did you mean 'X'?)" for the Closest candidate X, or empty if there is none.
template <typename Range>
std::string DidYouMean(std::string_view word, const Range& candidates) {
  const std::string best = Closest(word, candidates);
  return best.empty() ? std::string() : " (did you mean '" + best + "'?)";
}

/// @brief The names separated by ", ", or "none" if there are none.
template <typename Range>
std::string JoinNames(const Range& names) {
  std::string out;
  for (const auto& n : names) {
    if (!out.empty()) out += ", ";
    out += std::string_view(n);
  }
  return out.empty() ? std::string("none") : out;
}

}  // namespace geardyn::internal
