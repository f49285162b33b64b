// Loading OBJ triangle meshes (scalp, hair volume, scans) into immutable Mesh values.
#pragma once
#include <filesystem>
#include <string>

#include "core/mesh.h"

namespace hairfit {

struct LoadedMesh {
  Mesh mesh;                     // in cm: file coordinates × scale_to_cm
  int file_vertices = 0;         // `v` lines in the file
  int file_faces = 0;            // `f` lines in the file
  int welded_duplicates = 0;     // vertices merged with an earlier one at the same position
  int dropped_degenerate = 0;    // triangles removed for zero area (after welding)
  int unused_vertices = 0;       // vertices no triangle refers to (removed)
  // Per-vertex colours (r g b in [0, 1] or as written) when every `v` line carries them
  // (`v x y z r g b`, how scanners and painting tools export a mask); empty otherwise.
  std::vector<Vec3> colors;
};

// Reads an OBJ file through tinyobjloader, triangulating polygons; coordinates are read in double
// precision, each the double nearest its text. Throws InputError naming the
// file (and the line, where one is at fault) for a missing, unreadable or binary file, a
// non-finite coordinate, a face index out of range, or a mesh without any usable triangle.
// Exact duplicate vertices are welded and zero-area triangles dropped; both are counted.
LoadedMesh load_obj_mesh(const std::filesystem::path& path, double scale_to_cm = 1.0);

// An OBJ mesh exactly as the file numbers it, for data whose vertex numbers mean something (a
// MakeHuman hair proxy and its fitted copy share them): every `v` in file order, nothing welded or
// dropped; every `vt`; each polygon split into a fan from its first corner, in file order.
struct TexturedMesh {
  Mesh mesh;                             // positions in cm (file coordinates × scale_to_cm)
  std::vector<Vec2> texture_coordinates;  // `vt` lines, in file order
  std::vector<Vec3i> triangle_texture;    // per triangle, its corners' texture coordinates (−1: none)
};

// Throws InputError naming the file as load_obj_mesh does, and for a non-finite texture
// coordinate, an index out of range or a file without faces.
TexturedMesh load_obj_textured(const std::filesystem::path& path, double scale_to_cm = 1.0);

// Writes positions (9 significant digits, more for a mesh far from the origin: as fine a step
// relative to its size), optional per-vertex texture coordinates (`vt`), optional per-vertex
// colours (`v x y z r g b`, one per position) and triangles.
void write_obj_mesh(const std::filesystem::path& path, const Mesh& mesh,
                    const std::vector<Vec2>& texture_coordinates = {}, const std::vector<Vec3>& colors = {});

}  // namespace hairfit
