#include "scalp/require_disk.h"

#include <algorithm>
#include <cstdio>

#include "core/error.h"

namespace hairfit {

void require_disk(const Mesh& mesh, const MeshTopology& topo, const std::string& file) {
  if (topo.is_disk()) return;
  std::string what;
  if (!topo.nonmanifold_vertices.empty()) {
    what = "it has non-manifold edges (shared by 3 or more triangles) at vertices";
    for (std::size_t i = 0; i < std::min<std::size_t>(6, topo.nonmanifold_vertices.size()); ++i) {
      const Vec3& p = mesh.positions[topo.nonmanifold_vertices[i]];
      char text[96];
      std::snprintf(text, sizeof text, " %d (%.4g, %.4g, %.4g)", topo.nonmanifold_vertices[i] + 1, p.x(), p.y(), p.z());
      what += text;
    }
    if (topo.nonmanifold_vertices.size() > 6) what += " …";
  } else if (topo.components > 1) {
    what = "it has " + std::to_string(topo.components) + " separate parts; keep only the scalp";
  } else if (topo.boundary_loops.empty()) {
    what = "it is closed (no boundary loop); cut it open along the hairline";
  } else if (topo.boundary_loops.size() > 1) {
    what = "it has " + std::to_string(topo.boundary_loops.size()) +
           " boundary loops (holes); fill the holes so only the hairline remains";
  } else {
    what = "its Euler characteristic is " + std::to_string(topo.euler_characteristic) + " instead of 1 (handles?)";
  }
  throw InputError(file, "the scalp must be a topological disk (one piece, one boundary loop), but " + what);
}

}  // namespace hairfit
