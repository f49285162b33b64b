// Large buffers on transparent huge pages: operator new asks the kernel (core/huge_pages.h) to back
// the whole 2 MiB pages inside every block of 4 MiB or more with huge pages before they are
// touched. A paper-scale run touches about 220 MB in such blocks; in 4 KiB pages that was 48 000
// page faults and as many pages to free at exit (a tenth of its wall time).
#include <cstdlib>
#include <new>

#include "core/huge_pages.h"

namespace {

constexpr std::size_t kThreshold = std::size_t(4) << 20;

void* allocate(std::size_t size) {
  void* p = std::malloc(size == 0 ? 1 : size);
  if (!p) throw std::bad_alloc();
  if (size >= kThreshold) hairfit::advise_huge_pages(p, size);
  return p;
}

}  // namespace

void* operator new(std::size_t size) { return allocate(size); }
void* operator new[](std::size_t size) { return allocate(size); }
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }
