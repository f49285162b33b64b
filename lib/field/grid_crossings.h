// Where a triangle soup's generalized winding number jumps along the lines of a grid, exactly.
// Internal to lib/field.
//
// Off its triangles the winding number w of a soup is smooth, and across a triangle it jumps by
// exactly the triangle's weight (−weight stepping onto the side its normal points to). So between
// two nodes of a grid line, w changes by the jumps on the grid edges between them plus a smooth
// part that only the soup's rims make (rim_bound.h). This records the net jump on every grid edge
// (a node to the next one along x, y or z), decided by exact integer predicates:
// - the vertices are snapped to a lattice of 2⁻¹⁶ voxel, so that every predicate is exact integer
//   arithmetic; the jumps are the snapped soup's, which differs from the soup only within 2⁻¹⁷
//   voxel of its surface;
// - the grid's nodes are displaced symbolically by (ε, ε², ε³) (simulation of simplicity, Edelsbrunner
//   and Mücke 1990), so that no node lies on a triangle's plane and no grid line meets an edge or a
//   vertex: a line through an edge that two triangles share crosses exactly one of them where the
//   surface passes through, and the jumps between two nodes are the same along every path that
//   winds around no rim.
#pragma once
#include <array>
#include <cstdint>
#include <vector>

#include "core/grid_geometry.h"
#include "field/winding_soup.h"

namespace hairfit::field {

class GridCrossings {
 public:
  // Throws std::invalid_argument where a vertex lies more than 2²⁴ voxels from the grid's origin
  // (the exact arithmetic's range).
  GridCrossings(const std::vector<SoupPart>& soup, const GridGeometry& grid, int threads);

  // The lines along `axis` are numbered by their nodes' other two indices u < t: u + dims[u]·t.
  int64_t line(int axis, int i, int j, int k) const {
    const Vec3i& d = dims_;
    if (axis == 0) return j + int64_t(d.y()) * k;
    if (axis == 1) return i + int64_t(d.x()) * k;
    return i + int64_t(d.x()) * j;
  }
  // The sum of the jumps stepping from node `from` to node `to` of line `line` along `axis`.
  int along(int axis, int64_t line, int from, int to) const {
    const Axis& a = axes_[axis];
    const int64_t first = a.offsets[line], last = a.offsets[line + 1];
    if (first == last || from == to) return 0;
    return prefix(a, first, last, to) - prefix(a, first, last, from);
  }
  // The sum of the jumps stepping from node `from` to node `to` along z, then y, then x.
  int path(const Vec3i& from, const Vec3i& to) const {
    return along(2, line(2, from.x(), from.y(), 0), from.z(), to.z()) +
           along(1, line(1, from.x(), 0, to.z()), from.y(), to.y()) + along(0, line(0, 0, to.y(), to.z()), from.x(), to.x());
  }
  // f(edge, jump) for every edge of line `line` along `axis` with a jump, ascending: `edge` is its
  // lower node, `jump` the sum of the jumps stepping up from it.
  template <class F>
  void for_each_jump(int axis, int64_t line, F&& f) const {
    const Axis& a = axes_[axis];
    for (int64_t e = a.offsets[line]; e < a.offsets[line + 1]; ++e) f(a.edge[e], a.jump[e]);
  }
  // Grid edges with a non-zero jump, over all axes.
  int64_t size() const { return int64_t(axes_[0].edge.size() + axes_[1].edge.size() + axes_[2].edge.size()); }

 private:
  struct Axis {
    std::vector<int64_t> offsets;  // per line, into the entries (one more than the lines)
    std::vector<int32_t> edge;     // the lower node of each edge with a jump, ascending per line
    std::vector<int32_t> before;   // per entry: the sum of its line's earlier jumps
    std::vector<int32_t> jump;     // stepping from node `edge` to `edge` + 1
  };
  // The sum of the jumps on edges below node n of the line whose entries are [first, last),
  // signed for stepping up.
  static int prefix(const Axis& a, int64_t first, int64_t last, int n);

  Vec3i dims_;
  std::array<Axis, 3> axes_;
};

}  // namespace hairfit::field
