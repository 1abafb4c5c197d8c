#include "malloc_counter.hpp"

#include <atomic>
#include <cstddef>

namespace {
std::atomic<bool> g_armed{false};
std::atomic<std::int64_t> g_count{0};
inline void note() {
  if (g_armed.load(std::memory_order_relaxed)) g_count.fetch_add(1, std::memory_order_relaxed);
}
}  // namespace

#if !defined(REENTRY_SANITIZE)
extern "C" {
void* __libc_malloc(std::size_t);
void* __libc_calloc(std::size_t, std::size_t);
void* __libc_realloc(void*, std::size_t);
void* __libc_memalign(std::size_t, std::size_t);

void* malloc(std::size_t n) {
  note();
  return __libc_malloc(n);
}
void* calloc(std::size_t n, std::size_t s) {
  note();
  return __libc_calloc(n, s);
}
void* realloc(void* p, std::size_t n) {
  note();
  return __libc_realloc(p, n);
}
void* memalign(std::size_t a, std::size_t n) {
  note();
  return __libc_memalign(a, n);
}
void* aligned_alloc(std::size_t a, std::size_t n) {
  note();
  return __libc_memalign(a, n);
}
int posix_memalign(void** out, std::size_t a, std::size_t n) {
  note();
  void* p = __libc_memalign(a, n);
  if (p == nullptr) return 12;  // ENOMEM
  *out = p;
  return 0;
}
}
#endif

namespace reentry::test {

bool malloc_counting_available() {
#if defined(REENTRY_SANITIZE)
  return false;
#else
  return true;
#endif
}

MallocCounter::MallocCounter() {
  g_count.store(0);
  g_armed.store(true);
}
MallocCounter::~MallocCounter() { g_armed.store(false); }
std::int64_t MallocCounter::count() const { return g_count.load(); }

}  // namespace reentry::test
