#include "scalp/scalp_outputs.h"

#include <stdexcept>

#include "io/obj_mesh.h"
#include "io/ply_points.h"

namespace hairfit {

void write_chart_obj(const std::filesystem::path& path, const ScalpChart& chart, const Vec3& origin) {
  std::vector<Vec2> vt(chart.chart.size());
  for (std::size_t v = 0; v < vt.size(); ++v) vt[v] = Vec2((chart.chart[v].x() + 1) / 2, (chart.chart[v].y() + 1) / 2);
  if (origin == Vec3::Zero()) return write_obj_mesh(path, chart.mesh, vt);
  Mesh moved = chart.mesh;
  for (Vec3& x : moved.positions) x += origin;
  write_obj_mesh(path, moved, vt);
}

void write_roots_ply(const std::filesystem::path& path, const Roots& roots, const Clusters& clusters, const Vec3& origin) {
  const RootSet& s = roots.pores;
  const int n = s.size();
  if (static_cast<int>(clusters.pore_cluster.size()) != n)
    throw std::invalid_argument("write_roots_ply: clusters were made from other roots");
  PlyPoints ply;
  ply.positions = s.positions;
  for (Vec3& x : ply.positions) x += origin;
  auto column = [&](const char* name, bool is_int, auto&& value) {
    PlyColumn c{name, is_int, std::vector<double>(n)};
    for (int i = 0; i < n; ++i) c.values[i] = value(i);
    ply.columns.push_back(std::move(c));
  };
  for (int k = 0; k < 3; ++k) column(k == 0 ? "nx" : k == 1 ? "ny" : "nz", false, [&](int i) { return s.normals[i][k]; });
  for (int k = 0; k < 3; ++k) column(k == 0 ? "dx" : k == 1 ? "dy" : "dz", false, [&](int i) { return s.directions[i][k]; });
  column("length", false, [&](int i) { return s.lengths[i]; });
  column("cluster", true, [&](int i) { return static_cast<double>(clusters.pore_cluster[i]); });
  column("height", false, [&](int i) { return s.heights[i]; });
  column("chart_x", false, [&](int i) { return s.chart[i].x(); });
  column("chart_y", false, [&](int i) { return s.chart[i].y(); });
  write_ply_points(path, ply);
}

}  // namespace hairfit
