/// @file
/// @brief SIGINT/SIGTERM → a cancel flag the long analyses poll (sweeps, charts, continuation,
/// time integration), so an interrupted command still writes the results computed so far, marked
/// as partial (output_files.hpp), and exits with kExitInterrupted.
#pragma once

#include <atomic>

namespace geardyn::app {

/// @brief The process-wide cancel flag set by the handlers of InterruptScope. Pass its address as
/// the `cancel` of an analysis (HbOptions::cancel, NhbOptions::cancel, StabilityChartOptions::
/// cancel, the time-domain runs).
const std::atomic<bool>* CancelFlag();

/// @brief True once SIGINT or SIGTERM arrived inside an InterruptScope (or RequestInterrupt ran).
bool Interrupted();

/// @brief Sets the flag as a signal would (tests; a caller that wants to stop a run).
void RequestInterrupt();

/// @brief Installs the SIGINT and SIGTERM handlers for its lifetime and clears the flag; the
/// previous handlers come back on destruction. A second signal of the same kind gets the
/// previous (default: terminating) handler, so a run that does not stop can still be killed.
class InterruptScope {
 public:
  InterruptScope();
  ~InterruptScope();
  InterruptScope(const InterruptScope&) = delete;
  InterruptScope& operator=(const InterruptScope&) = delete;

 private:
  void (*previous_int_)(int);
  void (*previous_term_)(int);
};

}  // namespace geardyn::app
