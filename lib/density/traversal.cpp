#include "density/traversal.h"

namespace hairfit {

void traverse_segment(const GridGeometry& grid, const Vec3& a, const Vec3& b, std::vector<CellCrossing>& out) {
  out.clear();
  for_each_cell_crossing(grid, a, b, [&out](const Vec3i& cell, double length) { out.push_back({cell, length}); });
}

std::vector<CellCrossing> traverse_segment(const GridGeometry& grid, const Vec3& a, const Vec3& b) {
  std::vector<CellCrossing> out;
  traverse_segment(grid, a, b, out);
  return out;
}

}  // namespace hairfit
