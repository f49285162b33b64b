#include "prepare/hair_region.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>
#include <queue>
#include <unordered_map>

#include "core/error.h"
#include "core/vertex_sort.h"
#include "prepare/holes.h"

namespace hairfit {

namespace {

std::string vec_text(const Vec3& v) {
  char text[96];
  std::snprintf(text, sizeof text, "(%.4g, %.4g, %.4g)", v.x(), v.y(), v.z());
  return text;
}

// The triangles (indices into `tris`) sharing each triangle side's undirected edge, in increasing
// order: sides(t, k) lists those of side k (t[k] → t[k + 1]) of triangle t, t itself included.
// Built by a counting sort on each edge's lower vertex, so it costs no allocation per edge.
class EdgeTriangles {
 public:
  explicit EdgeTriangles(const std::vector<Vec3i>& tris) : corners_(tris) {
    int n = 0;
    for (const Vec3i& t : tris) n = std::max(n, t.maxCoeff() + 1);
    struct Side {
      int low, high, triangle, side;
    };
    std::vector<Side> sorted;
    sorted.reserve(3 * tris.size());
    for (int t = 0; t < static_cast<int>(tris.size()); ++t)
      for (int k = 0; k < 3; ++k) {
        const int a = tris[t][k], b = tris[t][(k + 1) % 3];
        sorted.push_back({std::min(a, b), std::max(a, b), t, k});
      }
    // By the lower vertex, then the higher one, then the triangle.
    sort_by_vertex(sorted, n, [](const Side& s) { return s.low; }, [](const Side& x, const Side& y) {
      return x.high != y.high ? x.high < y.high : x.triangle < y.triangle;
    });
    group_of_.resize(3 * tris.size());
    for (std::size_t i = 0; i < sorted.size(); ++i) {
      if (i == 0 || sorted[i].low != sorted[i - 1].low || sorted[i].high != sorted[i - 1].high)
        group_start_.push_back(static_cast<int>(i));
      group_of_[3 * sorted[i].triangle + sorted[i].side] = static_cast<int>(group_start_.size()) - 1;
      triangles_.push_back(sorted[i].triangle);
    }
    group_start_.push_back(static_cast<int>(sorted.size()));
  }
  struct Range {
    const int *first, *last;
    const int* begin() const { return first; }
    const int* end() const { return last; }
  };
  Range sides(int t, int k) const {
    const int g = group_of_[3 * t + k];
    return {triangles_.data() + group_start_[g], triangles_.data() + group_start_[g + 1]};
  }
  // The same for the side of triangle t (as built) that joins a and b, either way round; for a
  // caller that reorders the triangles' corners as it goes.
  Range sharing(int t, int a, int b) const {
    for (int k = 0; k < 3; ++k) {
      const int p = corners_[t][k], q = corners_[t][(k + 1) % 3];
      if ((p == a && q == b) || (p == b && q == a)) return sides(t, k);
    }
    return {nullptr, nullptr};
  }

