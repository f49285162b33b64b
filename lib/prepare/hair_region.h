// Cutting the hair hull out of a scan: a selection (a plane, a spherical cap or a painted colour
// mask) gives every point a value f, hair where f ≥ 0; clip the scan at f = 0 (level_set_clip.h,
// so the hairline follows the selection, not the mesh's edges), keep the largest
// connected part, make it a clean oriented disk (bow-tie vertices shaved, small holes filled) and
// turn it to face away from the head.
#pragma once
#include <string>
#include <vector>

#include "core/mesh.h"
#include "prepare/level_set_clip.h"

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
  // Paint is known at vertices only: its value (clamped to ±tolerance) is averaged with the
  // neighbours' this many times, so the hairline runs smoothly between painted and bare vertices
  // instead of tracing the mesh's edges.
  int mask_smoothing = 2;

  std::string describe() const;  // e.g. "cap: centre (0, 0, 0), axis (0, 1, 0), 60°"
};

// The selection as a continuous value, f ≥ 0 on the hair: plane, the signed distance to it; cap,
// half_angle − the angle to the axis seen from the centre (radians; −1 at the centre itself);
// mask, tolerance − the colour's distance to `color`, clamped to ±tolerance and smoothed over the
// scan (HairSelection::mask_smoothing; per vertex, linear along edges). `colors`
// is per vertex or empty; a mask selection on a scan without colours throws InputError naming `file`.
SelectionField selection_field(const Mesh& scan, const std::vector<Vec3>& colors, const HairSelection& selection,
                               const std::string& file);

struct HullOptions {
  double max_hole = 0.25;  // largest hole filled, as a share of the hairline's length
  ClipOptions clip;
};

struct Hull {
  Mesh mesh;                       // an oriented topological disk, normals away from `centre`
  std::vector<int> scan_triangle;  // per hull triangle: the scan triangle it is (a part of), −1 for hole fillings
  std::vector<int> scan_vertex;    // per hull vertex: the scan vertex it is, −1 for hole centres and for
                                   // hairline points the cut made (on scan edges, or scan vertices moved there)
  std::vector<int> hairline;       // the boundary loop, hull vertex indices, in triangle order
  Vec3 centre = Vec3::Zero();      // centre of the sphere fitted to the hull (the head's centre)
  int selected_triangles = 0;      // triangles of the clipped scan (whole scan triangles and parts), all parts
  int cut_triangles = 0;           // scan triangles the hairline splits
  int snapped_vertices = 0;        // scan vertices moved onto the hairline (ClipOptions::snap)
  int parts = 0;                   // connected parts they form
  double selected_area = 0.0;      // cm², all parts
  double kept_area = 0.0;          // cm², the largest part after shaving
  int shaved_triangles = 0;        // removed at bow-tie vertices
  int holes_filled = 0;
  double hairline_length = 0.0;    // cm
};

// Cuts the hull: clips the scan at the field's zero level set, then keeps the largest part. Throws
// InputError naming `file` when the selection catches nothing, when the
// largest part holds less than half the selected area (no one connected hair region), when the
// region is closed (no hairline), has a hole longer than options.max_hole × the hairline, or is not
// a disk for another reason (handles, non-manifold edges).
Hull cut_hull(const Mesh& scan, const SelectionField& field, const HullOptions& options, const std::string& file);

// Centre of the least-squares sphere through the points (algebraic fit: |p|² = 2c·p + k).
Vec3 fit_sphere_centre(const std::vector<Vec3>& points);

}  // namespace hairfit
