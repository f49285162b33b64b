// Strand and guide files that other tools read (FORMATS.md). Every writer is atomic and writes
// every curve root first; none writes NaN (a non-finite point is an internal error).
#pragma once
#include <filesystem>
#include <string>

#include "core/curves.h"

namespace hairfit {

// cyHair .hair (Cem Yuksel): 128-byte little-endian header, segment counts, points, and thickness
// when the curves carry widths. At most 65 535 segments per curve.
void write_hair_file(const std::filesystem::path& path, const Curves& curves, const std::string& info = "hairfit");
// Reads a .hair file (segments, points, thickness; transparency and colours are skipped).
// Throws InputError naming the file for a truncated or inconsistent file.
Curves read_hair_file(const std::filesystem::path& path);

// OBJ: `v` lines, then one `l a b` line per segment (Blender, tinyobjloader and MeshLab read only
// two indices of a longer `l` line); an `o` group per guide is not used, to keep files small.
// The text is formatted on up to `threads` threads (the bytes do not depend on it).
void write_obj_curves(const std::filesystem::path& path, const Curves& curves, int threads = 1);

// USD ASCII with one BasisCurves prim: type "linear", non-periodic, widths per vertex, extent,
// metersPerUnit 0.01 (cm). `default_width` in cm is used when the curves carry no widths.
void write_usda_curves(const std::filesystem::path& path, const Curves& curves, double default_width = 0.007,
                       const Vec3& up = Vec3(0, 1, 0));

// Binary little-endian PLY: `vertex` (x, y, z float, guide int) and `edge` (vertex1, vertex2 int).
void write_ply_curves(const std::filesystem::path& path, const Curves& curves);

}  // namespace hairfit
