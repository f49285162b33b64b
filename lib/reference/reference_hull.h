// A hair hull voxelised from reference hair (issue 47's round trip): every grid node within
// `dilation` of the hair's surfaces or of the scalp is occupied, nodes the occupied ones enclose
// (the inside of a thick braid, cards' tubes) are filled, and the hull is the boundary of that
// occupancy, the zero set of (distance − dilation) by marching tetrahedra
// (prepare/marching_tetrahedra.h). Distances are the exact ones of the project's distance field
// (field/distance_field.h) of the hair and the scalp together. The scalp is in it so that the
// roots lie inside the hull wherever the hair stands off the head.
#pragma once
#include <cstdint>

#include "core/mesh.h"

namespace hairfit {

struct ReferenceHullOptions {
  double voxel = 0.5;     // cm: grid spacing
  double dilation = 1.0;  // cm: how far the hull lies beyond the hair and the scalp (> 0)
  int threads = 0;        // 0: all; the hull is the same for any count
};

struct ReferenceHull {
  Mesh mesh;                       // cm; closed, oriented outward (toward increasing distance)
  std::int64_t occupied_nodes = 0;  // nodes within `dilation`
  std::int64_t filled_nodes = 0;    // nodes farther, but enclosed by occupied ones
};

// `hair` (its triangles: cards, shells, tubes) and `scalp` in cm. Throws std::invalid_argument
// for a voxel or dilation ≤ 0, and InputError as make_distance_field does for a grid too large.
ReferenceHull reference_hull(const Mesh& hair, const Mesh& scalp, const ReferenceHullOptions& options = {});

}  // namespace hairfit
