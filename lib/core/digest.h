// A stable 64-bit digest of a stage's value, for report.json, caching and regression checks.
// It hashes the exact bytes of what is added (doubles bit for bit), so equal digests mean equal
// values on the same build; the hash is fixed and never depends on the platform's std::hash.
#pragma once
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "core/types.h"

namespace hairfit {

class Digest {
 public:
  Digest& add_bytes(const void* data, std::size_t size);
  Digest& add(double x);
  Digest& add(std::int64_t x);
  Digest& add(std::string_view text);
  Digest& add(const Vec3& v);
  Digest& add(const std::vector<double>& xs);
  Digest& add(const std::vector<Vec3>& points);

  std::uint64_t value() const;
  std::string hex() const;  // 16 lowercase hex digits

 private:
  std::uint64_t state_ = 0x6a09e667f3bcc908ull;
  std::uint64_t length_ = 0;
};

}  // namespace hairfit
