// Cleaning a raw triangle mesh (a hair hull as exported: open, in several parts, with repeated
// vertices and faces, slivers and patches wound the other way) before winding numbers and fields
// are computed from it, and reporting what was found for `hairfit validate`.
#pragma once
#include <string>
#include <vector>

#include "core/mesh.h"

namespace hairfit {

// What a raw mesh was found to hold, and what cleaning did to it. Every count after welding is of
// the cleaned mesh.
struct MeshReport {
  int input_vertices = 0, input_triangles = 0;
  int welded_vertices = 0;       // used vertices merged into an earlier one within the tolerance
  int duplicate_triangles = 0;   // dropped: the same three vertices as an earlier kept triangle, either orientation
  int degenerate_triangles = 0;  // dropped: a repeated vertex after welding, or |(b−a)×(c−a)| ≤ 1e-12·L², L its longest edge
  int parts = 0;                 // connected components through shared edges
  int boundary_loops = 0;        // all loops of all parts (edges used by one triangle)
  int holes = 0;                 // every loop of a part but its longest by length (the part's rim)
  double longest_hole = 0.0;     // length of the longest hole, in the mesh's units (0 without holes)
  int nonmanifold_edges = 0;     // edges shared by 3 or more triangles
  int flipped_patches = 0;       // consistently wound patches turned over to agree with the rest of their part
  int flipped_triangles = 0;     // triangles in those patches (see orient() in mesh_repair.cpp for the rule)
  int misoriented_edges = 0;     // edges of 2 triangles still traversed the same way: a non-orientable part
  std::vector<int> part_triangles;  // triangles per part, largest first (ties: the part with the earlier triangle)
  bool closed() const { return boundary_loops == 0 && nonmanifold_edges == 0; }
};

struct CleanMesh {
  Mesh mesh;
  MeshReport report;
  std::vector<int> old_to_new_vertex;  // per input vertex: its vertex in `mesh`, −1 when no kept triangle uses it
};

// Welds vertices within `weld_tolerance` (absolute, in the mesh's units; 0 merges exact duplicates
// only), drops degenerate and duplicate triangles, and orients each part consistently. The result
// keeps the input's triangle order minus the dropped ones (a flipped triangle (a, b, c) becomes
// (a, c, b)), and its vertices are those kept triangles use, in input order, at the position of
// the first input vertex of each welded group. Only vertices some input triangle uses are welded.
// Which way a whole part faces (towards the head or away) is not decided here.
// Throws std::out_of_range for a vertex index outside the positions, std::invalid_argument for a
// negative tolerance or a non-finite position.
CleanMesh clean_mesh(const Mesh& raw, double weld_tolerance);

// A one-paragraph summary for `hairfit validate`, e.g. "3 parts (2200, 14, 6 triangles), 1
// boundary loop (the rim), 0 holes, 0 non-manifold edges, 0 flipped patches, 12 welded vertices,
// 0 duplicate and 0 zero-area triangles dropped".
std::string describe(const MeshReport& report);

}  // namespace hairfit
