// A mesh's triangles binned on a uniform grid over its bounding box, for exact segment queries:
// every triangle is listed in each cell its bounding box touches, so a segment meets only the
// triangles near it. Built once, then read-only: safe to query from many threads.
#pragma once
#include <vector>

#include "core/mesh.h"

namespace hairfit {

struct SegmentHit {
  double t = 0.0;     // share of the way along the segment
  int triangle = -1;  // the triangle crossed, −1 for none
  bool found() const { return triangle >= 0; }
};

class TriangleGrid {
 public:
  // The cell's edge is twice the mean edge of a triangle's bounding box, so that a triangle
  // touches a few cells, grown where needed to keep the grid at most 8 cells per triangle.
  explicit TriangleGrid(const Mesh& mesh);

  // The largest slack first_crossing is exact for: the cells list each triangle grown by it.
  static constexpr double kSlackCovered = 1e-5;

  // The first crossing of segment pq with the mesh (the least t; of equal ones the lowest
  // triangle index), as segment_triangle_parameter decides each with `slack` (≤ kSlackCovered)
  // and t in (t_min, t_max): exact, and the same whatever the order of the cells.
  SegmentHit first_crossing(const Vec3& p, const Vec3& q, double slack = 0.0, double t_min = 1e-9,
                            double t_max = 1 - 1e-9) const;

  const Mesh& mesh() const { return mesh_; }
  double cell() const { return cell_; }

 private:
  Vec3i cell_of(const Vec3& p) const;
  int cell_index(int x, int y, int z) const { return x + dims_.x() * (y + dims_.y() * z); }

  const Mesh& mesh_;
  Vec3 origin_ = Vec3::Zero();
  double cell_ = 1.0;
  Vec3i dims_ = Vec3i::Zero();
  std::vector<int> cell_begin_;  // CSR: cell k lists triangles_[cell_begin_[k] .. cell_begin_[k + 1])
  std::vector<int> triangles_;
};

}  // namespace hairfit
