// Filling the holes of a surface with a rim: every boundary loop but the longest (the rim) is a
// hole, and those up to a share of the rim's length are closed by a fan about their centroid (a
// single triangle for three vertices). The hull cut from a scan (hair_region.h: where the scan
// lacks data or the paint misses an island) and the level-set scalp (scalp_level_set.h: where the
// layer thins below its clip level inside the hair, as over skin coming near) use it.
#pragma once
#include <vector>

#include "core/mesh.h"

namespace hairfit {

struct FilledHoles {
  int rim = -1;                   // the topology's loop taken as the rim (the longest), −1 without loops
  double rim_length = 0.0;
  int filled = 0;                 // holes closed
  double longest_filled = 0.0;    // the longest of them
  std::vector<std::vector<int>> loops;  // each hole closed, as its boundary loop
  std::vector<int> centres;       // per hole closed: the fan's centre vertex, −1 for a single triangle
  int open = 0;                   // holes too long to fill, left open
  double longest_open = 0.0;      // the longest of them
  Vec3 open_at = Vec3::Zero();    // its centroid
};

// `topology` is analyse_topology(mesh). The filling runs each boundary half-edge the other way, so
// the mesh's orientation carries over; centres are appended to mesh.positions.
FilledHoles fill_holes(Mesh& mesh, const MeshTopology& topology, double max_share);

// The length of a closed loop of mesh vertices.
double loop_length(const Mesh& mesh, const std::vector<int>& loop);

}  // namespace hairfit
