// PLY point sets: a `vertex` element with x, y, z (float) and named per-vertex float or int
// properties (e.g. nx ny nz, a growth direction, a cluster id). Blender, MeshLab and ParaView read
// these; binary little-endian by default, ASCII on request.
#pragma once
#include <filesystem>
#include <string>
#include <vector>

#include "core/types.h"

namespace hairfit {

struct PlyColumn {
  std::string name;            // property name: [A-Za-z_][A-Za-z0-9_]*
  bool is_int = false;         // int32 when true, float32 otherwise
  std::vector<double> values;  // one per point (ints exactly representable)
};

struct PlyPoints {
  std::vector<Vec3> positions;
  std::vector<PlyColumn> columns;  // in file order after x, y, z
  const PlyColumn* column(const std::string& name) const;
};

// Writes the points atomically (io/atomic_file.h). Throws std::invalid_argument when a column's
// length differs from the number of points or a name is not a valid property name.
void write_ply_points(const std::filesystem::path& path, const PlyPoints& points, bool binary = true);

// Reads a PLY file's `vertex` element (ascii or binary_little_endian; property types char … double;
// other elements skipped when they come after the vertices; list properties rejected). Throws
// InputError naming the file for anything else.
PlyPoints read_ply_points(const std::filesystem::path& path);

}  // namespace hairfit
