// The allocator interposition behind tests/support/no_malloc.hpp: malloc & co. counted while a
// geardyn::test::AllocationCounter is active. Compiled twice (tests/CMakeLists.txt): plainly for
// the plain test executables, and with the sanitizers for the sanitized twins, where ASan owns
// malloc and this file defines the counter state only (AllocationCounterAvailable() false).
#include <cstddef>

#include "support/no_malloc.hpp"

// Interposition needs glibc's __libc_* entry points, and is off under AddressSanitizer.
#if defined(__SANITIZE_ADDRESS__)  // GCC
#define GEARDYN_TEST_INTERPOSE_MALLOC 0
#elif defined(__has_feature)  // clang
#if __has_feature(address_sanitizer)
#define GEARDYN_TEST_INTERPOSE_MALLOC 0
#endif
#endif
#if !defined(GEARDYN_TEST_INTERPOSE_MALLOC) && defined(__GLIBC__)
#define GEARDYN_TEST_INTERPOSE_MALLOC 1
#elif !defined(GEARDYN_TEST_INTERPOSE_MALLOC)
#define GEARDYN_TEST_INTERPOSE_MALLOC 0
#endif

namespace geardyn::test {
namespace internal {
namespace {
bool g_counting = false;
long g_allocations = 0;
}  // namespace
// Called by the interposed allocator below.
void Count() {
  if (g_counting) ++g_allocations;
}
void StartCounting() {
  g_allocations = 0;
  g_counting = true;
}
long StopCounting() {
  g_counting = false;
  return g_allocations;
}
}  // namespace internal

bool AllocationCounterAvailable() { return GEARDYN_TEST_INTERPOSE_MALLOC == 1; }

}  // namespace geardyn::test

#if GEARDYN_TEST_INTERPOSE_MALLOC
extern "C" {
void* __libc_malloc(size_t size);  // NOLINT(bugprone-reserved-identifier)
void* __libc_calloc(size_t count, size_t size);
void* __libc_realloc(void* ptr, size_t size);
void* __libc_memalign(size_t alignment, size_t size);
}

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
#endif
