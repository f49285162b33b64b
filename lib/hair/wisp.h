// The wisp of fibres around a guide (paper §3.6), as both the density model's deposit and the
// strand stage grow it: one fibre per pore of the guide's cluster, inside a generalised cylinder
// whose radius varies linearly along the guide, optionally winding about it. Each fibre starts at
// its pore, settles into its place in the wisp over the first fifth of its length, and has exactly
// its own length.
#pragma once
#include <functional>
#include <vector>

#include "core/types.h"
#include "hair/guide_track.h"

namespace hairfit {

struct WispShape {
  int points = 16;           // points per fibre (before cutting)
  double root_radius = 0.3;  // cm: wisp radius at the root
  double tip_radius = 0.6;   // cm: wisp radius at the tip
  double turns = 0.0;        // windings about the guide, root to tip (0 = no winding)
};

// The pores to grow fibres from: position on the scalp (cm), own length (cm), guide index.
struct Pores {
  std::vector<Vec3> positions;
  std::vector<double> lengths;
  std::vector<int> guide;
  // Per pore, the unit normal of the scalp triangle it lies on, or empty. Given with a head exit,
  // every fibre's first segment leaves its pore at least kRootRise (strands/strands.h) above that
  // triangle's plane.
  std::vector<Vec3> normals;
};

// Points per fibre: shape.points, at least 2.
int fibre_point_count(const WispShape& shape);

// A wisp's extent: the largest distance of its pores (indices into `positions`) from the guide's
// root in the plane of the root frame's (d1, d2).
double wisp_extent(const GuideTrack& guide, const std::vector<Vec3>& positions, const std::vector<int>& pores);

// What point i of every fibre shares (it depends on i and the shape alone): t_i = i/(n−1) along
// the reach, the settle blend, the wisp radius and the winding's cos/sin. Computed once, not per
// fibre: per fibre, the winding's cos/sin would be its largest setup cost.
struct WispStation {
  double t, w, radius, ca, sa;
};
std::vector<WispStation> wisp_stations(const WispShape& shape);
// The same, kept per thread while the shape stays the same (the density model grows fibres one
// by one with one shape).
const std::vector<WispStation>& kept_wisp_stations(const WispShape& shape);

// Where point i of a fibre sits relative to the guide: t_i along the reach, and its offsets along
// the frame (d1, d2) and the root tangent (fibre_along's scratch, one per station).
struct WispPoint {
  double t;  // i/(n−1)
  double along_d1, along_d2, along_root_tangent;
};

// Moves a fibre's n points in place (the strand stage's head exit), inside the length solve.
using FibreAdjust = std::function<void(Vec3* points, int n)>;

// The fibre of exactly `length` along the track, into points[0..n) (n = stations.size()), with
// `layout` as n points of scratch. With `adjust`, every swept fibre is adjusted before its length
// is measured, so the adjusted fibre still has exactly its length.
void fibre_along(const GuideTrack& track, const Vec3& pore, double length, double wisp_extent,
                 const std::vector<WispStation>& stations, const FibreAdjust* adjust, Vec3* points, WispPoint* layout);

// The fibre of `pore` along `guide` into points[0, fibre_point_count(shape)); `wisp_extent` as
// wisp_extent() gives it.
void grow_fibre(const GuideTrack& guide, const Vec3& pore, double length, double wisp_extent, const WispShape& shape,
                Vec3* points);

}  // namespace hairfit
