// The scalp chart needs a topological disk; this says what a mesh is instead, for the user.
#pragma once
#include <string>

#include "core/mesh.h"

namespace hairfit {

// Throws InputError naming `file` unless the mesh is a topological disk (one part, one boundary
// loop, manifold, χ = 1), saying what it is instead: closed, several parts, several boundary loops
// (holes), non-manifold edges (at which vertices, 1-based as in the OBJ file), or handles.
void require_disk(const Mesh& mesh, const MeshTopology& topology, const std::string& file);

}  // namespace hairfit
