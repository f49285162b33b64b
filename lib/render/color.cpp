#include "render/color.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace hairfit {

Color mix(const Color& a, const Color& b, float t) {
  return {a.r + (b.r - a.r) * t, a.g + (b.g - a.g) * t, a.b + (b.b - a.b) * t};
}

Color scale(const Color& c, float factor) { return {c.r * factor, c.g * factor, c.b * factor}; }

namespace {

Color from_hex(std::uint32_t hex) {
  return {((hex >> 16) & 0xff) / 255.0f, ((hex >> 8) & 0xff) / 255.0f, (hex & 0xff) / 255.0f};
}

Color from_hsv(double h, double s, double v) {
  const double h6 = 6.0 * (h - std::floor(h));
  const int sector = std::min(5, static_cast<int>(h6));
  const double f = h6 - sector;
  const double p = v * (1 - s), q = v * (1 - s * f), t = v * (1 - s * (1 - f));
  const std::array<std::array<double, 3>, 6> rgb{{{v, t, p}, {q, v, p}, {p, v, t}, {p, q, v}, {t, p, v}, {v, p, q}}};
  return {static_cast<float>(rgb[sector][0]), static_cast<float>(rgb[sector][1]), static_cast<float>(rgb[sector][2])};
}

// Piecewise-linear interpolation through evenly spaced control colours.
template <std::size_t N>
Color ramp(const std::array<std::uint32_t, N>& stops, double t) {
  t = std::clamp(std::isnan(t) ? 0.0 : t, 0.0, 1.0) * (N - 1);
  const std::size_t i = std::min<std::size_t>(N - 2, static_cast<std::size_t>(t));
  return mix(from_hex(stops[i]), from_hex(stops[i + 1]), static_cast<float>(t - i));
}

}  // namespace

Color palette_color(int id) {
  static constexpr std::array<std::uint32_t, 10> kTableau{0x4e79a7, 0xf28e2b, 0xe15759, 0x76b7b2, 0x59a14f,
                                                          0xedc948, 0xb07aa1, 0xff9da7, 0x9c755f, 0xbab0ac};
  if (id < 0) return {0.6f, 0.6f, 0.6f};
  if (id < 10) return from_hex(kTableau[id]);
  // Golden-ratio hue steps never repeat and keep consecutive ids apart; saturation and value
  // alternate so that nearby hues still differ.
  const double hue = std::fmod(0.13 + 0.6180339887498949 * id, 1.0);
  return from_hsv(hue, id % 2 ? 0.55 : 0.75, id % 3 ? 0.92 : 0.78);
}

Color diverging_color(double t) {
  // ColorBrewer RdBu (reversed so that negative is blue), white in the middle.
  static constexpr std::array<std::uint32_t, 9> kStops{0x2166ac, 0x4393c3, 0x92c5de, 0xd1e5f0, 0xf7f7f7,
                                                       0xfddbc7, 0xf4a582, 0xd6604d, 0xb2182b};
  return ramp(kStops, 0.5 * (t + 1.0));
}

Color sequential_color(double t) {
  // Sampled from the "magma" ramp (black-purple → orange → pale yellow).
  static constexpr std::array<std::uint32_t, 9> kStops{0x000004, 0x1c1044, 0x4f127b, 0x812581, 0xb5367a,
                                                       0xe55064, 0xfb8761, 0xfec287, 0xfcfdbf};
  return ramp(kStops, t);
}

std::uint8_t to_byte(float value) {
  if (!(value > 0.0f)) return 0;
  if (value >= 1.0f) return 255;
  return static_cast<std::uint8_t>(std::lround(value * 255.0f));
}

}  // namespace hairfit
