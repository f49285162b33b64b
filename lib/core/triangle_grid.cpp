#include "core/triangle_grid.h"

#include <algorithm>
#include <cmath>

#include "core/segment_triangle.h"

namespace hairfit {

TriangleGrid::TriangleGrid(const Mesh& mesh) : mesh_(mesh) {
  const int n = static_cast<int>(mesh.triangles.size());
  if (n == 0) return;
  std::vector<Vec3> lo(n), hi(n);
  Vec3 box_lo = mesh.positions[mesh.triangles[0][0]], box_hi = box_lo;
  double extent = 0.0;
  for (int t = 0; t < n; ++t) {
    const Vec3i& f = mesh.triangles[t];
    lo[t] = hi[t] = mesh.positions[f[0]];
    for (int k = 1; k < 3; ++k) lo[t] = lo[t].cwiseMin(mesh.positions[f[k]]), hi[t] = hi[t].cwiseMax(mesh.positions[f[k]]);
    const double pad = kSlackCovered * 4.0 * (hi[t] - lo[t]).maxCoeff();  // a grown triangle stays in its cells
    lo[t] -= Vec3::Constant(pad);
    hi[t] += Vec3::Constant(pad);
    box_lo = box_lo.cwiseMin(lo[t]);
    box_hi = box_hi.cwiseMax(hi[t]);
    extent += (hi[t] - lo[t]).sum() / 3.0;
  }
  const Vec3 size = box_hi - box_lo;
  cell_ = std::max({2.0 * extent / n, 1e-9 * std::max(1.0, size.maxCoeff())});
  while ((size / cell_).array().floor().prod() + 1.0 > 8.0 * n + 64.0) cell_ *= 1.25;
  origin_ = box_lo;
  dims_ = ((size / cell_).array().floor().cast<int>() + 1).matrix();
  // Two passes over the same boxes: count, then place (triangles in index order within a cell).
  cell_begin_.assign(static_cast<std::size_t>(dims_.prod()) + 1, 0);
  for (int pass = 0; pass < 2; ++pass) {
    std::vector<int> next;
    if (pass == 1) {
      for (std::size_t k = 1; k < cell_begin_.size(); ++k) cell_begin_[k] += cell_begin_[k - 1];
      triangles_.resize(cell_begin_.back());
      next.assign(cell_begin_.begin(), cell_begin_.end() - 1);
    }
    for (int t = 0; t < n; ++t) {
      const Vec3i a = cell_of(lo[t]), b = cell_of(hi[t]);
      for (int z = a.z(); z <= b.z(); ++z)
        for (int y = a.y(); y <= b.y(); ++y)
          for (int x = a.x(); x <= b.x(); ++x) {
            const int k = cell_index(x, y, z);
            if (pass == 0) ++cell_begin_[k + 1];
            else triangles_[next[k]++] = t;
          }
    }
  }
}

Vec3i TriangleGrid::cell_of(const Vec3& p) const {
  const Vec3 c = ((p - origin_) / cell_).array().floor();
  return c.cwiseMax(Vec3::Zero()).cwiseMin((dims_ - Vec3i::Ones()).cast<double>()).cast<int>();
}

SegmentHit TriangleGrid::first_crossing(const Vec3& p, const Vec3& q, double slack, double t_min, double t_max) const {
  SegmentHit hit;
  if (triangles_.empty() || !p.allFinite() || !q.allFinite()) return hit;
  // The segment as far as t reaches, beyond its ends with t_min < 0 or t_max > 1.
  const Vec3 from = p + std::min(0.0, t_min) * (q - p), to = p + std::max(1.0, t_max) * (q - p);
  const Vec3 lo = from.cwiseMin(to), hi = from.cwiseMax(to);
  const Vec3 box_hi = origin_ + dims_.cast<double>() * cell_;
  if ((lo.array() > box_hi.array()).any() || (hi.array() < origin_.array()).any()) return hit;
  const Vec3i a = cell_of(lo), b = cell_of(hi);
  for (int z = a.z(); z <= b.z(); ++z)
    for (int y = a.y(); y <= b.y(); ++y)
      for (int x = a.x(); x <= b.x(); ++x) {
        const int k = cell_index(x, y, z);
        for (int i = cell_begin_[k]; i < cell_begin_[k + 1]; ++i) {
          const int t = triangles_[i];
          const Vec3i& f = mesh_.triangles[t];
          const double s = segment_triangle_parameter(p, q, mesh_.positions[f[0]], mesh_.positions[f[1]], mesh_.positions[f[2]],
                                                      slack, t_min, t_max);
          if (!std::isnan(s) && (!hit.found() || s < hit.t || (s == hit.t && t < hit.triangle))) hit = {s, t};
        }
      }
  return hit;
}

}  // namespace hairfit
