// Checks of a run's fibres that do not use its distance fields: inside the hair region by direct
// winding-number sums, and segments crossing the scalp by exact segment–triangle tests (the scalp's
// triangles binned on a uniform grid so every segment meets only those near it; each
// segment–triangle pair is tested at most once per segment, so the count is exact).
#pragma once
#include <algorithm>
#include <cmath>
#include <unordered_map>
#include <vector>

#include "core/curves.h"
#include "core/fast_winding.h"
#include "core/segment_triangle.h"
#include "field/hair_region.h"

namespace hairfit::testing {

// Whether segment pq crosses triangle abc (the segment's open interior).
inline bool segment_crosses_triangle(const Vec3& p, const Vec3& q, const Vec3& a, const Vec3& b, const Vec3& c) {
  return !std::isnan(segment_triangle_parameter(p, q, a, b, c));
}

struct IndependentCheck {
  double inside = 0.0;      // share of fibre points after the root inside the region (direct sums)
  long long crossings = 0;  // fibre segments that cross the scalp
  long long segments = 0;
  bool finite = true;
};

// The region: inside `volume` (closed), or for an open hull inside it together with the reversed
// scalp; and not in the head (the scalp closed by its floor).
inline IndependentCheck independent_check(const Mesh& volume, bool volume_closed, const Mesh& scalp, const Curves& fibres) {
  const FastWindingNumber hull(volume), scalp_winding(scalp), head(closed_head(scalp));
  // The scalp's triangles by the grid cells their bounding boxes touch.
  const auto [lo, hi] = bounding_box(scalp);
  const double cell = std::max(1e-6, std::cbrt((hi - lo).prod() / std::max<std::size_t>(1, scalp.triangles.size())) * 2.0);
  auto key = [&](const Vec3i& c) { return (static_cast<long long>(c.x()) * 73856093) ^ (static_cast<long long>(c.y()) * 19349663) ^
                                          (static_cast<long long>(c.z()) * 83492791); };
  auto coords = [&](const Vec3& p) { return Vec3i(((p - lo) / cell).array().floor().cast<int>()); };
  std::unordered_map<long long, std::vector<int>> bins;
  for (int t = 0; t < static_cast<int>(scalp.triangles.size()); ++t) {
    const Vec3i& f = scalp.triangles[t];
    Vec3 a = scalp.positions[f[0]], b = a;
    for (int k = 1; k < 3; ++k) a = a.cwiseMin(scalp.positions[f[k]]), b = b.cwiseMax(scalp.positions[f[k]]);
    const Vec3i ca = coords(a), cb = coords(b);
    for (int x = ca.x(); x <= cb.x(); ++x)
      for (int y = ca.y(); y <= cb.y(); ++y)
        for (int z = ca.z(); z <= cb.z(); ++z) bins[key(Vec3i(x, y, z))].push_back(t);
  }
  IndependentCheck r;
  long long inside = 0, points = 0;
  std::vector<int> candidates;
  for (std::size_t c = 0; c < fibres.count(); ++c)
    for (std::size_t k = fibres.offsets[c]; k < fibres.offsets[c + 1]; ++k) {
      const Vec3& p = fibres.points[k];
      r.finite = r.finite && p.allFinite();
      if (k == fibres.offsets[c]) continue;  // the root: on the scalp by construction
      // A closed volume's inside is decided exactly by the hierarchy (FastWindingNumber::above);
      // an open hull's needs the difference of two direct sums.
      const bool in_region = volume_closed ? hull.above(p, 0.5) : hull.direct(p) - scalp_winding.direct(p) > 0.5;
      inside += in_region && !head.above(p, 0.5);
      ++points;
      ++r.segments;
      const Vec3& q = fibres.points[k - 1];
      const Vec3i ca = coords(p.cwiseMin(q)), cb = coords(p.cwiseMax(q));
      candidates.clear();
      for (int x = ca.x(); x <= cb.x(); ++x)
        for (int y = ca.y(); y <= cb.y(); ++y)
          for (int z = ca.z(); z <= cb.z(); ++z) {
            const auto found = bins.find(key(Vec3i(x, y, z)));
            if (found != bins.end()) candidates.insert(candidates.end(), found->second.begin(), found->second.end());
          }
      std::sort(candidates.begin(), candidates.end());
      candidates.erase(std::unique(candidates.begin(), candidates.end()), candidates.end());
      bool crossing = false;
      for (int t : candidates) {
        const Vec3i& f = scalp.triangles[t];
        crossing = crossing || segment_crosses_triangle(q, p, scalp.positions[f[0]], scalp.positions[f[1]], scalp.positions[f[2]]);
      }
      r.crossings += crossing;
    }
  r.inside = points ? double(inside) / points : 0.0;
  return r;
}

}  // namespace hairfit::testing
