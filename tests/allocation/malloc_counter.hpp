// Counts heap allocations (malloc/calloc/realloc/aligned allocation, and therefore every
// operator new of glibc's libstdc++, which allocates through malloc) while a scope is armed.
// Interposes the C allocator by forwarding to glibc's __libc_* entry points. Not available
// under AddressSanitizer, which owns malloc itself: available() is false there.
#pragma once

#include <cstdint>

namespace reentry::test {

bool malloc_counting_available();

/// Arms counting for its lifetime (one at a time, any thread's allocations are counted).
class MallocCounter {
 public:
  MallocCounter();
  ~MallocCounter();
  MallocCounter(const MallocCounter&) = delete;
  MallocCounter& operator=(const MallocCounter&) = delete;
  std::int64_t count() const;
};

}  // namespace reentry::test
