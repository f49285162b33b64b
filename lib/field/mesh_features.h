// The closest-point features of a raw triangle mesh — faces, edges, vertices — with the
// angle-weighted pseudo-normals that give the sign of the distance (Bærentzen & Aanæs 2005).
// Internal to lib/field: the distance-field builder scan-converts each feature's neighbourhood.
#pragma once
#include <string>
#include <vector>

#include "core/mesh.h"

namespace hairfit::field {

struct MeshFeatures {
  // Positions after welding exactly coincident vertices (so duplicates share edges and normals).
  std::vector<Vec3> vertices;
  std::vector<int> vertex_of_input;  // per input vertex: its welded vertex (−1 when no triangle uses it)
  // Triangles of non-negligible area, as welded vertex ids, counter-clockwise as in the input.
  std::vector<Vec3i> faces;
  std::vector<Vec3> face_normals;  // unit
  // Unique undirected edges of every input triangle (degenerate ones included: their points are
  // still mesh points), with the non-degenerate faces that contain them (CSR).
  std::vector<std::pair<int, int>> edges;
  std::vector<int> edge_face_offsets;  // size edges + 1
  std::vector<int> edge_faces;
  std::vector<Vec3> edge_normals;  // sum of the adjacent face normals (zero when none)
  // For every vertex, its incident edges (CSR) and its angle-weighted pseudo-normal.
  std::vector<int> vertex_edge_offsets;  // size vertices + 1
  std::vector<int> vertex_edges;
  std::vector<Vec3> vertex_normals;
  int degenerate_triangles = 0;  // input triangles with (near) zero area: represented by their edges
};

// Checks the mesh (throws InputError for no triangles, an index out of range or a non-finite
// coordinate; `name` names the mesh in the message), welds, and extracts the features.
MeshFeatures extract_features(const Mesh& mesh, const std::string& name);

}  // namespace hairfit::field
