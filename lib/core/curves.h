// A set of polylines (pre-guides, guides, fibres) as one value: all points in one array, root to
// tip, curve after curve. Every curve knows the guide it belongs to.
#pragma once
#include <cstdint>
#include <vector>

#include "core/types.h"

namespace hairfit {

struct Curves {
  std::vector<Vec3> points;            // cm
  std::vector<std::uint32_t> offsets{0};  // curve c is points[offsets[c] .. offsets[c+1]); size = count + 1
  std::vector<std::int32_t> guide;     // per curve: the guide (cluster) it belongs to, −1 if none
  std::vector<float> widths;           // per point diameters in cm, or empty (writers use a default)

  std::size_t count() const { return offsets.size() - 1; }
  std::size_t size(std::size_t c) const { return offsets[c + 1] - offsets[c]; }
  const Vec3& point(std::size_t c, std::size_t i) const { return points[offsets[c] + i]; }

  // Appends one curve (at least 2 points).
  void add(const std::vector<Vec3>& curve, std::int32_t guide_id = -1) {
    points.insert(points.end(), curve.begin(), curve.end());
    offsets.push_back(static_cast<std::uint32_t>(points.size()));
    guide.push_back(guide_id);
  }
};

// Polylines given one vector each, as one Curves (no guide).
inline Curves make_curves(const std::vector<std::vector<Vec3>>& polylines) {
  Curves curves;
  for (const std::vector<Vec3>& p : polylines) curves.add(p);
  return curves;
}

}  // namespace hairfit
