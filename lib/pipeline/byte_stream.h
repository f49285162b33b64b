// Little binary writer and reader for the stage cache (lib/pipeline/stage_codec.h): plain values
// copied byte for byte (doubles bit for bit), vectors prefixed by their length. The reader checks
// every length against what is left, so a truncated or foreign payload throws CodecError instead
// of reading past the end or allocating absurd sizes.
#pragma once
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include "core/types.h"

namespace hairfit {

static_assert(__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__, "the cache format is little-endian");

struct CodecError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

class ByteWriter {
 public:
  template <class T>
  void put(const T& x) {
    static_assert(std::is_trivially_copyable_v<T>);
    bytes_.append(reinterpret_cast<const char*>(&x), sizeof x);
  }
  void put(const Vec2& v) { raw(v.data(), sizeof(double) * 2); }
  void put(const Vec3& v) { raw(v.data(), sizeof(double) * 3); }
  void put(const Vec3i& v) { raw(v.data(), sizeof(int) * 3); }
  void put(const std::string& s) {
    put<std::uint64_t>(s.size());
    raw(s.data(), s.size());
  }
  template <class T>
  void put(const std::vector<T>& xs) {
    put<std::uint64_t>(xs.size());
    if constexpr (std::is_trivially_copyable_v<T>) raw(xs.data(), xs.size() * sizeof(T));
    else
      for (const T& x : xs) put(x);
  }
  void raw(const void* data, std::size_t size) { bytes_.append(static_cast<const char*>(data), size); }
  const std::string& bytes() const { return bytes_; }
  std::string take() { return std::move(bytes_); }

 private:
  std::string bytes_;
};

class ByteReader {
 public:
  explicit ByteReader(std::string_view bytes) : bytes_(bytes) {}

  template <class T>
  T get() {
    static_assert(std::is_trivially_copyable_v<T>);
    T x;
    raw(&x, sizeof x);
    return x;
  }
  void get(Vec2& v) { raw(v.data(), sizeof(double) * 2); }
  void get(Vec3& v) { raw(v.data(), sizeof(double) * 3); }
  void get(Vec3i& v) { raw(v.data(), sizeof(int) * 3); }
  void get(std::string& s) {
    s.resize(count(1));
    raw(s.data(), s.size());
  }
  template <class T>
  void get(T& x) {
    x = get<T>();
  }
  template <class T>
  void get(std::vector<T>& xs) {
    xs.resize(count(std::is_trivially_copyable_v<T> ? sizeof(T) : 1));
    if constexpr (std::is_trivially_copyable_v<T>) raw(xs.data(), xs.size() * sizeof(T));
    else
      for (T& x : xs) get(x);
  }
  void raw(void* out, std::size_t size) {
    if (size > bytes_.size() - at_) throw CodecError("cache payload ends early");
    if (size == 0) return;  // an empty vector's data() may be null, which memcpy must not get
    std::memcpy(out, bytes_.data() + at_, size);
    at_ += size;
  }
  std::size_t remaining() const { return bytes_.size() - at_; }
  bool done() const { return at_ == bytes_.size(); }
  // Throws unless every byte was read: a payload longer than its value is not ours either.
  void expect_end() const {
    if (!done()) throw CodecError("cache payload has " + std::to_string(bytes_.size() - at_) + " bytes left over");
  }

 private:
  // A length prefix; each element takes at least `element_bytes`, so a length beyond what is left
  // is rejected before anything is allocated.
  std::size_t count(std::size_t element_bytes) {
    const auto n = get<std::uint64_t>();
    if (n > (bytes_.size() - at_) / element_bytes) throw CodecError("cache payload holds an impossible length");
    return static_cast<std::size_t>(n);
  }
  std::string_view bytes_;
  std::size_t at_ = 0;
};

}  // namespace hairfit
