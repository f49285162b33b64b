#include "scalp/direction_field.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>

namespace hairfit {

namespace {

// The vertex's tangent basis: x is the projection of a fixed world axis (the one least aligned
// with the normal), y = n × x.
struct Basis {
  Vec3 x, y;
};

Basis tangent_basis(const Vec3& n) {
  const Vec3 a = std::fabs(n.x()) <= std::fabs(n.y()) && std::fabs(n.x()) <= std::fabs(n.z()) ? Vec3::UnitX()
                 : std::fabs(n.y()) <= std::fabs(n.z())                                       ? Vec3::UnitY()
                                                                                              : Vec3::UnitZ();
  const Vec3 x = (a - a.dot(n) * n).normalized();
  return Basis{x, n.cross(x)};
}

// The minimal rotation taking unit a to unit b, applied to v (Rodrigues); a ≠ −b.
Vec3 rotate_between(const Vec3& a, const Vec3& b, const Vec3& v) {
  const Vec3 axis = a.cross(b);
  const double c = a.dot(b);
  if (c <= -1.0 + 1e-12) return -v;  // antipodal normals: no minimal rotation; never on a sane mesh
  return c * v + axis.cross(v) + axis * (axis.dot(v) / (1.0 + c));
}

// ρ_ij: the angle, in j's basis, of i's x axis carried to j.
double transport_angle(const Vec3& ni, const Basis& bi, const Vec3& nj, const Basis& bj) {
  const Vec3 x = rotate_between(ni, nj, bi.x);
  return std::atan2(x.dot(bj.y), x.dot(bj.x));
}

double wrap(double a) {  // to (−π, π]
  a = std::fmod(a, 2.0 * M_PI);
  if (a <= -M_PI) a += 2.0 * M_PI;
  if (a > M_PI) a -= 2.0 * M_PI;
  return a;
}

double cotangent(const Vec3& a, const Vec3& b) {  // of the angle between a and b
  const double s = a.cross(b).norm();
  return s > 0.0 ? a.dot(b) / s : 0.0;
}

}  // namespace

DirectionField smoothest_aligned_field(const Mesh& mesh, const std::vector<Vec3>& normals,
                                       const std::vector<Vec3>& guidance, const DirectionFieldOptions& o) {
  const int n = static_cast<int>(mesh.positions.size());
  if (static_cast<int>(normals.size()) != n || static_cast<int>(guidance.size()) != n)
    throw std::invalid_argument("direction field: one normal and one guidance vector per vertex");
  if (!(o.smoothing > 0.0) || !std::isfinite(o.smoothing))
    throw std::invalid_argument("direction field: the smoothing length must be > 0");
  std::vector<Basis> basis(n);
  for (int i = 0; i < n; ++i) basis[i] = tangent_basis(normals[i]);

  // Cotangent weights per undirected edge, and lumped areas.
  std::vector<Eigen::Triplet<double>> entries;
  std::vector<double> mass(n, 0.0);
  std::vector<std::pair<long long, double>> edge_weights;
  for (const Vec3i& t : mesh.triangles) {
    const Vec3 p[3] = {mesh.positions[t[0]], mesh.positions[t[1]], mesh.positions[t[2]]};
    const double area = 0.5 * (p[1] - p[0]).cross(p[2] - p[0]).norm();
    for (int k = 0; k < 3; ++k) {
      mass[t[k]] += area / 3.0;
      const int a = t[(k + 1) % 3], b = t[(k + 2) % 3];  // the edge opposite corner k
      edge_weights.push_back({edge_key(a, b), 0.5 * cotangent(p[(k + 1) % 3] - p[k], p[(k + 2) % 3] - p[k])});
    }
  }
  std::stable_sort(edge_weights.begin(), edge_weights.end(),
            [](const auto& x, const auto& y) { return x.first < y.first; });  // stable per key: sums in a fixed order
  // Real form of the Hermitian matrix: entry α + iβ at (i, j) is the block [[α, −β], [β, α]].
  auto add = [&](int i, int j, double re, double im) {
    entries.emplace_back(2 * i, 2 * j, re);
    entries.emplace_back(2 * i, 2 * j + 1, -im);
    entries.emplace_back(2 * i + 1, 2 * j, im);
    entries.emplace_back(2 * i + 1, 2 * j + 1, re);
  };
  for (std::size_t e = 0; e < edge_weights.size();) {
    const long long key = edge_weights[e].first;
    double w = 0.0;
    for (; e < edge_weights.size() && edge_weights[e].first == key; ++e) w += edge_weights[e].second;
    w = std::max(w, 0.0);
    if (w == 0.0) continue;
    const int i = static_cast<int>(key >> 32), j = static_cast<int>(key & 0xffffffff);
    const double rho = transport_angle(normals[i], basis[i], normals[j], basis[j]);
    add(i, i, w, 0.0);
    add(j, j, w, 0.0);
    add(j, i, -w * std::cos(rho), -w * std::sin(rho));  // −w r_ij
    add(i, j, -w * std::cos(rho), w * std::sin(rho));   // −w conj(r_ij)
  }
  const double t = 1.0 / (o.smoothing * o.smoothing);
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(2 * n);
  // A vanishing share of plain mass keeps the system definite where no guidance reaches a part.
  const double floor = 1e-9 * t;
  for (int i = 0; i < n; ++i) {
    const Vec3 g = guidance[i] - guidance[i].dot(normals[i]) * normals[i];
    const double length = g.norm();
    const double confidence = std::isfinite(length) ? std::min(1.0, length) : 0.0;
    const double a = t * mass[i] * confidence + floor * mass[i];
    add(i, i, a, 0.0);
    if (confidence > 0.0) {
      rhs[2 * i] = t * mass[i] * confidence * g.dot(basis[i].x) / length;
      rhs[2 * i + 1] = t * mass[i] * confidence * g.dot(basis[i].y) / length;
    }
  }
  Eigen::SparseMatrix<double> system(2 * n, 2 * n);
  system.setFromTriplets(entries.begin(), entries.end());
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(system);
  if (solver.info() != Eigen::Success) throw std::runtime_error("direction field: the system is not definite");
  const Eigen::VectorXd u = solver.solve(rhs);

  DirectionField field;
  field.directions.assign(n, Vec3::Zero());
  field.magnitude.assign(n, 0.0);
  for (int i = 0; i < n; ++i) {
    const Vec3 v = u[2 * i] * basis[i].x + u[2 * i + 1] * basis[i].y;
    const double m = v.norm();
    field.magnitude[i] = std::isfinite(m) ? m : 0.0;
    if (m > 1e-12 && std::isfinite(m)) field.directions[i] = v / m;
  }
  return field;
}

Vec3 field_direction(const Mesh& mesh, const DirectionField& field, int triangle, const Vec3& b, const Vec3& normal,
                     const Vec3& fallback) {
  const Vec3i& t = mesh.triangles[triangle];
  Vec3 v = b[0] * field.directions[t[0]] + b[1] * field.directions[t[1]] + b[2] * field.directions[t[2]];
  v -= v.dot(normal) * normal;
  const double m = v.norm();
  return m > 1e-9 ? Vec3(v / m) : fallback;
}

std::vector<int> field_indices(const Mesh& mesh, const std::vector<Vec3>& normals, const DirectionField& field) {
  std::vector<int> index(mesh.triangles.size(), 0);
  for (std::size_t f = 0; f < mesh.triangles.size(); ++f) {
    const Vec3i& t = mesh.triangles[f];
    double turning = 0.0, holonomy = 0.0;
    bool defined = true;
    for (int k = 0; k < 3; ++k) {
      const int i = t[k], j = t[(k + 1) % 3];
      if (field.directions[i].isZero(0.0) || field.directions[j].isZero(0.0)) defined = false;
      const Basis bi = tangent_basis(normals[i]), bj = tangent_basis(normals[j]);
      const double rho = transport_angle(normals[i], bi, normals[j], bj);
      const double ai = std::atan2(field.directions[i].dot(bi.y), field.directions[i].dot(bi.x));
      const double aj = std::atan2(field.directions[j].dot(bj.y), field.directions[j].dot(bj.x));
      turning += wrap(aj - ai - rho);
      holonomy += rho;
    }
    if (defined) index[f] = static_cast<int>(std::lround((turning + wrap(holonomy)) / (2.0 * M_PI)));
  }
  return index;
}

}  // namespace hairfit
