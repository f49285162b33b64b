// The scalp under a hair hull (the paper's §3 suggestion, made concrete): an inward offset whose
// thickness is zero at the hairline and grows to a declared crown thickness, smoothed so that it
// follows a skull rather than the curls, bun and braids of the hair.
//
// How: seen from the head centre (the centre of the sphere fitted to the hull), the hull is a
// radius R(u) over directions u. A low-order surface f(u) (polynomials of degree ≤ 2 in u, i.e.
// spherical harmonics up to l = 2) is fitted to R robustly (Tukey weights), so bumps such as a bun
// or braids count as outliers; f is the hair's envelope without them, and f − T the skull. With a
// ramp w that rises smoothly from 0 at the hairline to 1 at `ramp` cm from it (along the hull's
// edges), the scalp radius is ρ = (1 − w)·R + w·(f − T), then smoothed by Jacobi passes over the
// mesh (hairline fixed), clamped after each pass to stay at least ½·w·T under the hull.
// Because the scalp reuses the hull's triangles and moves every vertex along its own direction
// from the centre, it is a disk with the hull's hairline, and — when the hull is star-shaped about
// the centre — it lies under the hull, faces outward and cannot intersect itself (each scalp
// triangle lies inside the tetrahedron of the centre and its hull triangle). Those properties are
// still checked afterwards (prepare.cpp).
//
// The hair volume the pipeline needs is closed: the hull plus a floor under the scalp at
// ρ − w·T (reversed, so the volume's normals face out), sharing the hairline.
#pragma once
#include <functional>
#include <string>
#include <vector>

#include "prepare/hair_region.h"

namespace hairfit {

struct ScalpOptions {
  double crown_thickness = 2.0;  // cm of hair over the skull away from the hairline (T)
  double ramp = 3.0;             // cm from the hairline over which the thickness grows
  int smoothing_passes = 40;     // Jacobi passes of ρ (λ = ½), hairline fixed (radial)
  double voxel = 0.0;            // cm: the level set's grid; 0 takes min(0.25, T / 6)
};

struct ScalpResult {
  std::string method;             // "radial" (here) or "level set" (scalp_level_set.h)
  Mesh scalp;                     // radial: the hull's triangles, moved inward
  std::vector<int> hairline;      // scalp vertices at the hull's hairline, in Hull::hairline's order (same positions)
  std::vector<int> volume_vertex; // per scalp vertex: the volume's vertex at the same place, or −1
  Mesh volume;                    // closed: the hull, then the floor (hull vertices first, the hairline shared)
  std::vector<double> thickness;  // per scalp vertex: the layer's thickness above it, cm (radial: R − ρ)
  std::vector<double> ramp;       // per scalp vertex: w ∈ [0, 1]
  double ramp_length = 0.0;       // cm actually used (at most 0.8 × the largest hairline distance)
  double hairline_reach = 0.0;    // cm: the largest distance from the hairline along the hull's edges
  double envelope_rms = 0.0;      // cm: RMS of R − f over the vertices the robust fit kept
  int envelope_outliers = 0;      // vertices the fit rejected (the bumps)
  int dropped_parts = 0;          // level set: pieces apart from the scalp and floor, left out
  int scalp_holes_filled = 0;     // level set: holes in the scalp's and the floor's pieces filled (the
  int floor_holes_filled = 0;     // layer thinning below the clip level inside the hair), and the longest (cm)
  double longest_hole_filled = 0.0;
  int strip_feet = 0;             // level set: hairline vertices whose strip was lowered (its chords crossed the hull)
};

// Jacobi passes of f over a mesh (each vertex to ½ itself + ½ its neighbours' mean; `neighbours`
// as vertex_neighbours gives them), the hairline vertices fixed; `after(v)` runs on each vertex
// once it is updated (a clamp).
void smooth_off_hairline(const std::vector<std::vector<int>>& neighbours, const std::vector<int>& hairline,
                         std::vector<double>& f, int passes, const std::function<void(int)>& after = {});

// Throws InputError naming `file` when the hull is not star-shaped about its centre (some triangle
// faces the centre: e.g. hair hanging below the head, which the radial offset cannot follow), or
// when the options are out of range.
ScalpResult make_scalp(const Hull& hull, const ScalpOptions& options, const std::string& file);

}  // namespace hairfit
