// NRRD volumes (distance fields, density grids): float32, raw little-endian, x fastest, placed in
// world space by `space origin` and `space directions` so ParaView, 3D Slicer, ITK and teem's
// `unu` show them where the meshes are (see /work/shared/FORMATS.md).
#pragma once
#include <filesystem>
#include <vector>

#include "core/types.h"

namespace hairfit {

struct NrrdVolume {
  Vec3i sizes = Vec3i::Zero();  // samples along x, y, z
  Vec3 origin = Vec3::Zero();   // cm: world position of sample (0,0,0)
  Vec3 spacing = Vec3::Ones();  // cm between samples along each axis (axis-aligned directions)
  std::vector<float> data;      // sizes.prod() samples, x fastest then y then z
};

// Writes atomically (temporary file, then rename). Throws std::invalid_argument when data does
// not have sizes.prod() samples.
void write_nrrd(const std::filesystem::path& path, const NrrdVolume& volume);

// Reads what write_nrrd writes — and any 3-D NRRD with type float, encoding raw, little endian,
// axis-aligned space directions (space origin optional) — throwing InputError naming the file and
// the offending header field otherwise.
NrrdVolume read_nrrd(const std::filesystem::path& path);

}  // namespace hairfit
