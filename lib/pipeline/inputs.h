// The scene's input files loaded into values, with the checks `hairfit validate` reports.
#pragma once
#include <memory>
#include <optional>

#include "core/grey_map.h"
#include "core/mesh_repair.h"
#include "io/obj_mesh.h"
#include "scalp/require_disk.h"
#include "spec/scene.h"

namespace hairfit {

struct Inputs {
  LoadedMesh scalp;   // in cm, cleaned (core/mesh_repair.h) and facing out of the head
  LoadedMesh volume;  // in cm, cleaned, oriented so that it encloses the scalp
  MeshReport scalp_report, volume_report;  // what cleaning found in each
  bool scalp_reversed = false;   // the scalp faced into the head: its triangles were reversed
  bool volume_reversed = false;  // the volume faced inward: its triangles were reversed
  double scalp_inside_share = 0.0;  // share of the scalp (one probe per triangle) inside the hull (HairRegion)
  std::shared_ptr<const GreyMap> density_map, tilt_map, length_map;  // only the maps effects.maps uses (else null)
  std::optional<Mesh> occluder;  // output.occluder in cm, for the pictures only
  // Every mesh above is moved by −origin: the run computes about this point (core/mesh.h,
  // frame_origin of the scalp; the origin itself for data about it) and its
  // writers move what they write back by +origin, into the scene's own frame.
  Vec3 origin = Vec3::Zero();
};

struct InputsSummary {
  MeshTopology scalp_topology;
  double scalp_area = 0.0;  // cm²
  MeshTopology volume_topology;
  double volume_area = 0.0;           // cm²
  double scalp_inside_fraction = 0.0;  // Inputs::scalp_inside_share
};

// Loads every input the scene names and cleans both meshes (welds, drops duplicate and zero-area
// triangles, orients each part consistently, turns the scalp out of the head and the volume so that
// it encloses the scalp). Raw hulls are accepted: open, in several parts, non-manifold, with holes.
// Throws InputError (naming the file, and the scene line for missing files) only for what leaves
// no region: unreadable data, coordinates beyond 10 km, a scalp the chart cannot take even cleaned
// (not a topological disk, edge-on from above), a volume with no triangle left, a scalp entirely
// outside the volume, and distance-field or density grids larger than fields.max_memory: every
// input error a run could meet, so a run refuses bad input before it writes anything.
// `threads` > 1 reads the two meshes at once (the same result and the same first error).
Inputs load_inputs(const Scene& scene, int threads = 1);

InputsSummary summarise_inputs(const Inputs& inputs);

// require_disk (the scalp must be a topological disk) lives in scalp/require_disk.h.

}  // namespace hairfit
