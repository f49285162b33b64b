// Memory for large arrays that are built and dropped within a stage, backed by transparent huge
// pages where Linux offers them (THP "always" or "madvise"). Every fresh 4 KiB page costs a page
// fault; in the VM the benchmarks run in that is about 20 µs, 4.5 ms per MB, and no faster with
// more threads, while one 2 MiB page serves 512 of them with one fault (measured: 100 MB touched
// in 450 ms with 4 KiB pages, in 6–11 ms with huge pages). Where huge pages are unavailable the
// memory is ordinary; nothing computed depends on it.
#pragma once
#include <cstddef>
#include <type_traits>
#include <vector>

namespace hairfit {

// Allocations from this size on are aligned to 2 MiB and advised to use huge pages; smaller ones
// come from operator new.
constexpr std::size_t kHugePageThreshold = std::size_t(1) << 20;

void* allocate_huge(std::size_t bytes);
void free_huge(void* memory, std::size_t bytes);

// Asks Linux to back the whole 2 MiB pages inside [memory, memory + bytes) with huge pages before
// they are touched (madvise MADV_HUGEPAGE; a hint, ignored where THP is off or elsewhere).
void advise_huge_pages(void* memory, std::size_t bytes);

template <class T>
struct HugePageAllocator {
  using value_type = T;
  HugePageAllocator() = default;
  template <class U>
  HugePageAllocator(const HugePageAllocator<U>&) {}
  T* allocate(std::size_t n) { return static_cast<T*>(allocate_huge(n * sizeof(T))); }
  void deallocate(T* p, std::size_t n) { free_huge(p, n * sizeof(T)); }
  template <class U>
  bool operator==(const HugePageAllocator<U>&) const { return true; }
  template <class U>
  bool operator!=(const HugePageAllocator<U>&) const { return false; }
};

template <class T>
using HugeVector = std::vector<T, HugePageAllocator<T>>;

// An uninitialised array of n trivial values (written before they are read): unlike a vector it
// touches no page until the values are written.
template <class T>
class HugeBuffer {
  static_assert(std::is_trivially_default_constructible_v<T> && std::is_trivially_destructible_v<T>);

 public:
  explicit HugeBuffer(std::size_t n) : data_(static_cast<T*>(allocate_huge(n * sizeof(T)))), bytes_(n * sizeof(T)) {}
  ~HugeBuffer() { free_huge(data_, bytes_); }
  HugeBuffer(const HugeBuffer&) = delete;
  HugeBuffer& operator=(const HugeBuffer&) = delete;
  T* data() const { return data_; }

 private:
  T* data_;
  std::size_t bytes_;
};

}  // namespace hairfit
