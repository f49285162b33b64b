#include "core/random.h"

#include <cmath>

namespace hairfit {

std::uint64_t mix64(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ull;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
  return x ^ (x >> 31);
}

Random::Random(std::uint64_t seed, RandomStage stage, std::uint64_t item)
    : key_(mix64(mix64(mix64(seed) ^ static_cast<std::uint64_t>(stage)) ^ item)) {}

std::uint64_t Random::next_u64() {
  // Counter mode: the i-th value is a keyed hash of i, so streams can also be skipped ahead.
  return mix64(key_ ^ mix64(++counter_));
}

double Random::uniform() { return static_cast<double>(next_u64() >> 11) * 0x1.0p-53; }

double Random::uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }

std::uint64_t Random::below(std::uint64_t n) {
  // Lemire-style rejection keeps the result exactly uniform.
  const std::uint64_t limit = -n % n;
  for (;;) {
    const std::uint64_t x = next_u64();
    const unsigned __int128 product = static_cast<unsigned __int128>(x) * n;
    if (static_cast<std::uint64_t>(product) >= limit) return static_cast<std::uint64_t>(product >> 64);
  }
}

double Random::normal() {
  const double u1 = 1.0 - uniform();  // in (0, 1], so the log is finite
  const double u2 = uniform();
  return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * M_PI * u2);
}

}  // namespace hairfit
