// A hashed uniform grid over points in 3D (or 2D with z = 0) for fixed-radius neighbour queries.
// Built once, then read-only: safe to query from many threads. Queries visit points in a fixed
// order (cells in x-fastest order, points by index within a cell), so sums over neighbours are
// deterministic.
#pragma once
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <utility>
#include <vector>

#include "core/huge_pages.h"
#include "core/types.h"

namespace hairfit {

class PointGrid {
 public:
  // cell: edge length of a grid cell (> 0), in the points' unit. Without keep_points the grid
  // holds only the order and the cells (for a caller that keeps its own copy of the points in
  // the grid's order); for_each_within, nearest and sorted() then must not be used.
  PointGrid(const Vec3* points, int count, double cell, bool keep_points = true);
  PointGrid(const std::vector<Vec3>& points, double cell, bool keep_points = true)
      : PointGrid(points.data(), static_cast<int>(points.size()), cell, keep_points) {}

  double cell() const { return cell_; }

  // Calls visit(index, squared_distance) for every point within `radius` of p.
  template <class Visit>
  void for_each_within(const Vec3& p, double radius, Visit&& visit) const {
    const double r2 = radius * radius;
    for_each_cell_near(cell_of(p), static_cast<int>(std::ceil(radius / cell_)), [&](int cell) {
      for (int k = cell_begin_[cell]; k < cell_begin_[cell + 1]; ++k) {
        const double d2 = (sorted_[k] - p).squaredNorm();
        if (d2 <= r2) visit(order_[k], d2);
      }
    });
  }

  // Index of the nearest point other than `exclude` (−1 for none), searching outward up to max_radius.
  int nearest(const Vec3& p, int exclude, double max_radius) const;

  // Occupied cells, for work organised by cell (one hash lookup per neighbouring cell and cell,
  // not per point): cell k holds the points order()[cell_begin(k) .. cell_begin(k + 1)).
  int cell_count() const { return static_cast<int>(cell_begin_.size()) - 1; }
  int cell_begin(int k) const { return cell_begin_[k]; }
  const HugeVector<int>& order() const { return order_; }
  // The points in that order (sorted()[k] = points[order()[k]]; empty without keep_points):
  // scans over a cell read memory contiguously instead of jumping through the index.
  const HugeVector<Vec3>& sorted() const { return sorted_; }
  // The occupied cells within `reach` cells of cell k, in the fixed order: their [begin, end)
  // ranges in order() and their integer coordinates (the cell spans coords .. coords + 1 in the
  // units of in_cells).
  struct CellRange {
    int begin, end;
    Vec3i coords;
  };
  Vec3i cell_coords(int k) const { return cell_coords_[k]; }
  // Fills `out` (cleared first), so a caller looping over cells reuses one buffer.
  void neighbourhood(int k, int reach, std::vector<CellRange>& out) const;
  // A position in cell units: the cell holding p is the floor of this.
  Vec3 in_cells(const Vec3& p) const { return Vec3((p.x() - origin_.x()) / cell_, (p.y() - origin_.y()) / cell_, (p.z() - origin_.z()) / cell_); }

 private:
  // Calls visit(cell) for every occupied cell within `reach` cells of `centre` on each axis, in the
  // fixed order (x fastest). Only cells inside the box of occupied cells can hold points (a flat
  // 2D set has one z layer), so the box is clipped to it first. Each row of cells (fixed y and z)
  // is one stretch of the cells in key order, x ascending: the cells of a row within reach are
  // found by one search in it instead of a hash lookup per cell.
  template <class Visit>
  void for_each_cell_near(const Vec3i& centre, int reach, Visit&& visit) const {
    const Vec3i lo = (centre - Vec3i::Constant(reach)).cwiseMax(occupied_lo_);
    const Vec3i hi = (centre + Vec3i::Constant(reach)).cwiseMin(occupied_hi_);
    if (row_start_.empty()) {  // too many rows for the row index (a sparse set)
      for (int z = lo.z(); z <= hi.z(); ++z)
        for (int y = lo.y(); y <= hi.y(); ++y)
          for (int x = lo.x(); x <= hi.x(); ++x) {
            const int cell = find(key(Vec3i(x, y, z)));
            if (cell >= 0) visit(cell);
          }
      return;
    }
    for (int z = lo.z(); z <= hi.z(); ++z)
      for (int y = lo.y(); y <= hi.y(); ++y) {
        const int row = (z - occupied_lo_.z()) * rows_y_ + (y - occupied_lo_.y());
        int cell = row_start_[row];
        const int end = row_start_[row + 1];
        while (cell < end && cell_coords_[cell].x() < lo.x()) ++cell;  // rows are short
        for (; cell < end && cell_coords_[cell].x() <= hi.x(); ++cell) visit(cell);
      }
  }

  // static_cast<int>(std::floor(x)) without the call into libm (baseline x86-64 has no rounding
  // instruction): truncation, one down for negative non-integers.
  static int floor_int(double x) {
    const int t = static_cast<int>(x);
    return x < t ? t - 1 : t;
  }
  Vec3i cell_of(const Vec3& p) const {
    const Vec3 u = in_cells(p);
    return Vec3i(floor_int(u.x()), floor_int(u.y()), floor_int(u.z()));
  }
  static std::uint64_t key(const Vec3i& c) {
    const auto f = [](int v) { return static_cast<std::uint64_t>(v + (1 << 20)) & 0x1fffff; };
    return f(c.x()) | (f(c.y()) << 21) | (f(c.z()) << 42);
  }

  // Point-sized arrays in huge pages (core/huge_pages.h): fresh memory is expensive.
  HugeVector<Vec3> sorted_;  // points in cell order
  double cell_;
  Vec3 origin_;
  HugeVector<int> order_;  // point indices sorted by cell key, then index
  // An empty table with room for `entries` cells (at most half full), and adding one.
  void build_table(std::size_t entries);
  void insert(std::uint64_t k, int cell);
  // Occupied cell with this key, or −1: open addressing, linear probing, power-of-two table.
  int find(std::uint64_t k) const {
    for (std::size_t slot = mix(k) & mask_;; slot = (slot + 1) & mask_) {
      if (table_[slot] < 0) return -1;
      if (cell_keys_[table_[slot]] == k) return table_[slot];
    }
  }
  static std::uint64_t mix(std::uint64_t x) {
    x ^= x >> 31;
    x *= 0x7fb5d329728ea185ull;
    return x ^ (x >> 27);
  }

  std::vector<int> table_;  // slot → occupied cell index, −1 empty
  std::size_t mask_ = 0;
  std::vector<std::uint64_t> cell_keys_;
  std::vector<int> cell_begin_;  // occupied cells in key order, with a final end offset
  std::vector<Vec3i> cell_coords_;
  // Row index: the cells of row (y, z) are row_start_[r] … row_start_[r + 1] − 1 for
  // r = (z − lo.z)·rows_y_ + (y − lo.y) over the occupied box; empty if that box has too many rows.
  std::vector<int> row_start_;
  int rows_y_ = 0;
  Vec3i occupied_lo_ = Vec3i::Zero(), occupied_hi_ = Vec3i::Constant(-1);  // box of occupied cells
};

}  // namespace hairfit