 private:
  std::vector<Vec3i> corners_;
  std::vector<int> group_of_, group_start_, triangles_;
};

// Connected parts through shared edges: part id per triangle, ids in order of first triangle.
std::vector<int> edge_parts(const std::vector<Vec3i>& tris, int& count) {
  const EdgeTriangles edges(tris);
  std::vector<int> part(tris.size(), -1);
  count = 0;
  for (int seed = 0; seed < static_cast<int>(tris.size()); ++seed) {
    if (part[seed] >= 0) continue;
    std::queue<int> queue;
    queue.push(seed);
    part[seed] = count;
    while (!queue.empty()) {
      const int t = queue.front();
      queue.pop();
      for (int k = 0; k < 3; ++k)
        for (int u : edges.sides(t, k))
          if (part[u] < 0) part[u] = count, queue.push(u);
    }
    ++count;
  }
  return part;
}

double area_of(const Mesh& scan, const Vec3i& t) {
  return 0.5 * (scan.positions[t[1]] - scan.positions[t[0]]).cross(scan.positions[t[2]] - scan.positions[t[0]]).norm();
}

// Keeps, at every vertex whose triangles form several fans (touching only at the vertex), the fan
// with the largest area; returns how many triangles it removed.
int shave_bow_ties(const Mesh& scan, std::vector<int>& kept) {
  std::vector<Vec3i> tris;
  for (int t : kept) tris.push_back(scan.triangles[t]);
  std::unordered_map<int, std::vector<int>> around;  // vertex → local triangles
  for (int t = 0; t < static_cast<int>(tris.size()); ++t)
    for (int k = 0; k < 3; ++k) around[tris[t][k]].push_back(t);
  std::vector<char> drop(tris.size(), 0);
  std::vector<int> vertices;
  for (const auto& entry : around) vertices.push_back(entry.first);
  std::sort(vertices.begin(), vertices.end());  // deterministic order
  for (int v : vertices) {
    const std::vector<int>& fan = around[v];
    // Group the vertex's triangles by shared edges through v.
    std::vector<int> group(fan.size(), -1);
    int groups = 0;
    for (std::size_t s = 0; s < fan.size(); ++s) {
      if (group[s] >= 0) continue;
      std::vector<std::size_t> stack{s};
      group[s] = groups;
      while (!stack.empty()) {
        const std::size_t a = stack.back();
        stack.pop_back();
        for (std::size_t b = 0; b < fan.size(); ++b) {
          if (group[b] >= 0) continue;
          int shared = 0;
          for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) shared += tris[fan[a]][i] == tris[fan[b]][j];
          if (shared >= 2) group[b] = groups, stack.push_back(b);
        }
      }
      ++groups;
    }
    if (groups < 2) continue;
    std::vector<double> area(groups, 0.0);
    for (std::size_t s = 0; s < fan.size(); ++s) area[group[s]] += area_of(scan, tris[fan[s]]);
    const int best = static_cast<int>(std::max_element(area.begin(), area.end()) - area.begin());
    for (std::size_t s = 0; s < fan.size(); ++s)
      if (group[s] != best) drop[fan[s]] = 1;
  }
  std::vector<int> next;
  for (std::size_t t = 0; t < kept.size(); ++t)
    if (!drop[t]) next.push_back(kept[t]);
  const int removed = static_cast<int>(kept.size() - next.size());
  kept = std::move(next);
  return removed;
}


// Makes neighbouring triangles traverse their shared edge in opposite directions (breadth first
// from triangle 0); throws if the surface cannot be oriented.
void orient_consistently(Mesh& mesh, const std::string& file) {
  const EdgeTriangles edges(mesh.triangles);
  std::vector<char> done(mesh.triangles.size(), 0);
  auto direction = [](const Vec3i& t, int a, int b) {
    for (int k = 0; k < 3; ++k) {
      if (t[k] == a && t[(k + 1) % 3] == b) return 1;
      if (t[k] == b && t[(k + 1) % 3] == a) return -1;
    }
    return 0;
  };
  std::queue<int> queue;
  queue.push(0);
  done[0] = 1;
  while (!queue.empty()) {
    const int t = queue.front();
    queue.pop();
    for (int k = 0; k < 3; ++k) {
      const int a = mesh.triangles[t][k], b = mesh.triangles[t][(k + 1) % 3];
      for (int u : edges.sharing(t, a, b)) {
        if (u == t) continue;
        const bool same = direction(mesh.triangles[u], a, b) == 1;
        if (!done[u]) {
          if (same) std::swap(mesh.triangles[u][1], mesh.triangles[u][2]);
          done[u] = 1;
          queue.push(u);
        } else if (same) {
          throw InputError(file, "the hair region cannot be oriented (it is a Möbius-like surface near " +
                                     vec_text(mesh.positions[a]) + "); repair the scan");
        }
      }
    }
  }
}

// Clamps the mask's values to ±tolerance (a bare vertex counts as bare however far its colour is)
// and averages each with its neighbours (Jacobi rounds, so the result does not depend on order).
void smooth_mask(const Mesh& scan, const HairSelection& s, std::vector<double>& f) {
  const double limit = std::max(s.tolerance, 1e-12);
  for (double& x : f) x = std::clamp(x, -limit, limit);
  if (s.mask_smoothing <= 0) return;
  const std::vector<std::vector<int>> neighbours = vertex_neighbours(scan);
  for (int round = 0; round < s.mask_smoothing; ++round) {
    std::vector<double> next(f.size());
    for (std::size_t v = 0; v < f.size(); ++v) {
      double sum = f[v];
      for (int u : neighbours[v]) sum += f[u];
      next[v] = sum / static_cast<double>(neighbours[v].size() + 1);
    }
    f = std::move(next);
  }
}

}  // namespace

