/// @file
/// @brief The one lock of FFTW's planner. Making and destroying plans is not thread-safe in FFTW
/// (manual §5.4 "Thread safety": only fftw_execute is); stability charts and speed sweeps run
/// analyses on OpenMP threads, so every geardyn plan is made and destroyed under this lock.
#pragma once

#include <mutex>

namespace geardyn {

/// The process-wide mutex around fftw_plan_* and fftw_destroy_plan.
std::mutex& FftwPlannerMutex();

}  // namespace geardyn
