// Strand generation (paper §3.6): around each principal guide, one fibre per pore of its
// cluster, inside a generalised cylinder whose radius varies along the guide, optionally winding
// about it, then optionally cut where it leaves the volume.
#pragma once
#include <cstddef>
#include <cstdint>
#include <functional>
#include <type_traits>
#include <vector>

#include "core/curves.h"
#include "core/exec.h"
#include "hair/wisp.h"
#include "strands/cutting.h"
#include "strands/density_spread.h"

namespace hairfit {

struct StrandOptions {
  WispShape wisp;
  bool cutting = false;
  double cut_threshold = 1.0;  // cm outside the volume before a cut
  bool cut_tips = false;       // a fibre ending outside is cut where it last left (cut_at_exit)
  // Fibres spread through the depth of the hair layer (strands.depth = "layer"; needs
  // StrandSurroundings::to_layer_depth): the fibres of a wisp take depths spaced evenly over the
  // layer between kLayerMargin of it at either side (over its top 2·tip_radius only where it is
  // deeper than that: to_layer_depth's placement, pipeline/scalp_exit.h), the fibre whose pore lies
  // furthest upstream along the guide's root tangent on top (its hair lies over its neighbours'
  // roots), each point moved to its depth by the settle weight of its wisp station. The first
  // segment leaves the pore as in the wisp: turned toward a depth it could dip under a curved scalp
  // beside the pore, where a chord from the root cannot be lifted.
  bool layer_depth = false;
  // The density models' fibre part (strands/density_spread.h): the grown fibres spread down their
  // own density gradient before the keep-out pass and the cut. Not with layer_depth, whose
  // placement grows the fibres again inside the keep-out pass.
  DensitySpread spread;
};

// The share of the layer's depth kept clear at either side when fibres spread through it.
constexpr double kLayerMargin = 0.1;

// The layer depth (0 scalp, 1 hull) of the fibre ranked `rank` of `count` (0 the furthest upstream).
double fibre_layer_depth(int rank, int count);

// Passes of the ¼, ½, ¼ filter that smooth a fibre's moves into its layer depth along it. One
// pass halves a station-to-station zigzag and keeps the spread: on the MakeHuman hulls at 600
// guides, 50 hairs/cm², bob01_full's coverage 0.910 → 0.907 and its fibres' sharpest turn (90th
// percentile) 89° → 54°; two passes turned them by 46° at most but covered 0.897.
constexpr int kLayerMoveSmoothing = 1;

// `passes` of the ¼, ½, ¼ filter over values[first, n), reading values[first − 1] (first ≥ 1)
// as it is and the line through the last two values past the end: values along a line stay on it.
void smooth_along(std::vector<Vec3>& values, int first, int passes);

// sin of the least angle a fibre's first segment rises above its pore's triangle (2°).
constexpr double kRootRise = 0.0348994967025;

struct Strands {
  Curves fibres;            // one per pore, in pore order; fibres.guide = the pore's guide
  std::vector<char> cut;    // per fibre: was it cut
  int cut_count = 0;
  // With HeadExit::chord_crossing: fibres cut before a chord the keep-out pass left through the
  // scalp (counted in cut_count too), and the fibre segments left crossing or touching it, which
  // only a fibre whose first chord crosses keeps (a cut end is part of a chord already tested, so
  // cutting adds none).
  int cut_at_scalp = 0;
  long long scalp_crossings = 0;
};

// Where a fibre's chord first crosses the scalp: the share t of the way along it, a point of the
// crossed triangle's plane, and that plane's unit normal pointing out of the head.
struct ChordCrossing {
  double t = -1.0;
  Vec3 point = Vec3::Zero();
  Vec3 normal = Vec3::Zero();
};

// How make_strands keeps fibres out of the head, and optionally in the hair volume (scalp_exit in
// lib/pipeline builds it from the fields and the scalp's mesh).
struct HeadExit {
  // Returns a point behind the scalp moved back out of the head, and any other point unchanged,
  // and sets `scalp` to the scalp's signed distance at the given point (negative inside the head),
  // or to +infinity where the point is certainly in front of the scalp; make_strands hands it on
  // (only its sign matters).
  std::function<Vec3(const Vec3& p, double& scalp)> move_out;
  // Optional, exact: whether the chord a→b crosses the scalp's triangles or touches them (at an
  // end, or a hair beside a rim: the test errs toward crossing, so that a chord it passes is clear
  // whichever way round-off falls), and where first; `from_root`: a is a root, on the scalp by
  // construction, whose touch does not count. With it, no fibre segment the repair can lift off
  // the scalp is left crossing it (move_out sees only the interpolated field, which rounds the
  // scalp's folds and its rim), and the probes along the chords are not needed.
  std::function<bool(const Vec3& a, const Vec3& b, bool from_root, ChordCrossing& first)> chord_crossing;
  // Optional, with chord_crossing: a distance (cm) the distance from p to the scalp is never
  // below, cheap to look up. Chords whose ends' bounds add up to more than their length are not
  // tested; without it every chord is.
  std::function<double(const Vec3& p)> clearance;
  // Optional: returns a point a little outside the hair volume moved back in, any other point
  // unchanged. Applied before move_out, so where the layer is too thin for both the head wins.
  std::function<Vec3(const Vec3& p)> into_volume;

