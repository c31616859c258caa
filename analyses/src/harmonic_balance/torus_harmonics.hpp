/// @file
/// @brief The kept orders κ ∈ Z^d, |κ|_1 ≤ H, of the quasi-periodic harmonic balances
/// (quasi_periodic_hb.hpp, nonlinear_quasi_periodic_hb.hpp), in one fixed order: both solvers
/// enumerate S the same way, so a linear solution seeds the nonlinear Newton index by index.
#pragma once

#include <cstdint>
#include <cstdlib>
#include <unordered_map>
#include <vector>

#include "geardyn/analyses/quasi_periodic_hb.hpp"

namespace geardyn::internal {

/// @brief Refuses a total order H below a base's period P_b (tooth errors repeating every P_b
/// mesh cycles): H counts harmonics of Ω_b = r_b ω_m / P_b, so the mesh frequency itself is
/// order P_b, and H < P_b would drop it (and every mesh harmonic) silently.
/// @throws InvalidInput naming `field`, the mesh, P_b and H.
void CheckOrderCoversMeshFrequencies(const SystemModel& model,
                                     const std::vector<QuasiPeriodicBase>& bases, int total_order,
                                     const char* field);

/// The kept orders κ (|κ|_1 ≤ H) and their index.
class HarmonicSet {
 public:
  HarmonicSet(int d, int H) : d_(d), H_(H) {
    std::vector<int> k(static_cast<std::size_t>(d), 0);
    Enumerate(0, H, &k);
    for (std::size_t i = 0; i < orders_.size(); ++i) index_[Key(orders_[i])] = static_cast<int>(i);
  }
  int size() const { return static_cast<int>(orders_.size()); }
  const std::vector<int>& order(int i) const { return orders_[static_cast<std::size_t>(i)]; }
  /// Index of κ, −1 when |κ|_1 > H.
  int Find(const std::vector<int>& k) const {
    int norm = 0;
    for (int v : k) norm += std::abs(v);
    if (norm > H_) return -1;
    return index_.at(Key(k));
  }

 private:
  void Enumerate(int axis, int budget, std::vector<int>* k) {
    if (axis == d_) {
      orders_.push_back(*k);
      return;
    }
    for (int v = -budget; v <= budget; ++v) {
      (*k)[static_cast<std::size_t>(axis)] = v;
      Enumerate(axis + 1, budget - std::abs(v), k);
    }
    (*k)[static_cast<std::size_t>(axis)] = 0;
  }
  std::int64_t Key(const std::vector<int>& k) const {
    std::int64_t key = 0;
    for (int v : k) key = key * (2 * H_ + 1) + (v + H_);
    return key;
  }
  int d_, H_;
  std::vector<std::vector<int>> orders_;
  std::unordered_map<std::int64_t, int> index_;
};

}  // namespace geardyn::internal
