#include "scalp/chart.h"

#include <Eigen/SparseCore>
#include <Eigen/SparseLU>
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/error.h"
#include "scalp/require_disk.h"

namespace hairfit {

namespace {

double cross2(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }

// tan(θ/2) of the angle between e1 and e2, as |e1×e2| / (|e1||e2| + e1·e2): exact for all
// angles in (0, π), no acos/tan round trip.
double tan_half_angle(const Vec3& e1, const Vec3& e2) {
  const double s = e1.cross(e2).norm();
  const double c = e1.norm() * e2.norm() + e1.dot(e2);
  return s / c;
}

std::string describe_vertex(const Mesh& mesh, int v) {
  char text[96];
  const Vec3& p = mesh.positions[v];
  std::snprintf(text, sizeof text, "%d (%.6g, %.6g, %.6g)", v + 1, p.x(), p.y(), p.z());
  return text;
}

// The boundary loop turned to run counter-clockwise about up and to start at the front vertex.
std::vector<int> oriented_boundary(const Mesh& mesh, std::vector<int> loop, int outward, const Vec3& front) {
  if (outward < 0) std::reverse(loop.begin(), loop.end());
  std::size_t start = 0;
  for (std::size_t k = 1; k < loop.size(); ++k) {
    const double a = mesh.positions[loop[k]].dot(front), b = mesh.positions[loop[start]].dot(front);
    if (a > b || (a == b && loop[k] < loop[start])) start = k;
  }
  std::rotate(loop.begin(), loop.begin() + static_cast<std::ptrdiff_t>(start), loop.end());
  return loop;
}

ChartGrid make_grid(const Mesh& mesh, const std::vector<Vec2>& chart) {
  ChartGrid grid;
  const int faces = static_cast<int>(mesh.triangles.size());
  grid.cells = std::clamp(static_cast<int>(std::ceil(std::sqrt(faces / 2.0))), 1, 2048);
  const int n = grid.cells;
  auto cell_of = [n](double x) { return std::clamp(static_cast<int>((x + 1.0) * 0.5 * n), 0, n - 1); };
  auto for_cells = [&](int t, auto&& visit) {
    const Vec3i& f = mesh.triangles[t];
    const Vec2 lo = chart[f[0]].cwiseMin(chart[f[1]]).cwiseMin(chart[f[2]]);
    const Vec2 hi = chart[f[0]].cwiseMax(chart[f[1]]).cwiseMax(chart[f[2]]);
    for (int y = cell_of(lo.y()); y <= cell_of(hi.y()); ++y)
      for (int x = cell_of(lo.x()); x <= cell_of(hi.x()); ++x) visit(y * n + x);
  };
  grid.cell_start.assign(static_cast<std::size_t>(n) * n + 1, 0);
  for (int t = 0; t < faces; ++t) for_cells(t, [&](int c) { ++grid.cell_start[c + 1]; });
  for (std::size_t c = 1; c < grid.cell_start.size(); ++c) grid.cell_start[c] += grid.cell_start[c - 1];
  grid.cell_triangles.resize(grid.cell_start.back());
  std::vector<int> fill(grid.cell_start.begin(), grid.cell_start.end() - 1);
  for (int t = 0; t < faces; ++t) for_cells(t, [&](int c) { grid.cell_triangles[fill[c]++] = t; });
  return grid;
}

Vec3 barycentric_2d(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& p) {
  const double d = cross2(b - a, c - a);
  const double lb = cross2(p - a, c - a) / d;
  const double lc = cross2(b - a, p - a) / d;
  return Vec3(1.0 - lb - lc, lb, lc);
}

}  // namespace

int check_scalp_for_chart(const Mesh& scalp, const Vec3& front, const Vec3& down, const std::string& file) {
  const MeshTopology topo = analyse_topology(scalp);
  // Boundary loops are traced along the triangles' turning, so an inconsistently oriented scalp
  // shows spurious holes: name the orientation first.
  if (topo.nonmanifold_vertices.empty() && !topo.orientation_consistent)
    throw InputError(file, "the scalp's triangles are not consistently oriented (some neighbours turn the other "
                           "way); re-orient the faces so all normals point the same way");
  require_disk(scalp, topo, file);
  if (front.norm() == 0.0 || down.norm() == 0.0 || front.cross(down).norm() < 1e-6 * front.norm() * down.norm())
    throw InputError(file, "units.front and units.down must be non-zero and not parallel");
  // The vector area ½∮p×dp of the hairline (Stokes) tells which way the triangles turn as seen
  // from above, independent of the mesh's interior.
  Vec3 vector_area = Vec3::Zero();
  double area = 0.0;
  for (int t = 0; t < static_cast<int>(scalp.triangles.size()); ++t) {
    const Vec3i& f = scalp.triangles[t];
    vector_area += 0.5 * (scalp.positions[f[1]] - scalp.positions[f[0]]).cross(scalp.positions[f[2]] - scalp.positions[f[0]]);
    area += triangle_area(scalp, t);
  }
  const double facing = -vector_area.dot(down.normalized());
  if (!(std::abs(facing) > 1e-3 * area))
    throw InputError(file, "the scalp's hairline is edge-on when seen from above (along units.down), so the chart "
                           "cannot tell left from right; check units.down");
  return facing > 0 ? 1 : -1;
}

ScalpChart make_scalp_chart(const Mesh& scalp, const Vec3& front_in, const Vec3& down_in,
                            const std::string& file) {
  const int outward = check_scalp_for_chart(scalp, front_in, down_in, file);
  const MeshTopology topo = analyse_topology(scalp);
  ScalpChart ch;
  ch.mesh = scalp;
  ch.front = front_in.normalized();
  ch.down = down_in.normalized();
  const Vec3 up = -ch.down;
  const Mesh& mesh = ch.mesh;
  const int nv = static_cast<int>(mesh.positions.size());
  const int nf = static_cast<int>(mesh.triangles.size());
  for (int t = 0; t < nf; ++t) ch.area += triangle_area(mesh, t);
  ch.outward = outward;
  ch.boundary = oriented_boundary(mesh, topo.boundary_loops.front(), ch.outward, ch.front);

  // Boundary: chord length on the unit circle, counter-clockwise from the front vertex at +90°.
  ch.chart.assign(nv, Vec2::Zero());
  const int nb = static_cast<int>(ch.boundary.size());
  std::vector<double> cumulative(nb + 1, 0.0);
  for (int k = 0; k < nb; ++k) {
    const double chord = (mesh.positions[ch.boundary[(k + 1) % nb]] - mesh.positions[ch.boundary[k]]).norm();
    if (chord == 0.0)
      throw InputError(file, "the scalp has coincident hairline vertices " + describe_vertex(mesh, ch.boundary[k]) +
                                 " and " + describe_vertex(mesh, ch.boundary[(k + 1) % nb]) + "; weld them");
    cumulative[k + 1] = cumulative[k] + chord;
  }
  std::vector<int> unknown(nv, -1);  // interior vertex → row; boundary −2
  for (int v : ch.boundary) unknown[v] = -2;
  for (int k = 0; k < nb; ++k) {
    const double angle = M_PI / 2 + 2 * M_PI * cumulative[k] / cumulative[nb];
    ch.chart[ch.boundary[k]] = Vec2(std::cos(angle), std::sin(angle));
  }
  std::vector<char> used(nv, 0);
  for (const Vec3i& f : mesh.triangles) used[f[0]] = used[f[1]] = used[f[2]] = 1;
  int interior = 0;
  for (int v = 0; v < nv; ++v)
    if (used[v] && unknown[v] == -1) unknown[v] = interior++;

  // Interior: mean-value weights (Floater 2003). For corner i of a triangle with neighbours j, k
  // and angle θ at i: w_ij += tan(θ/2)/|x_j−x_i|, w_ik += tan(θ/2)/|x_k−x_i|. Row i of the system
  // is Σ_j w_ij (u_i − u_j) = 0; weights are positive, the matrix is a non-symmetric M-matrix.
  std::vector<Eigen::Triplet<double>> triplets;
  triplets.reserve(static_cast<std::size_t>(nf) * 9);
  Eigen::MatrixX2d rhs = Eigen::MatrixX2d::Zero(interior, 2);
  auto couple = [&](int i, int j, double w) {
    if (unknown[i] < 0) return;
    const int row = unknown[i];
    triplets.emplace_back(row, row, w);
    if (unknown[j] >= 0)
      triplets.emplace_back(row, unknown[j], -w);
    else
      rhs.row(row) += w * ch.chart[j].transpose();
  };
  for (int t = 0; t < nf; ++t) {
    const Vec3i& f = mesh.triangles[t];
    for (int c = 0; c < 3; ++c) {
      const int i = f[c], j = f[(c + 1) % 3], k = f[(c + 2) % 3];
      const Vec3 eij = mesh.positions[j] - mesh.positions[i], eik = mesh.positions[k] - mesh.positions[i];
      const double lij = eij.norm(), lik = eik.norm();
      if (lij == 0.0 || lik == 0.0)
        throw InputError(file, "the scalp has coincident vertices in triangle " + std::to_string(t + 1) +
                                   " at " + describe_vertex(mesh, i) + "; weld them");
      const double th = tan_half_angle(eij, eik);
      if (!std::isfinite(th) || th <= 0.0)
        throw InputError(file, "the scalp has a zero-area triangle " + std::to_string(t + 1) + " at " +
                                   describe_vertex(mesh, i) + "; remove it");
      couple(i, j, th / lij);
      couple(i, k, th / lik);
    }
  }
  if (interior > 0) {
    Eigen::SparseMatrix<double> a(interior, interior);
    a.setFromTriplets(triplets.begin(), triplets.end());
    a.makeCompressed();
    // SparseLU: the mean-value matrix is not symmetric (no Cholesky/CG); a direct factorisation
    // solves both coordinates with one factorisation, is deterministic and needs no tolerance.
    Eigen::SparseLU<Eigen::SparseMatrix<double>, Eigen::COLAMDOrdering<int>> lu;
    lu.analyzePattern(a);
    lu.factorize(a);
    if (lu.info() != Eigen::Success)
      throw std::runtime_error("scalp chart: sparse LU factorisation failed: " + lu.lastErrorMessage());
    const Eigen::MatrixX2d uv = lu.solve(rhs);
    for (int v = 0; v < nv; ++v)
      if (unknown[v] >= 0) ch.chart[v] = uv.row(unknown[v]).transpose();
  }
  ch.solver = "SparseLU (COLAMD)";

  for (int t = 0; t < nf; ++t)
    if (!(ch.outward * chart_triangle_area(ch, t) > 0.0)) ++ch.flipped_triangles;

  // Angle-weighted vertex normals, turned outward.
  ch.vertex_normals.assign(nv, Vec3::Zero());
  for (int t = 0; t < nf; ++t) {
    const Vec3i& f = mesh.triangles[t];
    const Vec3 n = ch.outward * triangle_normal(mesh, t);
    for (int c = 0; c < 3; ++c) {
      const Vec3 e1 = mesh.positions[f[(c + 1) % 3]] - mesh.positions[f[c]];
      const Vec3 e2 = mesh.positions[f[(c + 2) % 3]] - mesh.positions[f[c]];
      ch.vertex_normals[f[c]] += std::atan2(e1.cross(e2).norm(), e1.dot(e2)) * n;
    }
  }
  for (Vec3& n : ch.vertex_normals)
    if (n.norm() > 0) n.normalize();

  ch.height_low = INFINITY;
  ch.height_high = -INFINITY;
  for (int v = 0; v < nv; ++v)
    if (used[v]) {
      ch.height_low = std::min(ch.height_low, mesh.positions[v].dot(up));
      ch.height_high = std::max(ch.height_high, mesh.positions[v].dot(up));
    }
  std::vector<int> loop_position(nv, -1);
  for (int k = 0; k < nb; ++k) loop_position[ch.boundary[k]] = k;
  ch.boundary_triangles.assign(nb, -1);
  for (int t = 0; t < nf; ++t)
    for (int c = 0; c < 3; ++c) {
      const int a = loop_position[mesh.triangles[t][c]], b = loop_position[mesh.triangles[t][(c + 1) % 3]];
      if (a < 0 || b < 0) continue;
      if ((a + 1) % nb == b) ch.boundary_triangles[a] = t;
      if ((b + 1) % nb == a) ch.boundary_triangles[b] = t;
    }
  ch.grid = make_grid(mesh, ch.chart);
  return ch;
}

double chart_triangle_area(const ScalpChart& ch, int t) {
  const Vec3i& f = ch.mesh.triangles[t];
  return 0.5 * cross2(ch.chart[f[1]] - ch.chart[f[0]], ch.chart[f[2]] - ch.chart[f[0]]);
}

SurfacePoint locate_in_chart(const ScalpChart& ch, const Vec2& p) {
  const Mesh& mesh = ch.mesh;
  const int n = ch.grid.cells;
  auto cell_of = [n](double x) { return std::clamp(static_cast<int>((x + 1.0) * 0.5 * n), 0, n - 1); };
  const int cell = cell_of(p.y()) * n + cell_of(p.x());
  SurfacePoint best;
  double best_min = -INFINITY;
  for (int k = ch.grid.cell_start[cell]; k < ch.grid.cell_start[cell + 1]; ++k) {
    const int t = ch.grid.cell_triangles[k];
    const Vec3i& f = mesh.triangles[t];
    const Vec3 b = barycentric_2d(ch.chart[f[0]], ch.chart[f[1]], ch.chart[f[2]], p);
    if (b.minCoeff() > best_min) {
      best_min = b.minCoeff();
      best.triangle = t;
      best.barycentric = b;
    }
  }
  if (best.triangle >= 0 && best_min > -1e-9) {
    best.barycentric = best.barycentric.cwiseMax(0.0);
    best.barycentric /= best.barycentric.sum();
    return best;
  }
  // Outside the chart polygon: the nearest point of the hairline polygon, on its one triangle.
  const int nb = static_cast<int>(ch.boundary.size());
  double best_d = INFINITY;
  int best_k = 0;
  double best_s = 0;
  for (int k = 0; k < nb; ++k) {
    const Vec2 a = ch.chart[ch.boundary[k]], b = ch.chart[ch.boundary[(k + 1) % nb]];
    const double s = std::clamp((p - a).dot(b - a) / (b - a).squaredNorm(), 0.0, 1.0);
    const double d = (a + s * (b - a) - p).squaredNorm();
    if (d < best_d) best_d = d, best_k = k, best_s = s;
  }
  const int va = ch.boundary[best_k], vb = ch.boundary[(best_k + 1) % nb];
  SurfacePoint sp;
  sp.triangle = ch.boundary_triangles[best_k];
  const Vec3i& f = mesh.triangles[sp.triangle];
  for (int c = 0; c < 3; ++c) {
    if (f[c] == va) sp.barycentric[c] = 1.0 - best_s;
    if (f[c] == vb) sp.barycentric[c] = best_s;
  }
  return sp;
}

Vec3 surface_position(const ScalpChart& ch, const SurfacePoint& sp) {
  const Vec3i& f = ch.mesh.triangles[sp.triangle];
  return sp.barycentric[0] * ch.mesh.positions[f[0]] + sp.barycentric[1] * ch.mesh.positions[f[1]] +
         sp.barycentric[2] * ch.mesh.positions[f[2]];
}

Vec3 surface_normal(const ScalpChart& ch, const SurfacePoint& sp) {
  const Vec3i& f = ch.mesh.triangles[sp.triangle];
  const Vec3 n = sp.barycentric[0] * ch.vertex_normals[f[0]] + sp.barycentric[1] * ch.vertex_normals[f[1]] +
                 sp.barycentric[2] * ch.vertex_normals[f[2]];
  // Opposite vertex normals can cancel on a sharp crease; the face normal is then the answer.
  if (n.norm() > 1e-12) return n.normalized();
  return ch.outward * triangle_normal(ch.mesh, sp.triangle);
}

Vec2 chart_position(const ScalpChart& ch, const SurfacePoint& sp) {
  const Vec3i& f = ch.mesh.triangles[sp.triangle];
  return sp.barycentric[0] * ch.chart[f[0]] + sp.barycentric[1] * ch.chart[f[1]] + sp.barycentric[2] * ch.chart[f[2]];
}

double height_of(const ScalpChart& ch, const Vec3& position) {
  const double span = ch.height_high - ch.height_low;
  if (!(span > 0)) return 1.0;
  return std::clamp((position.dot(-ch.down) - ch.height_low) / span, 0.0, 1.0);
}

Digest digest(const ScalpChart& ch) {
  Digest d;
  d.add(std::string_view("ScalpChart/1"));
  d.add(ch.mesh.positions);
  d.add(static_cast<std::int64_t>(ch.mesh.triangles.size()));
  for (const Vec3i& f : ch.mesh.triangles) d.add_bytes(f.data(), 3 * sizeof(int));
  d.add(static_cast<std::int64_t>(ch.chart.size()));
  for (const Vec2& c : ch.chart) d.add_bytes(c.data(), 2 * sizeof(double));
  d.add(static_cast<std::int64_t>(ch.boundary.size()));
  d.add_bytes(ch.boundary.data(), ch.boundary.size() * sizeof(int));
  d.add(static_cast<std::int64_t>(ch.outward));
  d.add(ch.front).add(ch.down);
  return d;
}

}  // namespace hairfit
