/// @file
/// @brief The parts of `geardyn compare` (compare_runner.hpp) behind RunCompare: the DTE of one
/// level over the grid (compare_dte.cpp) and the verdicts of a level against the references
/// (compare_verdicts.cpp). Internal to the command.
#pragma once

#include <chrono>
#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "geardyn/compare_runner.hpp"
#include "geardyn/system/system_model.hpp"

namespace geardyn::app::compare_internal {

inline constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
/// Up and down branches closer than this fraction of the peak are one branch: a jump changes the
/// RMS by far more, and time-domain branches differ by their steady-state tolerance (1e-3 in the
/// Kim runs) where no jump is.
inline constexpr double kBranchSplit = 1e-2;

/// Seconds since `start`.
inline double Seconds(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

/// Writes one progress line.
using ProgressLine = std::function<void(const std::string&)>;

/// DTE of mesh `mesh` by the linear HB on the grid; δ_η = DTE + ε_η (compare_runner.hpp).
LevelDte LinearDte(const SystemModel& model, int mesh, const std::vector<double>& grid,
                   std::vector<std::string>* warnings);
/// DTE by the traced nonlinear HB, read on the grid along both sweep branches.
LevelDte NonlinearDte(const SystemModel& model, int mesh, const std::vector<double>& grid,
                      const CompareSettings& settings);
/// DTE by the time-domain up/down sweeps (one steady run for a single frequency).
LevelDte TimeDomainDte(const SystemModel& model, int mesh, const std::vector<double>& grid,
                       const CompareSettings& settings, const ProgressLine& progress_line,
                       const std::string& level);
/// The scene at level lti excited by the loaded static TE of blankenship_singh (see the .cpp),
/// or nullopt with the reason.
std::optional<Scene> LtiWithLoadedSte(const Scene& scene, std::string* why);
/// True when the up and down branches differ somewhere by more than kBranchSplit of the peak.
bool IsMultivalued(const LevelDte& d);

/// A Floquet result with a verdict and a finite max|λ|.
bool FloquetDetermined(const FloquetResult& r);
/// The first `count` modes of a result (frequencies, shapes, labels, groups inside the range).
ModalResult FirstModes(const ModalResult& r, int count);
/// The run of `level`, or nullptr.
const LevelRun* FindRun(const CompareResult& result, const std::string& level);
/// One level against the references of `result` (verdicts and notes).
LevelComparison CompareToReferences(const LevelRun& run, const CompareResult& result,
                                    const CompareSettings& settings);

}  // namespace geardyn::app::compare_internal
