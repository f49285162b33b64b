#include "core/grey_map.h"

#include <algorithm>
#include <cmath>

namespace hairfit {

double GreyMap::sample(const Vec2& uv) const {
  const double x = std::clamp(uv.x() * width - 0.5, 0.0, width - 1.0);
  const double y = std::clamp(uv.y() * height - 0.5, 0.0, height - 1.0);
  const int x0 = std::min(static_cast<int>(x), width - 1), y0 = std::min(static_cast<int>(y), height - 1);
  const int x1 = std::min(x0 + 1, width - 1), y1 = std::min(y0 + 1, height - 1);
  const double fx = x - x0, fy = y - y0;
  const double top = (1 - fx) * at(x0, y0) + fx * at(x1, y0);
  const double bottom = (1 - fx) * at(x0, y1) + fx * at(x1, y1);
  return (1 - fy) * top + fy * bottom;
}

}  // namespace hairfit
