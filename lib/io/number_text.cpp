#include "io/number_text.h"

#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>

namespace hairfit {

namespace {

using u128 = unsigned __int128;

constexpr std::uint64_t kPow10[20] = {1ULL,
                                      10ULL,
                                      100ULL,
                                      1000ULL,
                                      10000ULL,
                                      100000ULL,
                                      1000000ULL,
                                      10000000ULL,
                                      100000000ULL,
                                      1000000000ULL,
                                      10000000000ULL,
                                      100000000000ULL,
                                      1000000000000ULL,
                                      10000000000000ULL,
                                      100000000000000ULL,
                                      1000000000000000ULL,
                                      10000000000000000ULL,
                                      100000000000000000ULL,
                                      1000000000000000000ULL,
                                      10000000000000000000ULL};

// q = floor(m·2^e2·10^k) exactly, and how the rest compares with one half (−1 below, 0 equal,
// +1 above). False where the integers would not fit 128 bits (the caller then asks the library).
bool scaled(std::uint64_t m, int e2, int k, std::uint64_t& q, int& rest) {
  if (k >= 0) {
    if (k > 19) return false;
    const u128 a = static_cast<u128>(m) * kPow10[k];  // < 2^53 · 2^64
    if (e2 >= 0) {
      if (e2 > 10) return false;  // a·2^e2 must stay below 2^128
      const u128 v = a << e2;
      if (v >> 64) return false;
      q = static_cast<std::uint64_t>(v);
      rest = -1;
      return true;
    }
    const int s = -e2;
    if (s >= 127) return false;
    const u128 whole = a >> s;
    if (whole >> 64) return false;
    const u128 r = a - (whole << s), half = static_cast<u128>(1) << (s - 1);
    q = static_cast<std::uint64_t>(whole);
    rest = r < half ? -1 : r == half ? 0 : 1;
    return true;
  }
  if (-k > 19) return false;
  const std::uint64_t d = kPow10[-k];
  u128 a, b;
  if (e2 >= 0) {
    if (e2 > 70) return false;
    a = static_cast<u128>(m) << e2;
    b = d;
  } else {
    if (-e2 > 63) return false;
    a = m;
    b = static_cast<u128>(d) << -e2;
  }
  const u128 whole = a / b, r = a - whole * b;
  if (whole >> 64) return false;
  q = static_cast<std::uint64_t>(whole);
  rest = 2 * r < b ? -1 : 2 * r == b ? 0 : 1;
  return true;
}

// "00" … "99".
constexpr char kPairs[] =
    "00010203040506070809101112131415161718192021222324252627282930313233343536373839"
    "40414243444546474849505152535455565758596061626364656667686970717273747576777879"
    "8081828384858687888990919293949596979899";

// n ≤ 17 characters, copied 8 at a time (fixed-size copies are plain moves, where a call to
// memcpy of n bytes costs more than the copy); writes up to 7 bytes past the end, within the
// caller's room.
char* copy(char* out, const char* from, int n) {
  for (int i = 0; i < n; i += 8) std::memcpy(out + i, from + i, 8);
  return out + n;
}

char* library(char* out, double v, int precision) {
  return std::to_chars(out, out + 48, v, std::chars_format::general, precision).ptr;
}

}  // namespace

char* format_general(char* out, double v, int precision) {
  std::uint64_t bits;
  std::memcpy(&bits, &v, sizeof bits);
  const int biased = static_cast<int>((bits >> 52) & 0x7ff);
  if (biased == 0 || biased == 0x7ff || precision < 1 || precision > 17) {  // zero, subnormal, inf, NaN
    if (v == 0.0) {
      if (bits >> 63) *out++ = '-';
      *out++ = '0';
      return out;
    }
    return library(out, v, precision);
  }
  const std::uint64_t m = (bits & ((1ULL << 52) - 1)) | (1ULL << 52);  // |v| = m · 2^e2, 2^52 ≤ m < 2^53
  const int e2 = biased - 1075;
  const int p = precision;
  // The decimal exponent: 10^e ≤ |v| < 10^(e+1); first guess floor((e2 + 52)·log10 2) from the
  // binary one (78913 / 2^18 ≈ log10 2; the shift floors negatives too), then corrected.
  int e = ((e2 + 52) * 78913) >> 18;
  std::uint64_t q = 0;
  int rest = 0;
  for (int attempt = 0;; ++attempt) {
    if (attempt == 3 || !scaled(m, e2, p - 1 - e, q, rest)) return library(out, v, precision);
    if (q < kPow10[p - 1]) --e;
    else if (q >= kPow10[p]) ++e;
    else break;
  }
  if (rest > 0 || (rest == 0 && (q & 1))) ++q;  // round half to even, as glibc's printf
  if (q == kPow10[p]) {
    q = kPow10[p - 1];
    ++e;
  }
  // The p digits, two at a time from the end (32-bit arithmetic once q fits).
  char digits[32];
  int at = p;
  while (q >= (1ULL << 32)) {
    const unsigned pair = static_cast<unsigned>(q % 100);
    q /= 100;
    at -= 2;
    std::memcpy(digits + at, kPairs + 2 * pair, 2);
  }
  std::uint32_t small = static_cast<std::uint32_t>(q);
  while (at >= 2) {
    const unsigned pair = small % 100;
    small /= 100;
    at -= 2;
    std::memcpy(digits + at, kPairs + 2 * pair, 2);
  }
  if (at == 1) digits[0] = static_cast<char>('0' + small);
  int significant = p;
  while (significant > 1 && digits[significant - 1] == '0') --significant;

  if (bits >> 63) *out++ = '-';
  if (e < -4 || e >= p) {  // %e: d.ddd e±XX
    *out++ = digits[0];
    if (significant > 1) {
      *out++ = '.';
      out = copy(out, digits + 1, significant - 1);
    }
    *out++ = 'e';
    *out++ = e < 0 ? '-' : '+';
    const int a = e < 0 ? -e : e;
    if (a >= 100) *out++ = static_cast<char>('0' + a / 100);
    *out++ = static_cast<char>('0' + a / 10 % 10);
    *out++ = static_cast<char>('0' + a % 10);
    return out;
  }
  if (e >= 0) {  // %f with p − 1 − e decimals: the integer part is the first e + 1 digits
    out = copy(out, digits, e + 1);
    if (significant > e + 1) {
      *out++ = '.';
      out = copy(out, digits + e + 1, significant - e - 1);
    }
    return out;
  }
  *out++ = '0';  // 0.000ddd
  *out++ = '.';
  for (int i = 0; i < -e - 1; ++i) *out++ = '0';
  return copy(out, digits, significant);
}

}  // namespace hairfit
