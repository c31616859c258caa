/// @file
/// @brief Heap-allocation counting for the "no allocation in per-θ kernels" tests (architecture
/// §3.9 item 7): `geardyn::test::CountAllocations(fn)` and the RAII `AllocationCounter`.
///
/// Eigen's EIGEN_RUNTIME_NO_MALLOC only checks Eigen code compiled in the test's own translation
/// unit, not the already-compiled library, so tests/support/allocation_counter.cpp interposes the
/// C allocator itself (glibc): every malloc/calloc/realloc/aligned allocation of the process —
/// Eigen's aligned_malloc, operator new, std containers — is counted while a counter is active.
/// tests/CMakeLists.txt links it into every plain test executable.
///
/// Where interposition is unavailable, `AllocationCounterAvailable()` is false and the counts are
/// always 0; guard the expectations with it (GEARDYN_HAVE_ALLOCATION_COUNTER, or GTEST_SKIP()).
/// That is so in the sanitized twins (GEARDYN_SANITIZED_TWINS) and under GEARDYN_SANITIZE: ASan
/// owns malloc, and a second malloc beside its interceptors made the 9 executables that counted
/// allocations abort before main ("CHECK failed: asan_posix.cpp:124 tsd_key_inited": glibc's
/// dlerror buffer, from __libc_malloc through the interposer, freed by ASan's free while ASan was
/// starting). The decision is made at link time, not in this header, because a test's objects are
/// shared by its plain and its sanitized executable.
#pragma once

#include <utility>

namespace geardyn::test {

/// True when this executable counts allocations (the plain build on glibc).
bool AllocationCounterAvailable();

namespace internal {
// Out of line (allocation_counter.cpp) on purpose: clang knows that malloc touches no program
// memory, so inline stores to a counting flag around an allocation were dead-store eliminated and
// the counter saw nothing (seen when the interposer moved out of this header).
void StartCounting();
long StopCounting();
}  // namespace internal

}  // namespace geardyn::test

/// A run-time value (was a preprocessor constant): use it in `if`, not in `#if`.
#define GEARDYN_HAVE_ALLOCATION_COUNTER (::geardyn::test::AllocationCounterAvailable())

namespace geardyn::test {

/// @brief Counts heap allocations between construction and count() / destruction. Not
/// re-entrant (one active counter at a time), not thread-safe.
class AllocationCounter {
 public:
  AllocationCounter() { internal::StartCounting(); }
  ~AllocationCounter() { internal::StopCounting(); }
  AllocationCounter(const AllocationCounter&) = delete;
  AllocationCounter& operator=(const AllocationCounter&) = delete;
  /// Allocations so far (stops counting).
  long Stop() { return internal::StopCounting(); }
};

/// @brief Number of heap allocations made while running fn() (0 without interposition).
template <typename Fn>
long CountAllocations(Fn&& fn) {
  AllocationCounter counter;
  std::forward<Fn>(fn)();
  return counter.Stop();
}

}  // namespace geardyn::test
