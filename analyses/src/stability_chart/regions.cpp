// Step 3 of ComputeStabilityChart: the unstable regions (4-connected components) and their
// resonance labels (stability_chart.hpp), and ListResonances.
#include <algorithm>
#include <cmath>
#include <map>
#include <string>

#include "stability_chart/chart_internal.hpp"

namespace geardyn {
namespace {

std::string ResonanceLabel(ResonanceKind kind, int p, int q, int k) {
  const std::string order = "/" + std::to_string(k);
  switch (kind) {
    case ResonanceKind::kPrincipal:
      return "2f_" + std::to_string(p) + order;
    case ResonanceKind::kSumCombination:
      return "(f_" + std::to_string(p) + "+f_" + std::to_string(q) + ")" + order;
    case ResonanceKind::kDifferenceCombination:
      return "(f_" + std::to_string(q) + "-f_" + std::to_string(p) + ")" + order;
  }
  return {};
}

}  // namespace

std::vector<Resonance> ListResonances(const std::vector<double>& f, int max_order,
                                      bool difference_combinations, int first_mode_index) {
  const int base = first_mode_index;
  std::vector<Resonance> out;
  const int m = static_cast<int>(f.size());
  for (int k = 1; k <= max_order; ++k) {
    for (int p = 0; p < m; ++p) {
      if (!(f[p] > 0.0)) continue;  // rigid-body modes have no parametric resonance
      out.push_back({ResonanceKind::kPrincipal, p + base, 0, k, 2.0 * f[p] / k,
                     ResonanceLabel(ResonanceKind::kPrincipal, p + base, 0, k)});
      for (int q = p + 1; q < m; ++q) {
        if (!(f[q] > 0.0)) continue;
        out.push_back({ResonanceKind::kSumCombination, p + base, q + base, k, (f[p] + f[q]) / k,
                       ResonanceLabel(ResonanceKind::kSumCombination, p + base, q + base, k)});
        const double diff = std::abs(f[q] - f[p]);
        if (difference_combinations && diff > 0.0) {
          // Label with the higher mode first: (f_q − f_p) for f_q > f_p.
          const bool q_higher = f[q] >= f[p];
          const int hi = q_higher ? q + base : p + base, lo = q_higher ? p + base : q + base;
          out.push_back({ResonanceKind::kDifferenceCombination, lo, hi, k, diff / k,
                         ResonanceLabel(ResonanceKind::kDifferenceCombination, lo, hi, k)});
        }
      }
    }
  }
  std::stable_sort(out.begin(), out.end(), [](const Resonance& a, const Resonance& b) {
    return a.mesh_frequency_hz < b.mesh_frequency_hz;
  });
  return out;
}

namespace internal {
namespace {

// Index of the resonance nearest f_m in relative distance |f_m − f_c| / f_c (−1 if none).
int NearestResonance(const std::vector<Resonance>& list, double f_m) {
  int best = -1;
  double best_d = 0.0;
  for (int r = 0; r < static_cast<int>(list.size()); ++r) {
    const double d = std::abs(f_m - list[r].mesh_frequency_hz) / list[r].mesh_frequency_hz;
    if (best < 0 || d < best_d) {
      best = r;
      best_d = d;
    }
  }
  return best;
}

}  // namespace

void FindRegions(const StabilityChartOptions& options, StabilityChartResult* chart) {
  StabilityChartResult& c = *chart;
  const int nx = c.x_axis.num_points, ny = c.y_axis.num_points;
  const auto unstable = [&c](int i) { return c.ok[i] && !c.stable[i]; };

  // Candidate resonances per row (one shared list when a single list is given).
  const std::size_t lists = options.natural_frequencies_hz.size();
  std::vector<std::vector<Resonance>> candidates(lists);
  for (std::size_t r = 0; r < lists; ++r) {
    candidates[r] = ListResonances(options.natural_frequencies_hz[r], options.max_resonance_order,
                                   options.difference_combinations, options.first_mode_index);
  }

  std::vector<int> stack;
  for (int start = 0; start < nx * ny; ++start) {
    if (!unstable(start) || c.region[start] >= 0) continue;
    const int id = static_cast<int>(c.regions.size());
    ChartRegion region;
    // Votes: (row list, resonance index) → summed growth.
    std::map<std::pair<int, int>, double> votes;
    double weight_sum = 0.0, weighted_f = 0.0;
    bool all_f_known = true;
    c.region[start] = id;
    stack.assign(1, start);
    while (!stack.empty()) {
      const int i = stack.back();
      stack.pop_back();
      const int ix = i % nx, iy = i / nx;
      ++region.num_points;
      region.centroid_x += c.x_axis.Value(ix);
      region.centroid_y += c.y_axis.Value(iy);
      region.max_abs_multiplier = std::max(region.max_abs_multiplier, c.max_abs_multiplier[i]);
      const double f_m = c.mesh_frequency_hz[i];
      // Growth weight; the floor keeps points at the threshold in the vote.
      const double w = std::max(c.max_abs_multiplier[i] - 1.0, 1e-300);
      if (f_m > 0.0) {
        weight_sum += w;
        weighted_f += w * f_m;
        if (lists > 0) {
          const int list = lists == 1 ? 0 : iy;
          const int r = NearestResonance(candidates[list], f_m);
          if (r >= 0) votes[{list, r}] += w;
        }
      } else {
        all_f_known = false;
      }
      const int next[4][2] = {{ix - 1, iy}, {ix + 1, iy}, {ix, iy - 1}, {ix, iy + 1}};
      for (const auto& n : next) {
        if (n[0] < 0 || n[0] >= nx || n[1] < 0 || n[1] >= ny) continue;
        const int j = c.index(n[0], n[1]);
        if (unstable(j) && c.region[j] < 0) {
          c.region[j] = id;
          stack.push_back(j);
        }
      }
    }
    region.centroid_x /= region.num_points;
    region.centroid_y /= region.num_points;
    if (weight_sum > 0.0) region.mean_mesh_frequency_hz = weighted_f / weight_sum;
    if (!votes.empty() && all_f_known) {
      // Resonances are compared by label, so that rows with their own lists vote together.
      std::map<std::string, double> by_label;
      for (const auto& [key, w] : votes) by_label[candidates[key.first][key.second].label] += w;
      auto best = votes.begin();
      double best_w = -1.0;
      for (auto it = votes.begin(); it != votes.end(); ++it) {
        const double w = by_label[candidates[it->first.first][it->first.second].label];
        if (w > best_w) {  // first (lowest row, then lowest f_m) wins a tie: deterministic
          best_w = w;
          best = it;
        }
      }
      region.labelled = true;
      region.resonance = candidates[best->first.first][best->first.second];
      region.vote_share = best_w / weight_sum;
    }
    c.regions.push_back(std::move(region));
  }
}

}  // namespace internal
}  // namespace geardyn
