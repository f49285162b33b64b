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
  const double nv = n.dot(ax.v), nw = n.dot(ax.w);
  const double across = std::sqrt(nv * nv + nw * nw);
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

// The frustum's point farthest along d: on the rim of the end disc that reaches farther.
Vec3 frustum_support_point(const Vec3& d, const Frustum& f, const Axis& ax) {
  // The part of d across the axis, from its (v, w) components: d − (d·u)u would leave a
  // round-off vector off the disc plane when d is nearly parallel to u.
  const double dv = d.dot(ax.v), dw = d.dot(ax.w), n = std::sqrt(dv * dv + dw * dw);
  const Vec3 rim = n > 0.0 ? Vec3((dv / n) * ax.v + (dw / n) * ax.w) : Vec3::Zero();
  const Vec3 pa = f.a + f.radius_a * rim, pb = f.b + f.radius_b * rim;
  return pa.dot(d) >= pb.dot(d) ? pa : pb;
}

// Boolean GJK (Gilbert–Johnson–Keerthi) on the Minkowski difference box − frustum: the sets meet
// iff it contains the origin. Returns 1 (a simplex encloses the origin, or the origin lies on a
// simplex feature: touching), 0 (a support plane separates: exact) or −1 (undecided: the origin
// is within round-off of the difference's curved boundary).
int gjk_box_frustum(const Vec3& lower, const Vec3& upper, const Frustum& f, const Axis& ax) {
  auto support = [&](const Vec3& d) {
    const Vec3 box(d.x() >= 0.0 ? upper.x() : lower.x(), d.y() >= 0.0 ? upper.y() : lower.y(),
                   d.z() >= 0.0 ? upper.z() : lower.z());
    return Vec3(box - frustum_support_point(-d, f, ax));
  };
  const double scale = (upper - lower).norm() + (f.b - f.a).norm() + f.radius_a + f.radius_b;
  const double tiny = 1e-24 * scale * scale * scale * scale;  // |d|² of a degenerate direction (cm⁴)
  Vec3 s[4];  // the simplex, newest last
  int n = 0;
  Vec3 d = 0.5 * (lower + upper) - 0.5 * (f.a + f.b);
  if (d.squaredNorm() == 0.0) d = Vec3::UnitX();
  s[n++] = support(d);
  d = -s[0];
  // The line case of the simplex [b, a] (a newest). By value: the arguments may alias s[].
  auto line = [&](const Vec3 b, const Vec3 a) {
    const Vec3 ab = b - a, ao = -a;
    if (ab.dot(ao) > 0.0) {
      s[0] = b, s[1] = a, n = 2;
      d = ab.cross(ao).cross(ab);
    } else {
      s[0] = a, n = 1;
      d = ao;
    }
  };
  // The triangle case [c, b, a]; returns true when the origin lies in its plane inside it.
  auto triangle = [&](const Vec3 c, const Vec3 b, const Vec3 a) {
    const Vec3 ab = b - a, ac = c - a, ao = -a, abc = ab.cross(ac);
    if (abc.cross(ac).dot(ao) > 0.0) {
      if (ac.dot(ao) > 0.0) {
        s[0] = c, s[1] = a, n = 2;
        d = ac.cross(ao).cross(ac);
      } else {
        line(b, a);
      }
    } else if (ab.cross(abc).dot(ao) > 0.0) {
      line(b, a);
    } else {
      const double side = abc.dot(ao);
      if (side == 0.0) return true;
      s[0] = side > 0.0 ? c : b, s[1] = side > 0.0 ? b : c, s[2] = a, n = 3;
      d = side > 0.0 ? abc : Vec3(-abc);
    }
    return false;
  };
  for (int iteration = 0; iteration < 48; ++iteration) {
    if (d.squaredNorm() <= tiny) return 1;  // the origin lies on the simplex
    const Vec3 a = support(d);
    if (a.dot(d) < 0.0) return 0;  // d separates the box from the frustum
    // No progress along d: the origin is (nearly) on the boundary; let the fallback decide.
    double reached = s[0].dot(d);
    for (int i = 1; i < n; ++i) reached = std::max(reached, s[i].dot(d));
    if (a.dot(d) - reached <= 1e-12 * scale * d.norm()) return -1;
    s[n++] = a;
    if (n == 2) {
      line(s[0], s[1]);
    } else if (n == 3) {
      if (triangle(s[0], s[1], s[2])) return 1;
    } else {
      // Tetrahedron [d0, c, b, a]: the origin is outside a face through a (facing away from the
      // fourth vertex) or inside all three, hence enclosed.
      const Vec3 pd = s[0], pc = s[1], pb = s[2], pa = s[3], ao = -pa;
      const Vec3 faces[3][3] = {{pc, pb, pd}, {pd, pc, pb}, {pb, pd, pc}};  // {x, y, opposite}
      bool outside = false;
      for (const auto& face : faces) {
        Vec3 normal = (face[0] - pa).cross(face[1] - pa);
        if (normal.dot(face[2] - pa) > 0.0) normal = -normal;
        if (normal.dot(ao) > 0.0) {
          if (triangle(face[0], face[1], pa)) return 1;
          outside = true;
          break;
        }
      }
      if (!outside) return 1;
    }
  }
  return -1;
}

// Alternating projections between the box and the frustum: the gap |p − q| shrinks towards
// their distance; each step tries p − q as a separating axis, exact at the closest pair. Only
// for what GJK leaves undecided (near-tangent contact), so slow convergence does not matter.
bool box_frustum_projections(const Vec3& lower, const Vec3& upper, const Frustum& f, const Axis& ax, double tolerance) {
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

bool box_frustum_exact(const Vec3& lower, const Vec3& upper, const Frustum& f, const Axis& ax, double tolerance) {
  const int gjk = gjk_box_frustum(lower, upper, f, ax);
  if (gjk >= 0) return gjk == 1;
  return box_frustum_projections(lower, upper, f, ax, tolerance);
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

namespace {

// frustum_cells and frustum_cells_unsettled: the cells not `settled`, or all for a null one.
std::vector<Vec3i> cells_of_frustum(const GridGeometry& grid, const Frustum& f, OccupancyShape shape,
                                    const std::vector<double>* settled, int k_begin, int k_end) {
  check_frustum(f);
  std::vector<Vec3i> cells;
  const Axis ax = frustum_axis(f);
  if (!(ax.length > 0.0) || grid.count() == 0) return cells;
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
        if (settled && (*settled)[grid.index(i, j, k)] != 0.0) continue;
        const Vec3 lower = grid.node(i, j, k), upper = lower + Vec3::Constant(h);
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

}  // namespace

std::vector<Vec3i> frustum_cells(const GridGeometry& grid, const Frustum& f, OccupancyShape shape, int k_begin,
                                 int k_end) {
  return cells_of_frustum(grid, f, shape, nullptr, k_begin, k_end);
}

std::vector<Vec3i> frustum_cells_unsettled(const GridGeometry& grid, const Frustum& f, OccupancyShape shape,
                                           const std::vector<double>& settled, int k_begin, int k_end) {
  if (settled.size() != static_cast<std::size_t>(grid.count()))
    throw std::invalid_argument("frustum_cells_unsettled: the settled cells are not the grid's");
  return cells_of_frustum(grid, f, shape, &settled, k_begin, k_end);
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
