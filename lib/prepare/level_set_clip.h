// Clipping a scan at the zero level set of a selection value f (f ≥ 0 is kept), so the hairline
// follows the selection itself instead of the mesh's edges (marching triangles).
#pragma once
#include <functional>
#include <vector>

#include "core/mesh.h"

namespace hairfit {

struct SelectionField {
  std::vector<double> values;  // f per scan vertex
  // f anywhere, when the selection is geometric (plane, cap): crossings are then found on the
  // edge to rounding. Empty (a colour mask): f is taken linear along each edge.
  std::function<double(const Vec3&)> at;
};

struct ClipOptions {
  // A vertex whose nearest crossing lies within this share of that edge's length is moved onto
  // the crossing (and counts as on the level set), so the cut makes no needles or slivers.
  double snap = 0.25;
};

struct Clipped {
  Mesh mesh;                       // the kept part of every scan triangle, same orientation
  std::vector<int> scan_triangle;  // per triangle: the scan triangle it is (a part of)
  std::vector<int> scan_vertex;    // per vertex: the scan vertex it is, −1 for points the cut made
  int cut_triangles = 0;           // scan triangles split by the level set
  int snapped_vertices = 0;        // scan vertices moved onto the level set
};

Clipped clip_at_level_set(const Mesh& scan, const SelectionField& field, const ClipOptions& options = {});

}  // namespace hairfit
