#include "density/voxelise.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "density/traversal.h"

namespace hairfit {

namespace {

// The frustum in the frame of its axis: u from a to b, length L, two perpendicular unit axes.
struct Axis {
  Vec3 u, v, w;
  double length;
};

Axis frustum_axis(const Frustum& f) {
  Axis ax;
  const Vec3 d = f.b - f.a;
  ax.length = d.norm();
  ax.u = ax.length > 0.0 ? Vec3(d / ax.length) : Vec3::UnitZ();
  // A perpendicular from the smallest component of u, so it never degenerates.
  int m = 0;
  ax.u.cwiseAbs().minCoeff(&m);
  ax.v = ax.u.cross(Vec3::Unit(m)).normalized();
  ax.w = ax.u.cross(ax.v);
  return ax;
}

// Closest point of the convex trapezoid {0 ≤ t ≤ L, 0 ≤ ρ ≤ r(t)} (the frustum's meridian
// section) to (t, ρ), ρ ≥ 0. The closest point of the solid of revolution lies in the same
// half-plane, so this 2-D projection gives the 3-D one.
Vec2 closest_in_section(double t, double rho, double L, double ra, double rb) {
  const double r_at = L > 0.0 ? ra + (rb - ra) * std::min(std::max(t / L, 0.0), 1.0) : std::max(ra, rb);
  if (t >= 0.0 && t <= L && rho <= r_at) return Vec2(t, rho);
  const Vec2 p(t, rho);
  const Vec2 corner[4] = {Vec2(0.0, 0.0), Vec2(L, 0.0), Vec2(L, rb), Vec2(0.0, ra)};
  Vec2 best = corner[0];
  double best_d2 = (p - best).squaredNorm();
  for (int e = 0; e < 4; ++e) {
    const Vec2 s = corner[e], d = corner[(e + 1) % 4] - s;
    const double dd = d.squaredNorm();
    const double lambda = dd > 0.0 ? std::min(std::max((p - s).dot(d) / dd, 0.0), 1.0) : 0.0;
    const Vec2 q = s + lambda * d;
    const double d2 = (p - q).squaredNorm();
    if (d2 < best_d2) {
      best_d2 = d2;
      best = q;
    }
  }
  return best;
}

Vec3 closest_on_frustum(const Vec3& p, const Frustum& f, const Axis& ax) {
  const Vec3 r = p - f.a;
  const double t = r.dot(ax.u);
  const Vec3 radial = r - t * ax.u;
  const double rho = radial.norm();
  const Vec2 q = closest_in_section(t, rho, ax.length, f.radius_a, f.radius_b);
  const Vec3 e = rho > 0.0 ? Vec3(radial / rho) : ax.v;
  return f.a + q.x() * ax.u + q.y() * e;
}

// max over the frustum of n·x: the larger of its two end discs' supports.
double frustum_support(const Vec3& n, const Frustum& f, const Axis& ax) {
  const double nu = n.dot(ax.u);
  const double across = std::sqrt(std::max(0.0, n.squaredNorm() - nu * nu));
  return std::max(n.dot(f.a) + f.radius_a * across, n.dot(f.b) + f.radius_b * across);
}

double box_min(const Vec3& n, const Vec3& lower, const Vec3& upper) {
  double s = 0.0;
  for (int k = 0; k < 3; ++k) s += n[k] >= 0.0 ? n[k] * lower[k] : n[k] * upper[k];
  return s;
}

bool sat_box_obb(const Vec3& lower, const Vec3& upper, const Frustum& f, const Axis& ax) {
  const Vec3 box_centre = 0.5 * (lower + upper), box_half = 0.5 * (upper - lower);
  const Vec3 obb_axis[3] = {ax.u, ax.v, ax.w};
  const double r = std::max(f.radius_a, f.radius_b);
  const double obb_half[3] = {0.5 * ax.length, r, r};
  const Vec3 T = 0.5 * (f.a + f.b) - box_centre;
  // Separated along L when the centres' distance exceeds the sum of the projected half-widths.
  auto separated = [&](const Vec3& L) {
    double rb = 0.0;
    for (int m = 0; m < 3; ++m) rb += obb_half[m] * std::abs(L.dot(obb_axis[m]));
    const double ra = box_half.dot(L.cwiseAbs());
    return std::abs(T.dot(L)) > ra + rb;
  };
  for (int k = 0; k < 3; ++k)
    if (separated(Vec3::Unit(k))) return false;
  for (int m = 0; m < 3; ++m)
    if (separated(obb_axis[m])) return false;
  for (int k = 0; k < 3; ++k) {
    for (int m = 0; m < 3; ++m) {
      const Vec3 L = Vec3::Unit(k).cross(obb_axis[m]);
      if (L.squaredNorm() < 1e-20) continue;  // parallel edges: covered by the face axes
      if (separated(L)) return false;
    }
  }
  return true;
}

bool box_frustum_exact(const Vec3& lower, const Vec3& upper, const Frustum& f, const Axis& ax, double tolerance) {
  // Alternating projections between the box and the frustum: the gap |p − q| shrinks towards
  // their distance. Each step tries p − q as a separating axis, which becomes exact at the
  // closest pair, so "apart" is proven by a certificate and "touching" means within tolerance.
  Vec3 q = closest_on_frustum(0.5 * (lower + upper), f, ax);
  for (int iteration = 0; iteration < 64; ++iteration) {
    const Vec3 p = q.cwiseMax(lower).cwiseMin(upper);
    if ((p - q).norm() <= tolerance) return true;
    q = closest_on_frustum(p, f, ax);
    const Vec3 n = p - q;
    if (n.norm() <= tolerance) return true;
    if (box_min(n, lower, upper) > frustum_support(n, f, ax)) return false;
  }
  return true;  // still undecided after 64 steps: the two nearly touch; keep the voxel
}

void check_frustum(const Frustum& f) {
  if (!f.a.allFinite() || !f.b.allFinite() || !std::isfinite(f.radius_a) || !std::isfinite(f.radius_b) ||
      f.radius_a < 0.0 || f.radius_b < 0.0) {
    std::ostringstream m;
    m << "density: frustum from (" << f.a.transpose() << ") to (" << f.b.transpose() << ") with radii "
      << f.radius_a << ", " << f.radius_b << " cm is not finite with radii >= 0";
    throw std::invalid_argument(m.str());
  }
}

}  // namespace

bool box_intersects_obb(const Vec3& lower, const Vec3& upper, const Frustum& f) {
  return sat_box_obb(lower, upper, f, frustum_axis(f));
}

bool box_intersects_frustum(const Vec3& lower, const Vec3& upper, const Frustum& f, double tolerance) {
  const Axis ax = frustum_axis(f);
  if (!sat_box_obb(lower, upper, f, ax)) return false;
  return box_frustum_exact(lower, upper, f, ax, tolerance);
}

double distance_to_frustum(const Vec3& p, const Frustum& f) {
  return (p - closest_on_frustum(p, f, frustum_axis(f))).norm();
}

std::vector<Vec3i> frustum_cells(const GridGeometry& grid, const Frustum& f, OccupancyShape shape, int k_begin,
                                 int k_end) {
  check_frustum(f);
  std::vector<Vec3i> cells;
  const Axis ax = frustum_axis(f);
  if (!(ax.length > 0.0) || grid.cell_count() == 0) return cells;
  if (k_end < 0 || k_end > grid.dims.z()) k_end = grid.dims.z();
  k_begin = std::max(k_begin, 0);

  // Bounding box: of the OBB (the paper) or of the two end discs (tighter, same cells decided).
  Vec3 lo, hi;
  if (shape == OccupancyShape::obb) {
    const double r = std::max(f.radius_a, f.radius_b);
    const Vec3 half = 0.5 * ax.length * ax.u.cwiseAbs() + r * (ax.v.cwiseAbs() + ax.w.cwiseAbs());
    lo = 0.5 * (f.a + f.b) - half;
    hi = 0.5 * (f.a + f.b) + half;
  } else {
    const Vec3 spread = (Vec3::Ones() - ax.u.cwiseProduct(ax.u)).cwiseMax(0.0).cwiseSqrt();
    lo = (f.a - f.radius_a * spread).cwiseMin(f.b - f.radius_b * spread);
    hi = (f.a + f.radius_a * spread).cwiseMax(f.b + f.radius_b * spread);
  }
  Vec3i first, last;
  for (int k = 0; k < 3; ++k) {
    const double top = k == 2 ? k_end - 1 : grid.dims[k] - 1;
    const double bottom = k == 2 ? k_begin : 0;
    first[k] = int(std::max(std::floor((lo[k] - grid.origin[k]) / grid.voxel), bottom));
    last[k] = int(std::min(std::floor((hi[k] - grid.origin[k]) / grid.voxel), top));
  }
  const double h = grid.voxel;
  const double tolerance = 1e-6 * h;
  const double half_diagonal = 0.5 * std::sqrt(3.0) * h;
  for (int k = first.z(); k <= last.z(); ++k) {
    for (int j = first.y(); j <= last.y(); ++j) {
      for (int i = first.x(); i <= last.x(); ++i) {
        const Vec3 lower = grid.cell_lower(i, j, k), upper = lower + Vec3::Constant(h);
        bool hit;
        if (shape == OccupancyShape::obb) {
          hit = sat_box_obb(lower, upper, f, ax);
        } else {
          // The centre's distance decides most cells: within h/2 the closest point lies in the
          // voxel's inscribed ball; beyond the half-diagonal the voxel lies in a ball missing it.
          const Vec3 centre = lower + Vec3::Constant(0.5 * h);
          const double dc = (centre - closest_on_frustum(centre, f, ax)).norm();
          if (dc <= 0.5 * h) {
            hit = true;
          } else if (dc > half_diagonal + tolerance) {
            hit = false;
          } else {
            hit = sat_box_obb(lower, upper, f, ax) && box_frustum_exact(lower, upper, f, ax, tolerance);
          }
        }
        if (hit) cells.emplace_back(i, j, k);
      }
    }
  }
  return cells;
}

std::vector<int64_t> tube_cells(const GridGeometry& grid, const Tube& tube, OccupancyShape shape) {
  if (tube.points.size() != tube.radii.size()) {
    std::ostringstream m;
    m << "density: a tube has " << tube.points.size() << " points but " << tube.radii.size()
      << " radii; give one radius per point";
    throw std::invalid_argument(m.str());
  }
  std::vector<int64_t> out;
  for (size_t s = 0; s + 1 < tube.points.size(); ++s) {
    const Frustum f{tube.points[s], tube.points[s + 1], tube.radii[s], tube.radii[s + 1]};
    for (const Vec3i& c : frustum_cells(grid, f, shape)) out.push_back(grid.index(c.x(), c.y(), c.z()));
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

double occupied_share(const DensityGrid& occupancy, const Tube& tube, OccupancyShape shape) {
  const std::vector<int64_t> cells = tube_cells(occupancy.geometry(), tube, shape);
  if (cells.empty()) return 0.0;
  int64_t occupied = 0;
  for (int64_t c : cells) occupied += occupancy.values()[c] >= 0.5 ? 1 : 0;
  return double(occupied) / double(cells.size());
}

bool segment_hits_occupied(const DensityGrid& occupancy, const Vec3& a, const Vec3& b) {
  for (const CellCrossing& c : traverse_segment(occupancy.geometry(), a, b))
    if (occupancy.cell(c.cell.x(), c.cell.y(), c.cell.z()) >= 0.5) return true;
  return false;
}

}  // namespace hairfit