std::string HairSelection::describe() const {
  char text[256];
  if (kind == Kind::plane)
    std::snprintf(text, sizeof text, "plane through %s, hair toward %s", vec_text(point).c_str(), vec_text(normal).c_str());
  else if (kind == Kind::cap)
    std::snprintf(text, sizeof text, "cap about %s, axis %s, half-angle %.4g°", vec_text(centre).c_str(),
                  vec_text(axis).c_str(), half_angle);
  else
    std::snprintf(text, sizeof text, "mask colour %s within %.4g, smoothed %d times", vec_text(color).c_str(), tolerance,
                  mask_smoothing);
  return text;
}

SelectionField selection_field(const Mesh& scan, const std::vector<Vec3>& colors, const HairSelection& s,
                               const std::string& file) {
  if (s.kind == HairSelection::Kind::mask && colors.size() != scan.positions.size())
    throw InputError(file, "has no vertex colours, so --mask has nothing to read; paint the hair and export the "
                           "colours (OBJ lines `v x y z r g b`), or select the hair with --plane or --cap");
  SelectionField field;
  if (s.kind == HairSelection::Kind::plane) {
    const Vec3 point = s.point, normal = s.normal.normalized();
    field.at = [point, normal](const Vec3& p) { return (p - point).dot(normal); };
  } else if (s.kind == HairSelection::Kind::cap) {
    const Vec3 centre = s.centre, axis = s.axis.normalized();
    const double half = s.half_angle * M_PI / 180.0;
    field.at = [centre, axis, half](const Vec3& p) {
      const Vec3 d = p - centre;
      return d.norm() > 0.0 ? half - std::atan2(d.cross(axis).norm(), d.dot(axis)) : -1.0;
    };
  }
  for (std::size_t i = 0; i < scan.positions.size(); ++i)
    field.values.push_back(field.at ? field.at(scan.positions[i]) : s.tolerance - (colors[i] - s.color).norm());
  if (!field.at) smooth_mask(scan, s, field.values);
  return field;
}

Vec3 fit_sphere_centre(const std::vector<Vec3>& points) {
  Eigen::MatrixXd a(points.size(), 4);
  Eigen::VectorXd b(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    a.row(i) << 2.0 * points[i].x(), 2.0 * points[i].y(), 2.0 * points[i].z(), 1.0;
    b[i] = points[i].squaredNorm();
  }
  const Eigen::Vector4d x = a.colPivHouseholderQr().solve(b);
  return x.head<3>();
}