  HeadExit() = default;
  HeadExit(std::nullptr_t) {}
  template <class MoveOut, class = std::enable_if_t<std::is_invocable_r_v<Vec3, MoveOut, const Vec3&, double&>>>
  HeadExit(MoveOut move) : move_out(std::move(move)) {}
  explicit operator bool() const { return static_cast<bool>(move_out); }
  Vec3 operator()(const Vec3& p, double& scalp) const { return move_out(p, scalp); }
};

// The clearance (cm) a head exit keeps the points it moves at, in front of the scalp.
constexpr double kHeadExitClearance = 0.05;

// What make_strands learns about every point of the fibres on the way (fibres.points order), so
// that callers need not ask the fields again: one byte a point.
struct FibrePointSides {
  std::vector<std::int8_t> outside_volume;  // with cutting: 1 where volume(p) > 0, else 0; else empty
  std::vector<std::int8_t> in_head;  // with out_of_head: 1 where it reported a scalp distance < 0, 0
                                     // where ≥ 0 (or NaN), −1 at points it was not asked about
                                     // (roots, moved points, cut ends); else empty
};

// What the fibres are grown against; each part is optional.
struct StrandSurroundings {
  DistanceFunction volume;  // signed distance to the hair-volume boundary (read only with cutting)
  // cut_at_exit's `quick`: volume(p), or ±infinity where the sign is certain.
  DistanceFunction volume_quick;
  // Keeps fibres out of the head: a fibre that would pass behind the scalp (a wisp wider than the
  // guide's clearance, or a guide that dips in) has those points moved out, still with exactly
  // its length.
  HeadExit out_of_head;
  // With StrandOptions::layer_depth: p moved across the fibre's unit direction `along` there, the
  // share `weight` of the way from its own layer depth to `depth` (field/layer_depth.h), less
  // beyond the hull, where the layer has ended, and (layer_placement) below the scalp's rim of a
  // head closed by its floor, where the depth runs along hanging hair.
  std::function<Vec3(const Vec3& p, const Vec3& along, double depth, double weight)> to_layer_depth;
  // Optional: whether p lies in the hair's region; the density spread (StrandOptions::spread)
  // then evens the fibres out per unit of the region (normalise_by_region), not of space.
  RegionTest hair_region;
};

// The strands, and what the field values looked up on the way said about every point.
struct GrownStrands {
  Strands strands;
  FibrePointSides sides;
};

// `guides` holds one polyline per guide (index = guide id), root first. Each fibre starts exactly
// at its pore and, unless cut, has exactly its length; a fibre longer than its guide continues
// along the guide's last tangent. Deterministic for any thread count.
// `grown` (optional, else empty): every pore's fibre as grow_fibre grows it along these guides
// with these options, fibre_point_count(options.wisp) points each, in pore order (the density
// model's deposit grew them already); those fibres are not grown again, and the result is the
// same bit for bit (with StrandOptions::layer_depth they are grown again, since the deposit
// does not spread them through the layer). Throws std::invalid_argument when it holds another
// number of points.
GrownStrands make_strands(const Curves& guides, const Pores& pores, const StrandOptions& options,
                          const StrandSurroundings& around = {}, const Exec& exec = {}, std::vector<Vec3> grown = {});

// One fibre (exposed for tests): the wisp frame is rotation-minimising along the guide.
std::vector<Vec3> make_fibre(const std::vector<Vec3>& guide, const Vec3& pore, double length, double wisp_extent,
                             const StrandOptions& options, const HeadExit& out_of_head = nullptr);

}  // namespace hairfit
