// Voxel traversal of a segment (Amanatides & Woo 1987, "A fast voxel traversal algorithm"): the
// cells a straight segment crosses and the length of the segment inside each, for the continuous
// density model (paper §3.5: each fibre adds length-in-cell / cell diagonal) and for the
// segments-per-cell histogram (Fig. 5).
#pragma once
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "core/types.h"
#include "density/grid.h"

namespace hairfit {

struct CellCrossing {
  Vec3i cell = Vec3i::Zero();  // (i, j, k), always inside the grid
  double length = 0.0;         // cm of the segment inside this cell, > 0
};

// The cells the segment a→b (cm) crosses, in order from a to b, each once, with the length inside
// each. Properties:
// - The lengths add up to the length of the part of the segment inside the grid box (to round-off,
//   ~1e-15 relative): a segment partly outside the grid is clipped to the box; outside parts
//   deposit nothing.
// - A segment lying exactly on a cell face or edge goes to the cell on the upper side of that
//   plane (the cell floor() picks), except at the grid's upper faces, where it stays in the last
//   cell; where it passes exactly through a cell corner or edge, cells touched only at that point
//   (zero length) are not listed.
// - A zero-length segment, one with a non-finite coordinate, or one entirely outside the grid
//   yields nothing.
// The result appends to `out` (cleared first) so callers can reuse its storage in a hot loop.
void traverse_segment(const GridGeometry& grid, const Vec3& a, const Vec3& b, std::vector<CellCrossing>& out);
std::vector<CellCrossing> traverse_segment(const GridGeometry& grid, const Vec3& a, const Vec3& b);

// The same walk, calling visit(cell, length) for each crossing in order instead of listing them
// (the deposit's inner loop: no list to fill and read back), and only for the cells of layers
// [k_begin, k_end): the walk starts where it enters them and ends where it leaves them (its layer
// only moves one way), with the lengths and cells it would have found walking from a.
template <class Visit>
void for_each_cell_crossing(const GridGeometry& grid, const Vec3& a, const Vec3& b, Visit&& visit,
                            int k_begin = std::numeric_limits<int>::min(), int k_end = std::numeric_limits<int>::max()) {
  const Vec3 d = b - a;
  const double length = d.norm();
  if (!(length > 0.0) || !std::isfinite(length) || grid.count() == 0) return;
  const Vec3 lo = grid.origin, hi = grid.upper();
  const double h = grid.voxel;

  // Clip the parameter range [0, 1] to the grid box (slab method).
  double t0 = 0.0, t1 = 1.0;
  for (int k = 0; k < 3; ++k) {
    if (d[k] == 0.0) {
      if (a[k] < lo[k] || a[k] > hi[k]) return;
      continue;
    }
    double ta = (lo[k] - a[k]) / d[k], tb = (hi[k] - a[k]) / d[k];
    if (ta > tb) std::swap(ta, tb);
    t0 = std::max(t0, ta);
    t1 = std::min(t1, tb);
  }
  if (!(t0 < t1)) return;

  // Start cell: the one the segment is in just after t0. Moving down an axis from exactly a cell
  // face means being in the lower cell; clamping absorbs round-off at the box faces.
  Vec3i cell;
  for (int k = 0; k < 3; ++k) {
    const double q = (a[k] + t0 * d[k] - lo[k]) / h;
    double fl = std::floor(q);
    if (d[k] < 0.0 && fl == q) fl -= 1.0;
    cell[k] = int(std::min(std::max(fl, 0.0), double(grid.dims[k] - 1)));
  }

  // Walk: the exit parameter of each axis comes from the cell index (never accumulated), so
  // long segments do not drift; a tie (a corner) steps one axis and then visits a zero-length
  // cell, which is not listed. An axis's exit parameter changes only when the walk steps along
  // that axis, so it is recomputed then (the same expression), not at every step.
  auto exit_parameter = [&](int k) {
    if (d[k] == 0.0) return std::numeric_limits<double>::infinity();  // never the nearest
    const double face = lo[k] + h * (cell[k] + (d[k] > 0.0 ? 1 : 0));
    return (face - a[k]) / d[k];
  };
  double t = t0;
  // Below (above) the layers, moving up (down): go straight to where the walk crosses into them,
  // at T, the exit parameter of the layer before. By then the walk has stepped x and y through the
  // faces whose exit parameter is ≤ T (ties go to x and y), unless one of them left the grid
  // first; they are stepped on here without visiting. (Should one lag, the walk below catches it
  // up without a visit, as a visit needs t_next > t = T: the result never depends on it.)
  const bool below = cell.z() < k_begin, above = cell.z() >= k_end;
  if (below || above) {
    if (d.z() == 0.0 || (below && d.z() < 0.0) || (above && d.z() > 0.0)) return;  // never gets there
    cell.z() = below ? k_begin - 1 : k_end;
    const double T = exit_parameter(2);
    if (!(T < t1)) return;
    for (int k = 0; k < 2; ++k) {
      if (d[k] == 0.0) continue;
      while (exit_parameter(k) <= T) {
        cell[k] += d[k] > 0.0 ? 1 : -1;
        if (cell[k] < 0 || cell[k] >= grid.dims[k]) return;
      }
    }
    cell.z() = below ? k_begin : k_end - 1;
    if (cell.z() < 0 || cell.z() >= grid.dims.z()) return;
    t = T;
  }
  double exit[3] = {exit_parameter(0), exit_parameter(1), exit_parameter(2)};
  const int max_steps = grid.dims.sum() + 8;
  for (int step = 0; step < max_steps; ++step) {
    double t_next = t1;
    int axis = -1;
    for (int k = 0; k < 3; ++k) {
      if (exit[k] < t_next) {
        t_next = exit[k];
        axis = k;
      }
    }
    if (t_next > t) {
      visit(static_cast<const Vec3i&>(cell), (t_next - t) * length);
      t = t_next;
    }
    if (axis < 0) break;  // reached t1 inside this cell
    cell[axis] += d[axis] > 0.0 ? 1 : -1;
    if (cell[axis] < 0 || cell[axis] >= grid.dims[axis]) break;
    if (axis == 2 && (cell.z() < k_begin || cell.z() >= k_end)) break;  // left the layers for good
    exit[axis] = exit_parameter(axis);
  }
}

}  // namespace hairfit
