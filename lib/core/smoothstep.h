// The C¹ smoothstep S(x) = 3x² − 2x³ on [0, 1], 0 below and 1 above: the ramp every blend in
// hairfit uses.
#pragma once
#include <algorithm>

namespace hairfit {

inline double smoothstep(double x) {
  const double t = std::clamp(x, 0.0, 1.0);
  return t * t * (3.0 - 2.0 * t);
}

}  // namespace hairfit
