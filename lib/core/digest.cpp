#include "core/digest.h"

#include <cstring>

#include "core/random.h"

namespace hairfit {

Digest& Digest::add_bytes(const void* data, std::size_t size) {
  const auto* bytes = static_cast<const unsigned char*>(data);
  std::size_t i = 0;
  for (; i + 8 <= size; i += 8) {
    std::uint64_t word;
    std::memcpy(&word, bytes + i, 8);
    state_ = mix64(state_ ^ word);
  }
  if (i < size) {
    std::uint64_t word = 0;
    std::memcpy(&word, bytes + i, size - i);
    state_ = mix64(state_ ^ word ^ (std::uint64_t(size - i) << 56));
  }
  length_ += size;
  return *this;
}

Digest& Digest::add(double x) { return add_bytes(&x, sizeof x); }
Digest& Digest::add(std::int64_t x) { return add_bytes(&x, sizeof x); }
Digest& Digest::add(std::string_view text) {
  add(static_cast<std::int64_t>(text.size()));
  return add_bytes(text.data(), text.size());
}
Digest& Digest::add(const Vec3& v) { return add_bytes(v.data(), 3 * sizeof(double)); }
Digest& Digest::add(const std::vector<double>& xs) {
  add(static_cast<std::int64_t>(xs.size()));
  return add_bytes(xs.data(), xs.size() * sizeof(double));
}
Digest& Digest::add(const std::vector<Vec3>& points) {
  // Point after point, as add(p) each would: a point is three whole 8-byte words, so one call
  // over the packed array mixes the same words in the same order.
  static_assert(sizeof(Vec3) == 3 * sizeof(double), "Vec3 is packed");
  add(static_cast<std::int64_t>(points.size()));
  return add_bytes(points.data(), points.size() * sizeof(Vec3));
}

std::uint64_t Digest::value() const { return mix64(state_ ^ length_); }

std::string Digest::hex() const {
  static const char digits[] = "0123456789abcdef";
  std::uint64_t v = value();
  std::string out(16, '0');
  for (int i = 15; i >= 0; --i, v >>= 4) out[i] = digits[v & 15];
  return out;
}

}  // namespace hairfit
