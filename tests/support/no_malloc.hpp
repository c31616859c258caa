/// @file
/// @brief Heap-allocation counting for the "no allocation in per-θ kernels" tests (architecture
/// §3.9 item 7): `geardyn::test::CountAllocations(fn)` and the RAII `AllocationCounter`.
///
/// Eigen's EIGEN_RUNTIME_NO_MALLOC only checks Eigen code compiled in the test's own translation
/// unit, not the already-compiled library, so this header interposes the C allocator itself
/// (glibc): every malloc/calloc/realloc/aligned allocation of the process — Eigen's
/// aligned_malloc, operator new, std containers — is counted while a counter is active.
///
/// **Include this header in exactly ONE translation unit of a test executable** (it defines
/// malloc & co.). Where interposition is unavailable (not glibc) GEARDYN_HAVE_ALLOCATION_COUNTER
/// is 0 and the counts are always 0; guard the expectations with it (or GTEST_SKIP()).
///
/// Under AddressSanitizer (GEARDYN_SANITIZE) the counter is off too: ASan owns malloc, and a
/// second malloc beside its interceptors made the 9 executables that include this header abort
/// before main ("CHECK failed: asan_posix.cpp:124 tsd_key_inited": glibc's dlerror buffer, from
/// __libc_malloc through this header, freed by ASan's free while ASan was starting).
#pragma once

#include <cstddef>
#include <utility>

#if defined(__SANITIZE_ADDRESS__)  // GCC
#define GEARDYN_TEST_UNDER_ASAN 1
#elif defined(__has_feature)  // clang
#if __has_feature(address_sanitizer)
#define GEARDYN_TEST_UNDER_ASAN 1
#endif
#endif

#if defined(__GLIBC__) && !defined(GEARDYN_TEST_UNDER_ASAN)
extern "C" {
void* __libc_malloc(size_t size);  // NOLINT(bugprone-reserved-identifier)
void* __libc_calloc(size_t count, size_t size);
void* __libc_realloc(void* ptr, size_t size);
void* __libc_memalign(size_t alignment, size_t size);
}

namespace geardyn::test::internal {
inline bool g_counting = false;
inline long g_allocations = 0;
inline void Count() {
  if (g_counting) ++g_allocations;
}
}  // namespace geardyn::test::internal

extern "C" {
void* malloc(size_t size) noexcept {
  geardyn::test::internal::Count();
  return __libc_malloc(size);
}
void* calloc(size_t count, size_t size) noexcept {
  geardyn::test::internal::Count();
  return __libc_calloc(count, size);
}
void* realloc(void* ptr, size_t size) noexcept {
  geardyn::test::internal::Count();
  return __libc_realloc(ptr, size);
}
void* aligned_alloc(size_t alignment, size_t size) noexcept {
  geardyn::test::internal::Count();
  return __libc_memalign(alignment, size);
}
int posix_memalign(void** out, size_t alignment, size_t size) noexcept {
  geardyn::test::internal::Count();
  void* p = __libc_memalign(alignment, size);
  if (p == nullptr) return 12;  // ENOMEM
  *out = p;
  return 0;
}
}
#define GEARDYN_HAVE_ALLOCATION_COUNTER 1
#else
#define GEARDYN_HAVE_ALLOCATION_COUNTER 0
namespace geardyn::test::internal {
inline bool g_counting = false;
inline long g_allocations = 0;
}  // namespace geardyn::test::internal
#endif

namespace geardyn::test {

/// @brief Counts heap allocations between construction and count() / destruction. Not
/// re-entrant (one active counter at a time), not thread-safe.
class AllocationCounter {
 public:
  AllocationCounter() {
    internal::g_allocations = 0;
    internal::g_counting = true;
  }
  ~AllocationCounter() { internal::g_counting = false; }
  AllocationCounter(const AllocationCounter&) = delete;
  AllocationCounter& operator=(const AllocationCounter&) = delete;
  /// Allocations so far (stops counting).
  long Stop() {
    internal::g_counting = false;
    return internal::g_allocations;
  }
};

/// @brief Number of heap allocations made while running fn() (0 without interposition).
template <typename Fn>
long CountAllocations(Fn&& fn) {
  AllocationCounter counter;
  std::forward<Fn>(fn)();
  return counter.Stop();
}

}  // namespace geardyn::test
