// Colours for pictures and plots: linear float RGB in [0, 1] (no gamma: the values are written as
// they are), a fixed palette for ids (guides, clusters, plot series) and the two colour maps.
#pragma once
#include <cstdint>

namespace hairfit {

struct Color {
  float r = 0.0f;
  float g = 0.0f;
  float b = 0.0f;
};

// (1 − t)·a + t·b, componentwise.
Color mix(const Color& a, const Color& b, float t);
Color scale(const Color& c, float factor);

// Colour number `id` of a fixed palette: ten well-separated colours (Tableau 10) for ids 0–9, then
// golden-ratio hue steps, so every id has a stable colour and neighbours differ. Negative ids give
// a neutral grey.
Color palette_color(int id);

// Diverging map for signed values (distance fields): t in [−1, 1] → blue (−1), white (0), red (+1);
// t outside is clamped.
Color diverging_color(double t);

// Sequential map for non-negative values (density): t in [0, 1] → dark purple … yellow, a
// perceptually ordered ramp in the manner of matplotlib's "magma"/"viridis"; t outside is clamped.
Color sequential_color(double t);

// Rounds a component in [0, 1] to 0–255 (clamped); NaN gives 0.
std::uint8_t to_byte(float value);

}  // namespace hairfit
