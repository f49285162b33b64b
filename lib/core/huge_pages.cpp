#include "core/huge_pages.h"

#include <cstdint>
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
  advise_huge_pages(memory, rounded(bytes));
  return memory;
}

void advise_huge_pages(void* memory, std::size_t bytes) {
  const std::uintptr_t start = reinterpret_cast<std::uintptr_t>(memory);
  const std::uintptr_t begin = (start + kHugePage - 1) & ~(kHugePage - 1), end = (start + bytes) & ~(kHugePage - 1);
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  if (end > begin) madvise(reinterpret_cast<void*>(begin), end - begin, MADV_HUGEPAGE);
#else
  (void)begin;
  (void)end;
#endif
}

void free_huge(void* memory, std::size_t bytes) {
  if (bytes < kHugePageThreshold) ::operator delete(memory);
  else std::free(memory);
}

}  // namespace hairfit
