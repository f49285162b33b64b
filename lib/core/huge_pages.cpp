#include "core/huge_pages.h"

#include <cstdlib>
#include <new>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace hairfit {

namespace {
constexpr std::size_t kHugePage = std::size_t(2) << 20;
std::size_t rounded(std::size_t bytes) { return (bytes + kHugePage - 1) / kHugePage * kHugePage; }
}  // namespace

void* allocate_huge(std::size_t bytes) {
  if (bytes < kHugePageThreshold) return ::operator new(bytes);
  // aligned_alloc wants a size that is a multiple of the alignment; the pages of the rounding
  // are never touched.
  void* memory = std::aligned_alloc(kHugePage, rounded(bytes));
  if (!memory) throw std::bad_alloc();
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  madvise(memory, rounded(bytes), MADV_HUGEPAGE);  // a hint: ignored where THP is off
#endif
  return memory;
}

void free_huge(void* memory, std::size_t bytes) {
  if (bytes < kHugePageThreshold) ::operator delete(memory);
  else std::free(memory);
}

}  // namespace hairfit
