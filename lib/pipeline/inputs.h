// The scene's input files loaded into values, with the checks `hairfit validate` reports.
#pragma once
#include <optional>

#include "core/grey_map.h"
#include "io/obj_mesh.h"
#include "scalp/require_disk.h"
#include "spec/scene.h"

namespace hairfit {

struct Inputs {
  LoadedMesh scalp;   // in cm
  LoadedMesh volume;  // in cm
  std::optional<GreyMap> density_map, tilt_map, length_map;  // only the maps effects.maps uses
};

struct InputsSummary {
  MeshTopology scalp_topology;
  double scalp_area = 0.0;  // cm²
  MeshTopology volume_topology;
  double volume_area = 0.0;           // cm²
  double scalp_inside_fraction = 0.0;  // share of scalp vertices the volume encloses (winding > ½)
};

// Loads every input the scene names. Throws InputError (naming the file, and the scene line for
// missing files) for unreadable data, coordinates beyond 10 km, a scalp the chart cannot take (not
// a topological disk, inconsistently oriented, edge-on from above), a volume that does not enclose
// the scalp or faces inward, and distance-field or density grids larger than fields.max_memory:
// every input error a run could meet, so a run refuses bad input before it writes anything.
// `threads` > 1 reads the two meshes at once (the same result and the same first error).
Inputs load_inputs(const Scene& scene, int threads = 1);

InputsSummary summarise_inputs(const Inputs& inputs);

// require_disk (the scalp must be a topological disk) lives in scalp/require_disk.h.

}  // namespace hairfit
