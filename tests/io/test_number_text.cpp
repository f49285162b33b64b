// format_general against printf's "%.Pg" (and std::to_chars, which the standard ties to it) on
// random doubles of every magnitude, on decimal ties and near-ties, and on the edge cases.
#include <doctest/doctest.h>

#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <limits>
#include <string>

#include "core/random.h"
#include "io/number_text.h"

using namespace hairfit;

namespace {

std::string fast(double v, int precision) {
  char text[48];
  return std::string(text, format_general(text, v, precision));
}

std::string printf_g(double v, int precision) {
  char text[64];
  std::snprintf(text, sizeof text, "%.*g", precision, v);
  return text;
}

std::string to_chars_g(double v, int precision) {
  char text[64];
  return std::string(text, std::to_chars(text, text + sizeof text, v, std::chars_format::general, precision).ptr);
}

}  // namespace

TEST_CASE("format_general writes what printf's %.Pg writes, byte for byte") {
  Random r(17, RandomStage::test, 0);
  int checked = 0, mismatches = 0;
  auto check = [&](double v) {
    for (int precision : {1, 4, 6, 7, 9, 12, 15, 17}) {
      const std::string expected = printf_g(v, precision), got = fast(v, precision);
      if (got != expected || to_chars_g(v, precision) != expected) {
        if (++mismatches < 10) FAIL_CHECK(v << " at " << precision << ": " << got << " vs " << expected);
      }
      ++checked;
    }
  };
  // Any bit pattern (every exponent, subnormals, both signs).
  for (int i = 0; i < 20000; ++i) {
    std::uint64_t bits = (std::uint64_t(r.uniform(0, 4294967296.0)) << 32) | std::uint64_t(r.uniform(0, 4294967296.0));
    double v;
    std::memcpy(&v, &bits, sizeof v);
    if (std::isfinite(v)) check(v);
  }
  // Coordinates in cm as the outputs hold them, and their neighbours one ulp away.
  for (int i = 0; i < 20000; ++i) {
    const double v = r.uniform(-50, 50) * std::pow(10.0, std::floor(r.uniform(-6, 8)));
    check(v);
    check(std::nextafter(v, 0.0));
  }
  // Decimal ties and near-ties at the last digit kept (x.5 units exactly representable: ties to
  // even), integers, powers of ten and the rounding carry into a new digit (9999999.5 → 1e+07).
  for (int i = 0; i < 5000; ++i) {
    const double k = std::floor(r.uniform(0, 1e7));
    for (double v : {k + 0.5, (k + 0.5) / 1024, k, k * 1e3 + 500, 9999999.5, 99999995.0, 0.00012345675, 1e-5, 1e16})
      check(v), check(-v), check(std::nextafter(v, 1e300)), check(std::nextafter(v, -1e300));
  }
  for (double v : {0.0, -0.0, 1.0, -1.0, 0.1, 1e-4, 9.9999995e-5, 1e-300, 4.9e-324, 2.2250738585072014e-308,
                   std::numeric_limits<double>::max(), std::numeric_limits<double>::lowest(),
                   std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()})
    check(v);
  CHECK(mismatches == 0);
  CHECK(checked > 500000);
}
