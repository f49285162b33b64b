#include <doctest/doctest.h>

#include <algorithm>
#include <cstdint>
#include <numeric>

#include "core/huge_pages.h"

using namespace hairfit;

TEST_CASE("huge pages: vectors below and above the threshold hold and copy their values") {
  for (const std::size_t n : {std::size_t(10), kHugePageThreshold / sizeof(double) + 7, std::size_t(3) << 20}) {
    HugeVector<double> v(n);
    CHECK(v.size() == n);
    CHECK(std::all_of(v.begin(), v.end(), [](double x) { return x == 0.0; }));  // value-initialised
    std::iota(v.begin(), v.end(), 1.0);
    HugeVector<double> copy = v;
    v.resize(n + 1000, -1.0);  // regrowth moves the values into a new block
    CHECK(v[n - 1] == static_cast<double>(n));
    CHECK(v[n] == -1.0);
    CHECK(copy == HugeVector<double>(v.begin(), v.begin() + n));
    if (n * sizeof(double) >= kHugePageThreshold)  // aligned to a 2 MiB page
      CHECK(reinterpret_cast<std::uintptr_t>(copy.data()) % (std::uintptr_t(2) << 20) == 0);
  }
}
