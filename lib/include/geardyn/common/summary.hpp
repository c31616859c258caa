/// @file
/// @brief Summary: the status report every analysis result carries (spec 02; architecture §3.3).
#pragma once

#include <map>
#include <string>
#include <vector>

namespace geardyn {

/// Numerical outcome of an analysis. Never an exception: see errors.hpp for those.
/// kInterrupted: the caller's cancel flag stopped the run; the result holds what was computed
/// before it (every point that is there is complete).
enum class Status { kSuccess, kNotConverged, kNumericalIssue, kToleranceNotMet, kInterrupted };

/// @brief Text name of a status ("success", "not_converged", ...), stable for JSON output.
const char* StatusName(Status status);

/// @brief Status, message, error estimate, counters, wall time and warnings of one analysis run.
struct Summary {
  Status status = Status::kSuccess;
  std::string message;                   ///< Why the status is not kSuccess (empty otherwise).
  double error_estimate = 0.0;           ///< Analysis-specific error estimate (documented there).
  std::map<std::string, long> counters;  ///< e.g. {"steps", 120}, {"factorizations", 3}.
  double wall_time_s = 0.0;              ///< Wall-clock time of the analysis [s].
  std::vector<std::string> warnings;     ///< Non-fatal diagnostics (the library never prints).

  /// True when status is kSuccess.
  bool ok() const { return status == Status::kSuccess; }
  /// One paragraph: status, message, error estimate, time, counters and warnings.
  std::string BriefReport() const;
};

}  // namespace geardyn
