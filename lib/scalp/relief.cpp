#include "scalp/relief.h"

#include <algorithm>
#include <cmath>
#include <map>

#include <Eigen/Eigenvalues>

#include "core/parallel.h"
#include "core/point_grid.h"

namespace hairfit {

namespace {

struct GrainEdge {
  Vec3 midpoint, direction;  // unit direction
  double weight;             // β·|e|
};

std::vector<GrainEdge> grain_edges(const Mesh& hull) {
  // Each undirected edge's triangles, in a fixed order (map by key).
  std::map<long long, std::vector<int>> faces;
  for (int t = 0; t < static_cast<int>(hull.triangles.size()); ++t)
    for (int k = 0; k < 3; ++k) faces[edge_key(hull.triangles[t][k], hull.triangles[t][(k + 1) % 3])].push_back(t);
  std::vector<GrainEdge> edges;
  for (const auto& [key, on] : faces) {
    const int a = static_cast<int>(key >> 32), b = static_cast<int>(key & 0xffffffff);
    const Vec3 e = hull.positions[b] - hull.positions[a];
    const double length = e.norm();
    if (!(length > 0.0)) continue;
    double beta = 0.0;
    if (on.size() == 1) {
      beta = 0.5 * M_PI;
    } else if (on.size() == 2) {
      const Vec3 n0 = triangle_normal(hull, on[0]), n1 = triangle_normal(hull, on[1]);
      beta = std::atan2(n0.cross(n1).norm(), std::fabs(n0.dot(n1)));  // unsigned, either orientation
    } else {
      continue;  // non-manifold: no dihedral angle
    }
    if (beta > 0.0) edges.push_back({0.5 * (hull.positions[a] + hull.positions[b]), e / length, beta * length});
  }
  return edges;
}

// The covariance of the hull's face normals about their mean, in the tangent plane (x, y), over
// the faces within `radius` of q (area-weighted, smooth falloff); its trace-normalised anisotropy
// and minor eigenvector: grooves tilt the normals only across themselves.
struct NormalSpread {
  double anisotropy = 0.0;
  Eigen::Vector2d along = Eigen::Vector2d::Zero();
};

NormalSpread normal_spread(const PointGrid& grid, const std::vector<Vec3>& normals, const std::vector<double>& areas,
                           const Vec3& q, const Vec3& x, const Vec3& y, double radius) {
  double total = 0.0;
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  Eigen::Matrix2d second = Eigen::Matrix2d::Zero();
  grid.for_each_within(q, radius, [&](int f, double d2) {
    const double fall = 1.0 - d2 / (radius * radius);
    const double w = areas[f] * fall * fall;
    const Eigen::Vector2d u(normals[f].dot(x), normals[f].dot(y));
    total += w;
    mean += w * u;
    second += w * (u * u.transpose());
  });
  NormalSpread out;
  if (!(total > 0.0)) return out;
  mean /= total;
  const Eigen::Matrix2d c = second / total - mean * mean.transpose();
  const double trace = c.trace();
  if (!(trace > 1e-12)) return out;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eigen(c);
  out.anisotropy = (eigen.eigenvalues()[1] - eigen.eigenvalues()[0]) / trace;
  out.along = eigen.eigenvectors().col(0);
  return out;
}

}  // namespace

std::vector<Vec3> relief_grain_of_normals(const ScalpChart& ch, const Mesh& hull, const std::vector<double>& lift,
                                          double radius, int threads) {
  const int faces = static_cast<int>(hull.triangles.size());
  std::vector<Vec3> centroids(faces), normals(faces);
  std::vector<double> areas(faces);
  for (int f = 0; f < faces; ++f) {
    centroids[f] = triangle_centroid(hull, f);
    normals[f] = triangle_normal(hull, f);
    areas[f] = triangle_area(hull, f);
  }
  const int n = static_cast<int>(ch.mesh.positions.size());
  std::vector<Vec3> grain(n, Vec3::Zero());
  if (faces == 0) return grain;
  const PointGrid grid(centroids, radius);
  static const double kScales[] = {0.5, 1.0, 2.0};
  parallel_for(n, threads, [&](int v) {
    const Vec3& normal = ch.vertex_normals[v];
    const Vec3 q = ch.mesh.positions[v] + std::max(0.0, lift[v]) * normal;
    const Vec3 x = normal.unitOrthogonal(), y = normal.cross(x);
    NormalSpread best;
    for (double scale : kScales) {
      const NormalSpread s = normal_spread(grid, normals, areas, q, x, y, scale * radius);
      if (s.anisotropy > best.anisotropy) best = s;
    }
    if (!(best.anisotropy > 0.0)) return;
    grain[v] = std::min(1.0, best.anisotropy / kSureSpread) * (best.along.x() * x + best.along.y() * y).normalized();
  });
  return grain;
}

std::vector<Vec3> relief_grain(const ScalpChart& ch, const Mesh& hull, double radius, int threads) {
  const std::vector<GrainEdge> edges = grain_edges(hull);
  std::vector<Vec3> midpoints;
  midpoints.reserve(edges.size());
  for (const GrainEdge& e : edges) midpoints.push_back(e.midpoint);
  const int n = static_cast<int>(ch.mesh.positions.size());
  std::vector<Vec3> grain(n, Vec3::Zero());
  if (edges.empty()) return grain;
  const PointGrid grid(midpoints, radius);
  parallel_for(n, threads, [&](int v) {
    const Vec3& p = ch.mesh.positions[v];
    const Vec3& normal = ch.vertex_normals[v];
    const Vec3 x = normal.unitOrthogonal(), y = normal.cross(x);
    Eigen::Matrix2d tensor = Eigen::Matrix2d::Zero();
    grid.for_each_within(p, radius, [&](int i, double d2) {
      // A smooth falloff so the grain changes continuously as the edges come into reach.
      const double fall = 1.0 - d2 / (radius * radius);
      const Eigen::Vector2d u(edges[i].direction.dot(x), edges[i].direction.dot(y));
      tensor += edges[i].weight * fall * fall * (u * u.transpose());
    });
    const double trace = tensor.trace();
    if (!(trace > 1e-12)) return;
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eigen(tensor);
    const double anisotropy = (eigen.eigenvalues()[1] - eigen.eigenvalues()[0]) / trace;
    const Eigen::Vector2d e = eigen.eigenvectors().col(1);
    grain[v] = std::min(1.0, anisotropy / kSureAnisotropy) * (e.x() * x + e.y() * y).normalized();
  });
  return grain;
}

}  // namespace hairfit
