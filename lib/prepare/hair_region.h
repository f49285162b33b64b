// Cutting the hair hull out of a scan: pick the hair's vertices (a plane, a spherical cap or a
// painted colour mask), keep the triangles whose three corners are picked, keep the largest
// connected part, make it a clean oriented disk (bow-tie vertices shaved, small holes filled) and
// turn it to face away from the head.
#pragma once
#include <string>
#include <vector>

#include "core/mesh.h"

namespace hairfit {

struct HairSelection {
  enum class Kind { plane, cap, mask };
  Kind kind = Kind::cap;
  // plane: the hair is on the side `normal` points to, from `point`.
  Vec3 point = Vec3::Zero(), normal = Vec3::UnitY();
  // cap: the hair is within `half_angle` degrees of `axis`, seen from `centre`.
  Vec3 centre = Vec3::Zero(), axis = Vec3::UnitY();
  double half_angle = 60.0;
  // mask: the hair is painted `color` (r g b as in the file); a vertex matches within `tolerance`
  // (Euclidean distance in the file's colour values).
  Vec3 color = Vec3::Zero();
  double tolerance = 0.15;

  std::string describe() const;  // e.g. "cap: centre (0, 0, 0), axis (0, 1, 0), 60°"
};

// Which scan vertices the selection picks. `colors` is per vertex or empty; a mask selection on a
// scan without colours throws InputError naming `file`.
std::vector<char> select_vertices(const Mesh& scan, const std::vector<Vec3>& colors, const HairSelection& selection,
                                  const std::string& file);

struct HullOptions {
  double max_hole = 0.25;  // largest hole filled, as a share of the hairline's length
};

struct Hull {
  Mesh mesh;                       // an oriented topological disk, normals away from `centre`
  std::vector<int> scan_triangle;  // per hull triangle: its scan triangle, −1 for hole fillings
  std::vector<int> scan_vertex;    // per hull vertex: its scan vertex, −1 for hole centres
  std::vector<int> hairline;       // the boundary loop, hull vertex indices, in triangle order
  Vec3 centre = Vec3::Zero();      // centre of the sphere fitted to the hull (the head's centre)
  int selected_triangles = 0;      // scan triangles with three picked corners
  int parts = 0;                   // connected parts they form
  double selected_area = 0.0;      // cm², all parts
  double kept_area = 0.0;          // cm², the largest part after shaving
  int shaved_triangles = 0;        // removed at bow-tie vertices
  int holes_filled = 0;
  double hairline_length = 0.0;    // cm
};

// Cuts the hull. Throws InputError naming `file` when the selection catches no triangle, when the
// largest part holds less than half the selected area (no one connected hair region), when the
// region is closed (no hairline), has a hole longer than options.max_hole × the hairline, or is not
// a disk for another reason (handles, non-manifold edges).
Hull cut_hull(const Mesh& scan, const std::vector<char>& selected, const HullOptions& options, const std::string& file);

// Centre of the least-squares sphere through the points (algebraic fit: |p|² = 2c·p + k).
Vec3 fit_sphere_centre(const std::vector<Vec3>& points);

}  // namespace hairfit