Hull cut_hull(const Mesh& scan_mesh, const SelectionField& field, const HullOptions& options, const std::string& file) {
  Hull hull;
  // From here on, "the scan" is the clipped scan: whole scan triangles and the parts the hairline cuts.
  const Clipped clipped = clip_at_level_set(scan_mesh, field, options.clip);
  const Mesh& scan = clipped.mesh;
  hull.cut_triangles = clipped.cut_triangles;
  hull.snapped_vertices = clipped.snapped_vertices;
  std::vector<int> kept(scan.triangles.size());
  std::iota(kept.begin(), kept.end(), 0);
  hull.selected_triangles = static_cast<int>(kept.size());
  if (kept.empty()) {
    const long picked = std::count_if(field.values.begin(), field.values.end(), [](double f) { return f >= 0.0; });
    throw InputError(file, "the hair selection catches no part of the scan (" + std::to_string(picked) + " of " +
                               std::to_string(field.values.size()) +
                               " vertices picked); check the selection's coordinates against the scan's (they "
                               "are in the scan's own units)");
  }
  for (int t : kept) hull.selected_area += area_of(scan, scan.triangles[t]);

  // The largest part (by area), shaved of bow-ties; shaving can split it, so repeat until stable.
  for (int round = 0;; ++round) {
    std::vector<Vec3i> tris;
    for (int t : kept) tris.push_back(scan.triangles[t]);
    int count = 0;
    const std::vector<int> part = edge_parts(tris, count);
    if (round == 0) hull.parts = count;
    std::vector<double> area(count, 0.0);
    for (std::size_t i = 0; i < kept.size(); ++i) area[part[i]] += area_of(scan, tris[i]);
    const int best = static_cast<int>(std::max_element(area.begin(), area.end()) - area.begin());
    if (round == 0 && area[best] < 0.5 * hull.selected_area) {
      char text[512];
      std::snprintf(text, sizeof text,
                    "the hair selection is not one connected region: it falls into %d parts and the largest holds "
                    "only %.0f%% of the selected area (%.4g of %.4g); select the hair as one piece (a mask painted "
                    "without gaps, or a plane or cap that cuts the scan once)",
                    count, 100.0 * area[best] / hull.selected_area, area[best], hull.selected_area);
      throw InputError(file, text);
    }
    std::vector<int> largest;
    for (std::size_t i = 0; i < kept.size(); ++i)
      if (part[i] == best) largest.push_back(kept[i]);
    kept = std::move(largest);
    const int shaved = shave_bow_ties(scan, kept);
    hull.shaved_triangles += shaved;
    if (shaved == 0 || round > 8) break;
  }

  // The hull's own vertex numbering, in scan order.
  std::vector<int> local(scan.positions.size(), -1);
  for (int t : kept)
    for (int k = 0; k < 3; ++k) local[scan.triangles[t][k]] = 0;
  for (std::size_t v = 0; v < local.size(); ++v) {
    if (local[v] < 0) continue;
    local[v] = static_cast<int>(hull.mesh.positions.size());
    hull.mesh.positions.push_back(scan.positions[v]);
    hull.scan_vertex.push_back(clipped.scan_vertex[v]);
  }
  for (int t : kept) {
    const Vec3i& f = scan.triangles[t];
    hull.mesh.triangles.emplace_back(local[f[0]], local[f[1]], local[f[2]]);
    hull.scan_triangle.push_back(clipped.scan_triangle[t]);
    hull.kept_area += area_of(scan, f);
  }
  MeshTopology topo = analyse_topology(hull.mesh);
  if (!topo.nonmanifold_vertices.empty())
    throw InputError(file, "the scan is non-manifold inside the hair region (an edge shared by 3 or more triangles near " +
                               vec_text(hull.mesh.positions[topo.nonmanifold_vertices[0]]) + "); repair the scan");
  if (topo.boundary_loops.empty())
    throw InputError(file, "the hair selection covers a closed surface (the whole scan?), so there is no hairline; "
                           "select only the hair");
  orient_consistently(hull.mesh, file);
  topo = analyse_topology(hull.mesh);

  // The hairline is the longest boundary loop; the others are holes, filled by a fan about their
  // centroid when short enough (holes.h).
  const FilledHoles holes = fill_holes(hull.mesh, topo, options.max_hole);
  hull.hairline_length = holes.rim_length;
  if (holes.open > 0) {
    char text[512];
    std::snprintf(text, sizeof text,
                  "the hair region has a hole %.4g long around %s (the hairline is %.4g long; holes up to %.0f%% "
                  "of it are filled); the scan is missing data there or the selection leaves an island out",
                  holes.longest_open, vec_text(holes.open_at).c_str(), hull.hairline_length, 100.0 * options.max_hole);
    throw InputError(file, text);
  }
  hull.scan_triangle.resize(hull.mesh.triangles.size(), -1);
  hull.scan_vertex.resize(hull.mesh.positions.size(), -1);
  hull.holes_filled = holes.filled;
  topo = analyse_topology(hull.mesh);
  if (!topo.is_disk())
    throw InputError(file, "the hair region is not a disk-like patch (Euler characteristic " +
                               std::to_string(topo.euler_characteristic) +
                               " with one hairline: it has handles, e.g. a strand bridging to the head); cut the "
                               "bridges from the scan or adjust the selection");
  hull.hairline = topo.boundary_loops[0];

  // Outward: the hull faces away from the centre of the sphere fitted to it.
  hull.centre = fit_sphere_centre(hull.mesh.positions);
  double facing = 0.0;
  for (int t = 0; t < static_cast<int>(hull.mesh.triangles.size()); ++t) {
    const Vec3i& f = hull.mesh.triangles[t];
    const Vec3& a = hull.mesh.positions[f[0]];
    facing += (hull.mesh.positions[f[1]] - a).cross(hull.mesh.positions[f[2]] - a).dot(a - hull.centre);
  }
  if (facing < 0.0) {
    for (Vec3i& f : hull.mesh.triangles) std::swap(f[1], f[2]);
    std::reverse(hull.hairline.begin(), hull.hairline.end());
  }
  return hull;
}

}  // namespace hairfit
