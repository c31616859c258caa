/// @file
/// @brief The ComputeModes benchmark body shared by modal_benchmark and geared_shafts_benchmark:
/// m = min(20, n/2) modes by a forced method, and (ARPACK, n ≤ 1 100) the max relative difference
/// of the returned nonzero eigenvalues against the dense path, computed once outside the timed
/// loop.
#pragma once

#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "geardyn/analyses/modal.hpp"

namespace geardyn::bench {

inline ModalOptions ModesBenchmarkOptions(ModalMethod method, int n) {
  ModalOptions o;
  o.method = method;
  o.num_modes = std::min(20, n / 2);
  return o;
}

/// Times ComputeModes on `model`; counters dofs, modes, ops, rel_diff (and f1_hz if asked).
inline void RunModesBenchmark(benchmark::State& state, const SystemModel& model, ModalMethod method,
                              bool report_first_frequency = false) {
  const int n = model.num_dofs();
  ModalResult r;
  for (auto _ : state) {
    r = ComputeModes(model, ModesBenchmarkOptions(method, n));
    benchmark::DoNotOptimize(r.eigenvalues.data());
  }
  if (!r.summary.ok() || r.method_used != method) {
    state.SkipWithError(("not ok or wrong method: " + r.summary.BriefReport()).c_str());
    return;
  }
  state.counters["dofs"] = n;
  state.counters["modes"] = static_cast<double>(r.eigenvalues.size());
  if (report_first_frequency) state.counters["f1_hz"] = r.frequencies_hz(r.num_rigid_body_modes);
  if (r.summary.counters.count("operator_applications") != 0) {
    state.counters["ops"] = static_cast<double>(r.summary.counters.at("operator_applications"));
  }
  if (method == ModalMethod::kArpack && n <= 1100) {
    const ModalResult dense = ComputeModes(model, ModesBenchmarkOptions(ModalMethod::kDense, n));
    double worst = 0.0;
    for (Eigen::Index k = 0; k < r.eigenvalues.size(); ++k) {
      if (dense.eigenvalues(k) > 0.0) {
        worst = std::max(worst, std::abs(r.eigenvalues(k) / dense.eigenvalues(k) - 1.0));
      }
    }
    state.counters["rel_diff"] = worst;
  }
}

}  // namespace geardyn::bench
