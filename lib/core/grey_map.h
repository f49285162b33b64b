// A grey-value image (density, tilt or length map) as an immutable value, values in [0, 1].
#pragma once
#include <string>
#include <vector>

#include "core/types.h"

namespace hairfit {

struct GreyMap {
  int width = 0;
  int height = 0;
  int bits = 8;               // 8 or 16, as stored in the file
  std::vector<float> values;  // row-major, row 0 at the top of the image, 0 = black, 1 = white

  float at(int x, int y) const { return values[static_cast<std::size_t>(y) * width + x]; }

  // Bilinear sample at image coordinates (u, v) in [0, 1]²: u to the right, v downward; pixel
  // centres sit at ((i + ½)/width, (j + ½)/height); outside, the edge pixels are repeated.
  double sample(const Vec2& uv) const;
};

}  // namespace hairfit
