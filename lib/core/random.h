// Counter-based random numbers: a stream is keyed by (seed, stage, item id), so a value never
// depends on evaluation order or on the number of threads. Nothing in hairfit shares a generator.
#pragma once
#include <cstdint>

namespace hairfit {

// Stream identifiers, one per consumer; never renumber (results would change).
enum class RandomStage : std::uint64_t {
  test = 0,
  roots = 1,
  clusters = 2,
  preguides = 3,
  guides = 4,
  density = 5,
  strands = 6,
  prepare = 7,
};

// The 64-bit finaliser of SplitMix64: a bijection with full avalanche.
std::uint64_t mix64(std::uint64_t x);

class Random {
 public:
  Random(std::uint64_t seed, RandomStage stage, std::uint64_t item);

  std::uint64_t next_u64();
  double uniform();                       // in [0, 1), 53 random bits
  double uniform(double lo, double hi);   // in [lo, hi)
  std::uint64_t below(std::uint64_t n);   // in [0, n), unbiased; n > 0
  double normal();                        // standard normal (Box–Muller, one value per call)

 private:
  std::uint64_t key_;
  std::uint64_t counter_ = 0;
};

}  // namespace hairfit
