#include "core/point_grid.h"

#include <algorithm>
#include <stdexcept>

namespace hairfit {

PointGrid::PointGrid(const Vec3* points, int n, double cell, bool keep_points) : cell_(cell) {
  if (!(cell > 0) || !std::isfinite(cell)) throw std::invalid_argument("PointGrid: cell size must be positive");
  origin_ = Vec3::Zero();
  if (n > 0) {
    origin_ = points[0];
    for (int i = 1; i < n; ++i) origin_ = origin_.cwiseMin(points[i]);
  }
  // The order (cell key, then index) without sorting the points: the occupied cells are found
  // and counted (in order of first appearance, through the hash table), only they are sorted by
  // key, and the points are then placed cell by cell in index order.
  HugeVector<int> point_cell(n);  // cell of each point, numbered by first appearance
  std::vector<int> count;
  // The table grows with the cells found (a table sized for one cell per point would be 8 bytes
  // per point of fresh memory, most of it never used: points share cells).
  build_table(1024);
  for (int i = 0; i < n; ++i) {
    const std::uint64_t k = key(cell_of(points[i]));
    int c = find(k);
    if (c < 0) {
      c = static_cast<int>(cell_keys_.size());
      if (2 * (cell_keys_.size() + 1) > table_.size()) {  // keep it at most half full
        build_table(2 * (cell_keys_.size() + 1));
        for (int old = 0; old < c; ++old) insert(cell_keys_[old], old);
      }
      insert(k, c);
      cell_keys_.push_back(k);
      count.push_back(0);
    }
    point_cell[i] = c;
    ++count[c];
  }
  const int cells = static_cast<int>(cell_keys_.size());
  std::vector<std::pair<std::uint64_t, int>> by_key(cells);  // (key, first-appearance number)
  for (int c = 0; c < cells; ++c) by_key[c] = {cell_keys_[c], c};
  std::sort(by_key.begin(), by_key.end());
  std::vector<int> next(cells);  // per first-appearance number: the next free place of its cell
  cell_begin_.resize(cells + 1);
  cell_begin_[0] = 0;
  for (int r = 0; r < cells; ++r) {
    const int c = by_key[r].second;
    next[c] = cell_begin_[r];
    cell_keys_[r] = by_key[r].first;
    cell_begin_[r + 1] = cell_begin_[r] + count[c];
  }
  order_.resize(n);
  for (int i = 0; i < n; ++i) order_[next[point_cell[i]]++] = i;
  if (keep_points) {
    sorted_.resize(n);
    for (int k = 0; k < n; ++k) sorted_[k] = points[order_[k]];
  }
  cell_coords_.resize(cells);
  for (int c = 0; c < cells; ++c) {
    const Vec3i at = cell_of(points[order_[cell_begin_[c]]]);
    cell_coords_[c] = at;
    if (c == 0) occupied_lo_ = occupied_hi_ = at;
    occupied_lo_ = occupied_lo_.cwiseMin(at);
    occupied_hi_ = occupied_hi_.cwiseMax(at);
  }
  // The row index where the occupied box has at most a few rows per cell; else the hash table,
  // again, sized for the occupied cells, now numbered by key.
  rows_y_ = occupied_hi_.y() - occupied_lo_.y() + 1;
  const long long rows = static_cast<long long>(rows_y_) * (occupied_hi_.z() - occupied_lo_.z() + 1);
  if (cells > 0 && rows <= 4LL * cells + 4096) {
    row_start_.assign(rows + 1, 0);
    for (int c = 0; c < cells; ++c)
      ++row_start_[(cell_coords_[c].z() - occupied_lo_.z()) * rows_y_ + (cell_coords_[c].y() - occupied_lo_.y()) + 1];
    for (long long r = 0; r < rows; ++r) row_start_[r + 1] += row_start_[r];
    table_.clear();
  } else {
    build_table(cell_keys_.size());
    for (int c = 0; c < cells; ++c) insert(cell_keys_[c], c);
  }
}

void PointGrid::build_table(std::size_t entries) {
  std::size_t capacity = 16;
  while (capacity < 2 * entries) capacity *= 2;
  mask_ = capacity - 1;
  table_.assign(capacity, -1);
}

void PointGrid::insert(std::uint64_t k, int cell) {
  std::size_t slot = mix(k) & mask_;
  while (table_[slot] >= 0) slot = (slot + 1) & mask_;
  table_[slot] = cell;
}

void PointGrid::neighbourhood(int k, int reach, std::vector<CellRange>& out) const {
  out.clear();
  for_each_cell_near(cell_coords_[k], reach,
                     [&](int cell) { out.push_back({cell_begin_[cell], cell_begin_[cell + 1], cell_coords_[cell]}); });
}

int PointGrid::nearest(const Vec3& p, int exclude, double max_radius) const {
  for (double radius = cell_;; radius *= 2) {
    const double r = std::min(radius, max_radius);
    int best = -1;
    double best_d2 = INFINITY;
    for_each_within(p, r, [&](int i, double d2) {
      if (i != exclude && (d2 < best_d2 || (d2 == best_d2 && i < best))) best = i, best_d2 = d2;
    });
    if (best >= 0 || r >= max_radius) return best;
  }
}

}  // namespace hairfit
