#include "prepare/scalp_level_set.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>

#include "core/error.h"
#include "core/fast_winding.h"
#include "core/parallel.h"
#include "field/distance_field.h"
#include "field/hair_region.h"
#include "prepare/level_set_clip.h"
#include "prepare/holes.h"
#include "prepare/level_set_strip.h"
#include "prepare/marching_tetrahedra.h"

namespace hairfit {

namespace {

// The thickness ramp: 0 at the hairline with slope π/2 per ramp length, 1 from one ramp length on
// (C¹ there). A linear start makes the scalp leave the hull at an angle, so the level set is
// resolved right up to the hairline instead of grazing the hull.
double ramp_shape(double x) { return std::sin(0.5 * M_PI * std::clamp(x, 0.0, 1.0)); }

// The floor lies T + T·ramp_shape(k·g / ramp) deep: as deep as twice the scalp away from the
// hairline, but leaving it k times as steeply (76° against the scalp's 46° below the hull, with
// T = 2 cm over 3 cm), so the strips joining both to the hairline stay well apart.
constexpr double kFloorSteepness = 3.0;

// Jacobi passes that smooth the distance from the hairline across the grid (hairline_distance_at_nodes).
constexpr int kDistancePasses = 4;

// The longest hole in a level set's piece that is filled, as a share of the piece's rim (the hull's
// own holes are filled up to HullOptions::max_hole, the same share by default).
constexpr double kMaxLevelSetHole = 0.25;

double signed_volume(const Mesh& mesh) {
  double v = 0.0;
  for (const Vec3i& t : mesh.triangles)
    v += mesh.positions[t[0]].dot(mesh.positions[t[1]].cross(mesh.positions[t[2]]));
  return v / 6.0;
}

// The largest part (by triangles, through shared vertices) of a mesh, its unused vertices dropped;
// `values` per vertex follow. How many other parts there were goes to `dropped`.
Mesh largest_part(const Mesh& mesh, std::vector<double>& values, int& dropped) {
  const int n = static_cast<int>(mesh.positions.size());
  std::vector<int> parent(n);
  std::iota(parent.begin(), parent.end(), 0);
  auto root = [&](int v) {
    while (parent[v] != v) v = parent[v] = parent[parent[v]];
    return v;
  };
  for (const Vec3i& t : mesh.triangles)
    for (int k = 1; k < 3; ++k) {
      const int a = root(t[0]), b = root(t[k]);
      if (a != b) parent[std::max(a, b)] = std::min(a, b);
    }
  std::vector<int> count(n, 0);
  for (const Vec3i& t : mesh.triangles) ++count[root(t[0])];
  const int best = static_cast<int>(std::max_element(count.begin(), count.end()) - count.begin());
  dropped = static_cast<int>(std::count_if(count.begin(), count.end(), [](int c) { return c > 0; })) - 1;
  Mesh out;
  std::vector<double> kept_values;
  std::vector<int> index(n, -1);
  for (const Vec3i& t : mesh.triangles) {
    if (root(t[0]) != best) continue;
    Vec3i f;
    for (int k = 0; k < 3; ++k) {
      if (index[t[k]] < 0) {
        index[t[k]] = static_cast<int>(out.positions.size());
        out.positions.push_back(mesh.positions[t[k]]);
        kept_values.push_back(values[t[k]]);
      }
      f[k] = index[t[k]];
    }
    out.triangles.push_back(f);
  }
  values = std::move(kept_values);
  return out;
}

// Cumulative arc length along a closed loop from its first vertex, as a share of the whole
// (size + 1 entries, the last 1).
std::vector<double> loop_parameters(const std::vector<Vec3>& loop) {
  std::vector<double> s(loop.size() + 1, 0.0);
  for (std::size_t i = 0; i < loop.size(); ++i) s[i + 1] = s[i] + (loop[(i + 1) % loop.size()] - loop[i]).norm();
  for (double& x : s) x /= s.back();
  return s;
}

// Each point of `inner` (a loop near `outer`, starting by its first point) placed along `outer`:
// the arc length share of its closest point there, unwrapped to follow the previous one and
// held non-decreasing, so zipping the two loops by these shares pairs points across, not by how
// long each loop is (the inner loop is shorter where the hairline bends away from it).
std::vector<double> parameters_along(const std::vector<Vec3>& outer, const std::vector<Vec3>& inner) {
  const std::vector<double> s = loop_parameters(outer);
  const std::size_t n = outer.size();
  std::vector<double> out(inner.size() + 1, 1.0);
  double previous = 0.0;
  for (std::size_t i = 0; i < inner.size(); ++i) {
    double best = INFINITY, at = 0.0;
    for (std::size_t j = 0; j < n; ++j) {
      const Vec3 &a = outer[j], &b = outer[(j + 1) % n];
      const double t = std::clamp((inner[i] - a).dot(b - a) / std::max(1e-300, (b - a).squaredNorm()), 0.0, 1.0);
      const double d = (a + t * (b - a) - inner[i]).squaredNorm();
      if (d < best) best = d, at = s[j] + t * (s[j + 1] - s[j]);
    }
    if (i == 0) at = at > 0.5 ? at - 1.0 : at;  // the start lies at the outer loop's first point
    else at += std::round(previous - at);         // the turn nearest the previous point's
    previous = std::clamp(std::max(previous, at), 0.0, 1.0);
    out[i] = previous;
  }
  out[0] = 0.0;
  return out;
}

// The zero set of `values` clipped where the thickness falls to ε, its largest part joined to
// `outer` (a loop running the same way as the piece's boundary) by a strip: a zipper pairing the
// vertices of both loops by their places along `reference` (parameters_along; the hairline,
// which lies above both).
LevelSetSheet sheet(const SampleGrid& grid, const std::vector<double>& values, const std::vector<double>& node_thickness,
            double epsilon, const std::vector<Vec3>& outer, const std::vector<Vec3>& reference, bool must_be_disk,
            const std::string& what, const std::string& file) {
  const ZeroSet zero = marching_tetrahedra(grid, values);
  SelectionField above;
  above.values.resize(zero.at.size());
  for (std::size_t v = 0; v < zero.at.size(); ++v) {
    const EdgePoint& e = zero.at[v];
    above.values[v] = (1.0 - e.t) * node_thickness[e.a] + e.t * node_thickness[e.b] - epsilon;
  }
  // No snapping: moving a vertex of these small triangles onto the cut could turn one over.
  ClipOptions exact;
  exact.snap = 0.0;
  const Clipped clipped = clip_at_level_set(zero.mesh, above, exact);
  std::vector<double> thickness(clipped.mesh.positions.size());
  // Clipping keeps the zero set's vertices first and adds the crossings, where the value is 0.
  for (std::size_t v = 0; v < thickness.size(); ++v)
    thickness[v] = clipped.scan_vertex[v] >= 0 ? above.values[clipped.scan_vertex[v]] + epsilon : epsilon;
  LevelSetSheet s;
  s.mesh = largest_part(clipped.mesh, thickness, s.dropped_parts);
  s.thickness = thickness;
  MeshTopology topology = analyse_topology(s.mesh);
  FilledHoles holes;
  // Where the layer thins below ε inside the hair (skin coming near it, a braid's root), the piece
  // has holes: those up to kMaxLevelSetHole of its rim are filled (holes.h), the fans' centres
  // placed for their loops' mean thickness.
  if (topology.nonmanifold_vertices.empty() && topology.boundary_loops.size() > 1) {
    holes = fill_holes(s.mesh, topology, kMaxLevelSetHole);
    for (std::size_t h = 0; h < holes.loops.size(); ++h) {
      if (holes.centres[h] < 0) continue;
      double sum = 0.0;
      for (int v : holes.loops[h]) sum += s.thickness[v];
      s.thickness.push_back(sum / static_cast<double>(holes.loops[h].size()));
    }
    s.holes_filled = holes.filled;
    s.longest_hole = holes.longest_filled;
    if (holes.filled > 0) topology = analyse_topology(s.mesh);
  }
  // The scalp must be a disk for the chart; the floor only closes the volume, so a handle in it
  // (where it passes under a tube of hair) is kept, but it too must end in one loop.
  const bool usable = !s.mesh.triangles.empty() && topology.boundary_loops.size() == 1 &&
                      topology.nonmanifold_vertices.empty() && (topology.is_disk() || !must_be_disk);
  if (!usable) {
    char text[768], open[256] = "";
    if (holes.open > 0)
      std::snprintf(open, sizeof open, "; a hole %.3g cm long, beyond the %.0f%% of the rim's %.3g cm that is filled",
                    holes.longest_open, 100.0 * kMaxLevelSetHole, holes.rim_length);
    std::snprintf(text, sizeof text,
                  "the level set for the %s under this hull is no disk (%zu boundary loops, Euler characteristic %d, "
                  "%d non-manifold vertices%s%s); try a smaller --crown-thickness, a finer --scalp-voxel or smooth the "
                  "scan's hair",
                  what.c_str(), topology.boundary_loops.size(), topology.euler_characteristic,
                  static_cast<int>(topology.nonmanifold_vertices.size()), holes.filled > 0 ? ", after filling its smaller holes" : "", open);
    throw InputError(file, text);
  }
  const std::vector<int>& loop = topology.boundary_loops[0];
  std::vector<Vec3> a_points;
  for (int v : loop) a_points.push_back(s.mesh.positions[v]);
  const Vec3& first = outer.front();
  const int start = static_cast<int>(std::min_element(a_points.begin(), a_points.end(), [&](const Vec3& p, const Vec3& q) {
                                       return (p - first).squaredNorm() < (q - first).squaredNorm();
                                     }) - a_points.begin());
  std::rotate(a_points.begin(), a_points.begin() + start, a_points.end());
  s.inner.assign(loop.begin(), loop.end());
  std::rotate(s.inner.begin(), s.inner.begin() + start, s.inner.end());
  // Both loops run with their surface on the left seen from outside; a piece facing the other way
  // would run against the outer loop.
  double agreement = 0.0;
  const std::vector<double> sa = parameters_along(reference, a_points), sb = parameters_along(reference, outer);
  for (std::size_t i = 0; i < a_points.size(); ++i) {
    const std::size_t j = std::min(outer.size() - 1, static_cast<std::size_t>(sa[i] * outer.size()));
    agreement += (a_points[(i + 1) % a_points.size()] - a_points[i]).dot(outer[(j + 1) % outer.size()] - outer[j]);
  }
  if (!(agreement > 0.0))
    throw InputError(file, "the level set for the " + what + " runs against the hull's hairline (it faces the head); "
                           "check that the scan is closed around the head");
  s.piece_vertices = s.mesh.positions.size();
  for (const Vec3& p : outer) {
    s.outer.push_back(static_cast<int>(s.mesh.positions.size()));
    s.mesh.positions.push_back(p), s.thickness.push_back(0.0);
  }
  s.strip_begin = s.mesh.triangles.size();
  s.inner_at = sa;
  s.outer_at = sb;
  zip_strip(s, std::vector<double>(outer.size(), 0.0), std::vector<Vec3>(outer.size(), Vec3::Zero()));
  return s;
}

// Jacobi passes moving each vertex of the scalp's piece toward its neighbours' mean, by
// ½·((t − ε)/(T − ε))² of the way for a vertex placed at thickness t (so the piece's end, where the floor joins it, and
// the strip stay put): the level set follows every turn of the closest point between hull and
// skin, which leaves creases a voxel wide where the two meet at an angle. A move is kept only
// while the vertex stays between ½ and 1½ times its depth below the scan (so it neither nears the
// hull nor sinks to the floor, at 2 to 4 times the scalp's depth).
void relax(LevelSetSheet& s, const DistanceField& field, double crown, double epsilon, int passes, int threads) {
  const int n = static_cast<int>(s.mesh.positions.size());
  std::vector<char> fixed(n, 0);
  for (int v : s.inner) fixed[v] = 1;
  for (int v : s.outer) fixed[v] = 1;
  const std::vector<std::vector<int>> next = vertex_neighbours(s.mesh);
  std::vector<Vec3> previous;
  for (int pass = 0; pass < passes; ++pass) {
    previous = s.mesh.positions;
    // Each vertex reads only `previous`: any split gives the same result.
    parallel_for_ranges(n, 1024, threads, [&](int begin, int end) {
      for (int v = begin; v < end; ++v) {
        if (fixed[v] || next[v].empty()) continue;
        Vec3 mean = Vec3::Zero();
        for (int k : next[v]) mean += previous[k];
        const double weight = 0.5 * std::pow(std::max(0.0, (s.thickness[v] - epsilon) / (crown - epsilon)), 2);
        const Vec3 moved = previous[v] + weight * (mean / static_cast<double>(next[v].size()) - previous[v]);
        const double depth = -field.value(previous[v]), depth_moved = -field.value(moved);
        if (depth_moved >= 0.5 * depth && depth_moved <= 1.5 * depth) s.mesh.positions[v] = moved;
      }
    });
  }
}

// The distance from the hairline the layers are placed for, at every node: 0 outside the scan
// (beyond 2 voxels), infinite deeper than `depth`, and between them the distance at the node's
// closest point of the scan (`carried`), smoothed by kDistancePasses Jacobi passes (each node
// halfway to its neighbours' mean) at nodes deeper than half a voxel. The closest point jumps where
// another part of the scan becomes nearer (under a braid lying over the neck, the skin), and with
// it the distance; unsmoothed, the scalp's and the floor's ends part there and the strip joining
// them cuts the scalp. Nodes at the scan keep their exact value, so the hairline stays where it is.
std::vector<double> hairline_distance_at_nodes(const SampleGrid& grid, const DistanceField& field,
                                               const std::vector<double>& carried, double depth, int threads) {
  const double h = grid.spacing;
  std::vector<double> distance(grid.nodes());
  std::vector<char> smoothed(grid.nodes(), 0);
  parallel_for(grid.dims.z(), threads, [&](int k) {
    for (int j = 0; j < grid.dims.y(); ++j)
      for (int i = 0; i < grid.dims.x(); ++i) {
        const std::int64_t n = grid.node(i, j, k);
        const double d = -field.sample(i, j, k);
        distance[n] = d <= -2.0 * h ? 0.0 : INFINITY;
        if (d > -2.0 * h && d < depth && !std::isnan(carried[n])) {
          distance[n] = carried[n];
          smoothed[n] = d > 0.5 * h;
        }
      }
  });
  const std::int64_t step[6] = {1, -1, grid.dims.x(), -grid.dims.x(), std::int64_t(grid.dims.x()) * grid.dims.y(),
                                -std::int64_t(grid.dims.x()) * grid.dims.y()};
  std::vector<double> previous;
  for (int pass = 0; pass < kDistancePasses; ++pass) {
    previous = distance;
    parallel_for(std::max(0, grid.dims.z() - 2), threads, [&](int k) {
      for (int j = 1; j + 1 < grid.dims.y(); ++j)
        for (int i = 1; i + 1 < grid.dims.x(); ++i) {
          const std::int64_t n = grid.node(i, j, k + 1);
          if (!smoothed[n]) continue;
          double sum = 0.0;
          int count = 0;
          for (std::int64_t s : step)
            if (std::isfinite(previous[n + s])) sum += previous[n + s], ++count;
          if (count > 0) distance[n] = 0.5 * (previous[n] + sum / count);
        }
    });
  }
  return distance;
}

}  // namespace

double level_set_voxel(const ScalpOptions& o) { return o.voxel > 0.0 ? o.voxel : std::min(0.25, o.crown_thickness / 6.0); }

ScalpResult make_level_set_scalp(const Hull& hull, const Mesh& skin, const ScalpOptions& o, const std::string& file,
                                 int threads) {
  if (!(o.crown_thickness > 0.0) || !(o.ramp > 0.0) || !(o.voxel >= 0.0))
    throw InputError(file, "the crown thickness and the ramp must be positive lengths and the scalp voxel ≥ 0");
  const double T = o.crown_thickness;
  const double h = level_set_voxel(o);
  const Mesh& mesh = hull.mesh;
  ScalpResult r;
  r.method = "level set";
  const std::vector<std::vector<int>> next = vertex_neighbours(mesh);
  const std::vector<double> g = edge_distances(mesh, next, hull.hairline);
  r.hairline_reach = *std::max_element(g.begin(), g.end());
  r.ramp_length = std::min(o.ramp, 0.8 * r.hairline_reach);
  // The distance from the hairline, relaxed so the zigzag of edge paths does not show in the layer.
  std::vector<double> hull_distance = g;
  smooth_off_hairline(next, hull.hairline, hull_distance, 10);

  // The scan: the hull, then the skin, turned to face the way the hull does (together they
  // enclose the head).
  Mesh both = mesh;
  const int offset = static_cast<int>(mesh.positions.size());
  for (const Vec3& p : skin.positions) both.positions.push_back(p);
  for (const Vec3i& t : skin.triangles) both.triangles.emplace_back(t[0] + offset, t[1] + offset, t[2] + offset);
  if (signed_volume(both) < 0.0)
    for (std::size_t t = mesh.triangles.size(); t < both.triangles.size(); ++t) std::swap(both.triangles[t][1], both.triangles[t][2]);

  // The scan's signed distance, exact to the floor's depth 2T and a little beyond.
  const FastWindingNumber winding(both, HairRegion::kFirstBeta, threads);
  FieldSpec spec;
  spec.voxel = h;
  spec.band = std::ceil((2.0 * T + 3.0 * h) / h);
  spec.margin = 3.0 * h;
  spec.name = file;
  // Only the scan near the hull matters: every point within 2T of the hull's level sets has its
  // closest point on the hull or on skin within reach of it, so the field is built of the hull and
  // the skin triangles that come within that reach of the hull's box (the sign still comes from
  // the whole scan's winding number).
  const auto [hull_low, hull_high] = bounding_box(mesh);
  const double reach_out = 2.0 * T + r.ramp_length + 4.0 * h;
  Mesh near = mesh;
  near.positions = both.positions;
  for (std::size_t t = mesh.triangles.size(); t < both.triangles.size(); ++t) {
    const Vec3i& f = both.triangles[t];
    const Vec3 &a = both.positions[f[0]], &b = both.positions[f[1]], &c = both.positions[f[2]];
    const Vec3 low = a.cwiseMin(b).cwiseMin(c), high = a.cwiseMax(b).cwiseMax(c);
    if ((low.array() <= hull_high.array() + reach_out).all() && (high.array() >= hull_low.array() - reach_out).all())
      near.triangles.push_back(f);
  }
  // The distance from the hairline at each node's closest point of the scan: the hull's, 0 on the skin.
  std::vector<double> from_hairline = hull_distance;
  from_hairline.resize(both.positions.size(), 0.0);
  const CarriedField carried =
      make_distance_field_carrying(near, from_hairline, spec, threads, RobustInside{{winding_soup(both, winding)}});
  const DistanceField& field = carried.field;

  SampleGrid grid;
  grid.origin = field.origin();
  grid.spacing = h;
  grid.dims = field.dims();
  const std::vector<double> node_distance = hairline_distance_at_nodes(grid, field, carried.carried, 2.0 * T + 2.0 * h, threads);
  std::vector<double> thickness(grid.nodes()), scalp_value(grid.nodes()), floor_value(grid.nodes());
  parallel_for(grid.dims.z(), threads, [&](int k) {
    for (int j = 0; j < grid.dims.y(); ++j)
      for (int i = 0; i < grid.dims.x(); ++i) {
        const std::int64_t n = grid.node(i, j, k);
        const double d = -field.sample(i, j, k);
        const double distance = node_distance[n];
        const double t = T * ramp_shape(distance / r.ramp_length);
        thickness[n] = t;
        scalp_value[n] = t - d;
        floor_value[n] = t + T * ramp_shape(kFloorSteepness * distance / r.ramp_length) - d;
      }
  });
  const double epsilon = T * ramp_shape(1.5 * h / r.ramp_length);
  std::vector<Vec3> hairline;
  for (int v : hull.hairline) hairline.push_back(mesh.positions[v]);
  LevelSetSheet scalp = sheet(grid, scalp_value, thickness, epsilon, hairline, hairline, true, "scalp", file);
  r.strip_feet = lower_strip(scalp, mesh, hull.hairline, field, epsilon, threads);
  relax(scalp, field, T, epsilon, o.smoothing_passes, threads);
  // The floor joins the scalp's piece where it ends, not the hairline: within those 1.5 voxels
  // of it the volume's floor is the scalp's strip (reversed), and the two strips can never cross.
  std::vector<Vec3> scalp_end;
  for (int v : scalp.inner) scalp_end.push_back(scalp.mesh.positions[v]);
  LevelSetSheet floor = sheet(grid, floor_value, thickness, epsilon, scalp_end, hairline, false, "floor", file);
  r.dropped_parts = scalp.dropped_parts + floor.dropped_parts;
  r.scalp_holes_filled = scalp.holes_filled;
  r.floor_holes_filled = floor.holes_filled;
  r.longest_hole_filled = std::max(scalp.longest_hole, floor.longest_hole);

  // The closed volume: the hull, the scalp's strip and the floor, reversed, sharing the hairline
  // and the scalp piece's end.
  r.volume = mesh;
  r.volume_vertex.assign(scalp.mesh.positions.size(), -1);
  for (std::size_t k = 0; k < scalp.outer.size(); ++k) r.volume_vertex[scalp.outer[k]] = hull.hairline[k];
  for (int v : scalp.inner) {
    r.volume_vertex[v] = static_cast<int>(r.volume.positions.size());
    r.volume.positions.push_back(scalp.mesh.positions[v]);
  }
  for (std::size_t v = scalp.piece_vertices + scalp.outer.size(); v < scalp.mesh.positions.size(); ++v) {
    r.volume_vertex[v] = static_cast<int>(r.volume.positions.size());  // the strip's feet
    r.volume.positions.push_back(scalp.mesh.positions[v]);
  }
  for (std::size_t t = scalp.strip_begin; t < scalp.mesh.triangles.size(); ++t) {
    const Vec3i& f = scalp.mesh.triangles[t];
    r.volume.triangles.emplace_back(r.volume_vertex[f[0]], r.volume_vertex[f[2]], r.volume_vertex[f[1]]);
  }
  std::vector<int> index(floor.mesh.positions.size(), -1);
  for (std::size_t k = 0; k < floor.outer.size(); ++k) index[floor.outer[k]] = r.volume_vertex[scalp.inner[k]];
  for (std::size_t v = 0; v < index.size(); ++v) {
    if (index[v] >= 0) continue;
    index[v] = static_cast<int>(r.volume.positions.size());
    r.volume.positions.push_back(floor.mesh.positions[v]);
  }
  for (const Vec3i& t : floor.mesh.triangles) r.volume.triangles.emplace_back(index[t[0]], index[t[2]], index[t[1]]);

  r.scalp = std::move(scalp.mesh);
  r.hairline = std::move(scalp.outer);
  r.thickness = std::move(scalp.thickness);
  r.ramp.resize(r.thickness.size());
  for (std::size_t v = 0; v < r.thickness.size(); ++v) r.ramp[v] = r.thickness[v] / T;
  return r;
}

}  // namespace hairfit
