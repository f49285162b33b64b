#include "field/mesh_features.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>

#include "core/error.h"
#include "core/vertex_sort.h"

namespace hairfit::field {

namespace {

void check_mesh(const Mesh& mesh, const std::string& name) {
  if (mesh.triangles.empty())
    throw InputError(name, "the mesh has no triangles; a distance field needs a surface");
  const int n = static_cast<int>(mesh.positions.size());
  for (size_t t = 0; t < mesh.triangles.size(); ++t)
    for (int k = 0; k < 3; ++k) {
      const int v = mesh.triangles[t][k];
      if (v < 0 || v >= n)
        throw InputError(name, "triangle " + std::to_string(t) + " refers to vertex " + std::to_string(v) +
                                   ", but the mesh has " + std::to_string(n) + " vertices");
      if (!mesh.positions[v].allFinite())
        throw InputError(name, "vertex " + std::to_string(v) +
                                   " has a non-finite coordinate; fix or remove it before building a field");
    }
}

}  // namespace

MeshFeatures extract_features(const Mesh& mesh, const std::string& name) {
  check_mesh(mesh, name);
  MeshFeatures f;

  // Weld exactly equal positions among the used vertices: sort by coordinates, keep the first of
  // each run. Deterministic (stable sort on the input order).
  std::vector<int> used;
  {
    std::vector<char> is_used(mesh.positions.size(), 0);
    for (const Vec3i& t : mesh.triangles)
      for (int k = 0; k < 3; ++k) is_used[t[k]] = 1;
    for (size_t i = 0; i < is_used.size(); ++i)
      if (is_used[i]) used.push_back(static_cast<int>(i));
  }
  auto less = [&](int a, int b) {
    const Vec3& p = mesh.positions[a];
    const Vec3& q = mesh.positions[b];
    return p.x() != q.x() ? p.x() < q.x() : p.y() != q.y() ? p.y() < q.y() : p.z() < q.z();
  };
  std::stable_sort(used.begin(), used.end(), less);
  std::vector<int> welded(mesh.positions.size(), -1);
  for (size_t i = 0; i < used.size(); ++i) {
    if (i == 0 || less(used[i - 1], used[i])) f.vertices.push_back(mesh.positions[used[i]]);
    welded[used[i]] = static_cast<int>(f.vertices.size()) - 1;
  }
  const int nv = static_cast<int>(f.vertices.size());
  f.vertex_of_input = std::move(welded);

  // Faces: non-degenerate triangles. A triangle whose doubled area is below 1e-8 of its longest
  // edge squared is a sliver narrower than 1e-8 of its length: its points are represented, to
  // that accuracy, by its edges, and its normal would not be accurate enough for exact distances.
  struct EdgeUse {
    int a, b, face;
  };
  std::vector<EdgeUse> uses;
  uses.reserve(mesh.triangles.size() * 3);
  for (const Vec3i& t : mesh.triangles) {
    const Vec3i w(f.vertex_of_input[t[0]], f.vertex_of_input[t[1]], f.vertex_of_input[t[2]]);
    int face = -1;
    if (w[0] != w[1] && w[1] != w[2] && w[2] != w[0]) {
      const Vec3& a = f.vertices[w[0]];
      const Vec3& b = f.vertices[w[1]];
      const Vec3& c = f.vertices[w[2]];
      const Vec3 cross = (b - a).cross(c - a);
      const double longest = std::max({(b - a).squaredNorm(), (c - b).squaredNorm(), (a - c).squaredNorm()});
      if (cross.norm() > 1e-8 * longest) {
        face = static_cast<int>(f.faces.size());
        f.faces.push_back(w);
        f.face_normals.push_back(cross.normalized());
      }
    }
    if (face < 0) ++f.degenerate_triangles;
    for (int k = 0; k < 3; ++k) {
      const int a = w[k], b = w[(k + 1) % 3];
      if (a != b) uses.push_back({std::min(a, b), std::max(a, b), face});
    }
  }
  sort_by_vertex(uses, static_cast<int>(f.vertices.size()), [](const EdgeUse& u) { return u.a; },
                 [](const EdgeUse& x, const EdgeUse& y) { return x.b != y.b ? x.b < y.b : x.face < y.face; });
  f.edge_face_offsets.push_back(0);
  for (size_t i = 0; i < uses.size(); ++i) {
    if (i == 0 || uses[i].a != uses[i - 1].a || uses[i].b != uses[i - 1].b) {
      if (i > 0) f.edge_face_offsets.push_back(static_cast<int>(f.edge_faces.size()));
      f.edges.push_back({uses[i].a, uses[i].b});
    }
    if (uses[i].face >= 0) f.edge_faces.push_back(uses[i].face);
  }
  f.edge_face_offsets.push_back(static_cast<int>(f.edge_faces.size()));
  const int ne = static_cast<int>(f.edges.size());

  // Edge pseudo-normal: the sum of the adjacent face normals (each face sees the edge under the
  // angle π, so this is the angle-weighted normal).
  f.edge_normals.assign(ne, Vec3::Zero());
  for (int e = 0; e < ne; ++e)
    for (int i = f.edge_face_offsets[e]; i < f.edge_face_offsets[e + 1]; ++i)
      f.edge_normals[e] += f.face_normals[f.edge_faces[i]];

  // Vertex pseudo-normal: incident face normals weighted by the face's angle at the vertex.
  f.vertex_normals.assign(nv, Vec3::Zero());
  for (size_t t = 0; t < f.faces.size(); ++t)
    for (int k = 0; k < 3; ++k) {
      const Vec3& p = f.vertices[f.faces[t][k]];
      const Vec3 u = f.vertices[f.faces[t][(k + 1) % 3]] - p;
      const Vec3 v = f.vertices[f.faces[t][(k + 2) % 3]] - p;
      const double angle = std::atan2(u.cross(v).norm(), u.dot(v));
      f.vertex_normals[f.faces[t][k]] += angle * f.face_normals[t];
    }

  // An open rim has no back: a point whose closest point lies on a boundary edge or vertex (the
  // wedge beyond the rim, e.g. below a scalp's hairline) is counted as outside. A zero
  // pseudo-normal gives the + sign, so the scalp's field says "inside the head" only behind the
  // scalp itself (spec/fields.md).
  for (int e = 0; e < ne; ++e)
    if (f.edge_face_offsets[e + 1] - f.edge_face_offsets[e] == 1) {
      f.edge_normals[e] = Vec3::Zero();
      f.vertex_normals[f.edges[e].first] = Vec3::Zero();
      f.vertex_normals[f.edges[e].second] = Vec3::Zero();
    }

  // Incident edges per vertex.
  f.vertex_edge_offsets.assign(nv + 1, 0);
  for (const auto& e : f.edges) {
    ++f.vertex_edge_offsets[e.first + 1];
    ++f.vertex_edge_offsets[e.second + 1];
  }
  std::partial_sum(f.vertex_edge_offsets.begin(), f.vertex_edge_offsets.end(), f.vertex_edge_offsets.begin());
  f.vertex_edges.resize(f.vertex_edge_offsets[nv]);
  std::vector<int> fill(f.vertex_edge_offsets.begin(), f.vertex_edge_offsets.end() - 1);
  for (int e = 0; e < ne; ++e) {
    f.vertex_edges[fill[f.edges[e].first]++] = e;
    f.vertex_edges[fill[f.edges[e].second]++] = e;
  }
  if (f.faces.empty())
    throw InputError(name, "every triangle of the mesh has zero area; a distance field needs a surface");
  return f;
}

}  // namespace hairfit::field
