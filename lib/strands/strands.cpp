#include "strands/strands.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>

#include "core/parallel.h"
#include "core/smoothstep.h"
#include "hair/guide_track.h"
#include "hair/wisp.h"

namespace hairfit {

namespace {


// Per-thread scratch of the fibre loop (no allocation per fibre).
struct Scratch {
  std::vector<WispPoint> layout;
  std::vector<double> distances;
  std::vector<Vec3> before_cut;
};

// Without an exact chord test (HeadExit::chord_crossing), where along a segment keep_out looks
// for it dipping into the head: the midpoint, and on the first segment also near the root, where
// a chord that leaves the pore below its tangent plane enters the head at once.
constexpr double kFirstSegmentProbes[] = {0.25, 0.5};
constexpr double kSegmentProbes[] = {0.5};
// A probe closer to the scalp than this (cm) dips; with the exact test, the clearance a lifted
// chord end keeps in front of the triangle it crossed. Less than the clearance the head exit
// keeps points at (kHeadExitClearance): near the root the chord of a fibre that leaves its pore
// at a low angle runs that close by construction, and lifting its far end by the whole shortfall
// over t lifts it out of a thin layer (bench/results/scalp_crossings.md).
constexpr double kProbeClearance = 0.03;

// Whether the segment a→b dips into the head at one of its probes: a probe within kProbeClearance
// of the scalp or behind it.
template <std::size_t N>
bool dips(const HeadExit& out_of_head, const Vec3& a, const Vec3& b, const double (&probes)[N]) {
  for (double t : probes) {
    double scalp;
    out_of_head(a + t * (b - a), scalp);
    if (scalp < kProbeClearance) return true;
  }
  return false;
}

// Whether the first segment rises less than `rise` (the sine of its angle) above the plane with
// unit normal n.
bool first_segment_low(const Vec3& n, const Vec3* points, double rise = kRootRise) {
  const Vec3 d = points[1] - points[0];
  return d.dot(n) < rise * d.norm();
}

// Turns the first segment about the root, in the plane of it and n, to rise `rise` above the
// plane with unit normal n where it rises less (its length kept).
void raise_first_segment(const Vec3& n, Vec3* points, double rise = kRootRise) {
  if (!first_segment_low(n, points, rise)) return;
  const Vec3 d = points[1] - points[0];
  const Vec3 along = d - d.dot(n) * n;
  const double length = d.norm(), across = along.norm();
  const Vec3 tangent = across > 1e-12 * length ? Vec3(along / across) : Vec3(Vec3::Zero());
  points[1] = points[0] + length * (std::sqrt(1.0 - rise * rise) * tangent + rise * n);
}

// Whether chord a→b crosses or touches the scalp (HeadExit::chord_crossing; a is a root when
// `from_root`), where the clearances at its ends leave room for it to.
bool chord_crosses(const HeadExit& out_of_head, const Vec3& a, const Vec3& b, bool from_root, ChordCrossing& first,
                   double clearance_a = std::numeric_limits<double>::quiet_NaN(),
                   double clearance_b = std::numeric_limits<double>::quiet_NaN()) {
  if (std::isnan(clearance_a)) clearance_a = out_of_head.clearance ? out_of_head.clearance(a) : 0.0;
  if (std::isnan(clearance_b)) clearance_b = out_of_head.clearance ? out_of_head.clearance(b) : 0.0;
  return clearance_a + clearance_b <= (b - a).norm() && out_of_head.chord_crossing(a, b, from_root, first);
}

// Lifts of one segment's end off the plane of the triangle its chord crosses, and passes over the
// fibre, before a crossing is left as it is (each lift clears one triangle; a lift of a segment's
// near end can make the segment before it cross, which the next pass finds).
constexpr int kLiftsPerSegment = 4;
constexpr int kCrossingPasses = 3;

// The rises (sines of the angle above the pore's plane) a first segment is turned up to, in turn,
// where its root lies behind the plane of a triangle its chord crosses (a pore in a hollow of the
// scalp, its chord leaving low across the rising triangle beside it): the steeper the chord, the
// nearer the pore it meets that plane, until it meets it off the triangle.
constexpr double kFirstSegmentRises[] = {0.25, 0.5, 0.75, 0.9};

// Turns the first segment up about its root toward the pore's normal n, to the first of
// kFirstSegmentRises at which its chord crosses the scalp no more; false (points unchanged) if
// none clears it.
bool turn_first_segment_up(const HeadExit& out_of_head, const Vec3& n, Vec3* points) {
  for (double rise : kFirstSegmentRises) {
    Vec3 trial[2] = {points[0], points[1]};
    raise_first_segment(n, trial, rise);
    ChordCrossing hit;
    if (!out_of_head.chord_crossing(trial[0], trial[1], true, hit)) {
      points[1] = trial[1];
      return true;
    }
  }
  return false;
}

// The search for a clear first chord where turning it up does not clear it: directions on cones
// about the chord, kClearSearchStep apart in angle up to its reverse, each cone sampled at about
// kClearSearchStep along its circle.
constexpr double kClearSearchStep = 5.0 * M_PI / 180.0;

// The first segment turned about its root to the nearest direction (in angle, of the cones'
// samples, the first of a cone's from the side of n) that rises at least kRootRise above the
// plane with unit normal n and along which its chord crosses the scalp nowhere; false (points
// unchanged) if none does. Where the pore's triangle faces across the head or into it (a riser or
// a fold of the scalp), its normal runs along the scalp or into the head, turning toward it
// need not clear a neighbouring triangle, and the clear directions can lie off to a side. Only
// chords the turns toward n leave crossing are searched: about 1 650 chord tests where none is
// clear.
bool turn_first_segment_clear(const HeadExit& out_of_head, const Vec3& n, Vec3* points) {
  const Vec3 d = points[1] - points[0];
  const double length = d.norm();
  if (!(length > 0.0)) return false;
  const Vec3 axis = d / length;
  // The cones' circles start on the side of n (or of any direction across the chord).
  Vec3 across = n - n.dot(axis) * axis;
  if (!(across.norm() > 1e-9)) across = axis.unitOrthogonal();
  across.normalize();
  const Vec3 side = axis.cross(across);
  const int cones = static_cast<int>(std::lround(M_PI / kClearSearchStep));
  for (int k = 1; k <= cones; ++k) {
    const double angle = k * kClearSearchStep;
    const int samples = std::max(1, static_cast<int>(std::ceil(2.0 * M_PI * std::sin(angle) / kClearSearchStep - 1e-9)));
    for (int j = 0; j < samples; ++j) {
      // 0, +1, −1, +2, −2, … steps round from the side of n
      const int step = (j + 1) / 2 * (j % 2 == 1 ? 1 : -1);
      const double azimuth = 2.0 * M_PI * step / samples;
      const Vec3 direction = std::cos(angle) * axis +
                             std::sin(angle) * (std::cos(azimuth) * across + std::sin(azimuth) * side);
      if (direction.dot(n) < kRootRise) continue;
      const Vec3 end = points[0] + length * direction;
      ChordCrossing hit;
      if (out_of_head.chord_crossing(points[0], end, true, hit)) continue;
      points[1] = end;
      return true;
    }
  }
  return false;
}

// Root to tip, where a segment's chord crosses the scalp (the exact test of `out_of_head`), the
// end behind the crossed triangle's plane moves out along its normal to kProbeClearance in front
// of it, so the chord no longer meets that triangle. The root stays where it is: a first segment
// whose root lies behind the crossed plane turns up about the root instead (given the pore's
// normal, turn_first_segment_up, else to the nearest clear direction, turn_first_segment_clear),
// or keeps that crossing.
void lift_off_crossings(const HeadExit& out_of_head, const Vec3* root_normal, Vec3* points, int n) {
  double unused;
  for (int pass = 0; pass < kCrossingPasses; ++pass) {
    bool lifted = false;
    for (int i = 1; i < n; ++i)
      for (int lift = 0; lift < kLiftsPerSegment; ++lift) {
        ChordCrossing hit;
        if (!chord_crosses(out_of_head, points[i - 1], points[i], i == 1, hit)) break;
        const double near = hit.normal.dot(points[i - 1] - hit.point), far = hit.normal.dot(points[i] - hit.point);
        Vec3& end = far <= near ? points[i] : points[i - 1];
        if (&end == points) {
          if (!root_normal || !(turn_first_segment_up(out_of_head, *root_normal, points) ||
                                turn_first_segment_clear(out_of_head, *root_normal, points)))
            break;
          lifted = true;
          continue;
        }
        end += (kProbeClearance - std::min(far, near)) * hit.normal;
        end = out_of_head(end, unused);
        lifted = true;
      }
    if (!lifted) return;
  }
}

// Passes every point but the root into the volume (HeadExit::into_volume, if given) and through
// `out_of_head` (and, given the pore's triangle normal, raises the first segment above the
// triangle's plane). Then, with the exact chord test, lifts the chords off the scalp
// (lift_off_crossings); without it, root to tip, probes every segment: where a chord dips into the
// head at the fraction t of its length (the probe lies behind the scalp and the exit moves it by
// Δ), its far end moves out by Δ / t, which lifts the probe out with it.
void keep_out(const HeadExit& out_of_head, const Vec3* root_normal, Vec3* points, int n) {
  double unused;
  if (out_of_head.into_volume)
    for (int i = 1; i < n; ++i) points[i] = out_of_head.into_volume(points[i]);
  for (int i = 1; i < n; ++i) points[i] = out_of_head(points[i], unused);
  if (root_normal) raise_first_segment(*root_normal, points);
  if (out_of_head.chord_crossing) {
    lift_off_crossings(out_of_head, root_normal, points, n);
    return;
  }
  for (int i = 1; i < n; ++i) {
    auto lift = [&](double t) {
      const Vec3 q = points[i - 1] + t * (points[i] - points[i - 1]);
      double scalp;
      const Vec3 moved = out_of_head(q, scalp);
      if (scalp < kProbeClearance && moved != q) {
        // The exit moves q to its own clearance; the probe needs only kProbeClearance.
        const double share = kHeadExitClearance > scalp ? (kProbeClearance - scalp) / (kHeadExitClearance - scalp) : 1.0;
        points[i] = out_of_head(points[i] + share * (moved - q) / t, unused);
      }
    };
    if (i == 1)
      for (double t : kFirstSegmentProbes) lift(t);
    else
      for (double t : kSegmentProbes) lift(t);
  }
}


// fibre_along, with the points behind the scalp (or segments dipping into it) moved out when
// `out_of_head` is given. Most
// fibres never enter the head; only those that do pay for field lookups inside the length solve.
// `in_head` (if given) receives FibrePointSides::in_head of each point of the result (−1 at the
// root and throughout a moved fibre). `grown`: `points` already hold fibre_along's result.
// The chords of a fibre that still cross the scalp by HeadExit::chord_crossing after the keep-out
// pass: how many, and the first (k: points k − 1 → k; 0 if none). None without that test, and
// none on the fast path, whose every chord passed it.
struct ChordsLeft {
  int count = 0;
  int first = 0;
};

// `place` (optional): the fibre's move into its layer depth, in the length solve before the
// keep-out pass.
ChordsLeft fibre_kept_out(const GuideTrack& track, const Vec3& pore, double length, double wisp_extent,
                   const std::vector<WispStation>& stations, const HeadExit& out_of_head, const Vec3* root_normal,
                   Vec3* points, WispPoint* layout, std::int8_t* in_head = nullptr, bool grown = false,
                   const FibreAdjust* place = nullptr) {
  if (!grown || place) fibre_along(track, pore, length, wisp_extent, stations, place, points, layout);
  if (!out_of_head) return {};
  const int n = static_cast<int>(stations.size());
  if (in_head) in_head[0] = -1;
  const bool chords = static_cast<bool>(out_of_head.chord_crossing);
  const bool bounded = chords && out_of_head.clearance;
  double clearance_before = bounded ? out_of_head.clearance(points[0]) : 0.0;
  for (int i = 1; i < n; ++i) {
    double value = std::numeric_limits<double>::quiet_NaN();
    const bool chord_dips = i == 1 ? (!chords && dips(out_of_head, points[0], points[1], kFirstSegmentProbes)) ||
                                         (root_normal && first_segment_low(*root_normal, points))
                                   : !chords && dips(out_of_head, points[i - 1], points[i], kSegmentProbes);
    const double clearance = bounded ? out_of_head.clearance(points[i]) : 0.0;
    ChordCrossing unused;
    if (out_of_head(points[i], value) != points[i] || chord_dips ||
        (out_of_head.into_volume && out_of_head.into_volume(points[i]) != points[i]) ||
        (chords && chord_crosses(out_of_head, points[i - 1], points[i], i == 1, unused, clearance_before, clearance))) {
      const FibreAdjust keep = [&](Vec3* fibre, int m) {
        if (place) (*place)(fibre, m);
        keep_out(out_of_head, root_normal, fibre, m);
      };
      fibre_along(track, pore, length, wisp_extent, stations, &keep, points, layout);
      if (in_head) std::fill(in_head, in_head + n, std::int8_t(-1));
      ChordsLeft left;
      ChordCrossing hit;
      for (int j = 1; chords && j < n; ++j)
        if (chord_crosses(out_of_head, points[j - 1], points[j], j == 1, hit) && left.count++ == 0) left.first = j;
      return left;
    }
    if (in_head) in_head[i] = std::isnan(value) ? -1 : value < 0.0;
    clearance_before = clearance;
  }
  return {};
}

}  // namespace


std::vector<Vec3> make_fibre(const std::vector<Vec3>& guide, const Vec3& pore, double length, double wisp_extent,
                             const StrandOptions& options, const HeadExit& out_of_head) {
  const std::vector<WispStation>& stations = kept_wisp_stations(options.wisp);
  std::vector<Vec3> points(stations.size());
  std::vector<WispPoint> layout(stations.size());
  fibre_kept_out(GuideTrack(guide), pore, length, wisp_extent, stations, out_of_head, nullptr, points.data(), layout.data());
  return points;
}

void smooth_along(std::vector<Vec3>& values, int first, int passes) {
  const int n = static_cast<int>(values.size());
  thread_local std::vector<Vec3> last;
  for (int pass = 0; pass < passes; ++pass) {
    last = values;
    for (int k = first; k < n; ++k)
      values[k] = 0.25 * last[k - 1] + 0.5 * last[k] + 0.25 * (k + 1 < n ? last[k + 1] : Vec3(2.0 * last[k] - last[k - 1]));
  }
}

double fibre_layer_depth(int rank, int count) {
  return kLayerMargin + (1.0 - 2.0 * kLayerMargin) * (1.0 - (rank + 0.5) / std::max(1, count));
}

namespace {

// Per pore, its fibre's layer depth (fibre_layer_depth): within its guide's wisp, ranked by how
// far upstream along the guide's root tangent the pore lies (ties by pore index).
std::vector<double> fibre_layer_depths(const std::vector<GuideTrack>& tracks, const Pores& pores,
                                       const std::vector<std::vector<int>>& pores_of) {
  std::vector<double> depth(pores.positions.size(), 0.5);
  std::vector<std::pair<double, int>> order;
  for (std::size_t g = 0; g < tracks.size(); ++g) {
    Vec3 root, tangent, d1, d2;
    tracks[g].at(0.0, root, tangent, d1, d2);
    order.clear();
    for (int i : pores_of[g]) order.push_back({(pores.positions[i] - root).dot(tangent), i});
    std::sort(order.begin(), order.end());
    const int count = static_cast<int>(order.size());
    for (int rank = 0; rank < count; ++rank) depth[order[rank].second] = fibre_layer_depth(rank, count);
  }
  return depth;
}

}  // namespace

GrownStrands make_strands(const Curves& guides, const Pores& pores, const StrandOptions& options,
                          const StrandSurroundings& around, const Exec& exec, std::vector<Vec3> grown) {
  const DistanceFunction& volume = around.volume;
  const DistanceFunction& volume_quick = around.volume_quick;
  const HeadExit& out_of_head = around.out_of_head;
  const bool pre_grown = !grown.empty();
  const int guide_count = static_cast<int>(guides.count());
  std::vector<GuideTrack> tracks;
  tracks.reserve(guide_count);
  for (int g = 0; g < guide_count; ++g)
    tracks.emplace_back(std::vector<Vec3>(guides.points.begin() + guides.offsets[g], guides.points.begin() + guides.offsets[g + 1]));

  std::vector<std::vector<int>> pores_of(guide_count);
  for (std::size_t i = 0; i < pores.positions.size(); ++i) pores_of[pores.guide[i]].push_back(static_cast<int>(i));
  std::vector<double> extent(guide_count, 0.0);
  for (int g = 0; g < guide_count; ++g) extent[g] = wisp_extent(tracks[g], pores.positions, pores_of[g]);

  const bool layered = options.layer_depth && static_cast<bool>(around.to_layer_depth);
  const std::vector<double> layer_depths = layered ? fibre_layer_depths(tracks, pores, pores_of) : std::vector<double>{};

  // Every fibre is grown (and cut) in place in its own slot of n points of the result; slots of
  // cut fibres are closed up afterwards.
  const int count = static_cast<int>(pores.positions.size());
  const bool cutting = options.cutting && volume;
  const std::vector<WispStation> stations = wisp_stations(options.wisp);
  const std::size_t n = stations.size(), slots = n * count;
  GrownStrands result;
  Strands& strands = result.strands;
  FibrePointSides* sides = &result.sides;
  Curves& out = strands.fibres;
  if (pre_grown) {
    if (grown.size() != slots)
      throw std::invalid_argument("make_strands: the grown fibres hold " + std::to_string(grown.size()) +
                                  " points; " + std::to_string(count) + " pores of " + std::to_string(n) +
                                  " points need " + std::to_string(slots));
    out.points = std::move(grown);
  } else {
    out.points.resize(slots);  // not zeroed: every slot is written on the thread that grows its fibre
  }
  if (options.spread.passes > 0 && !layered) {
    if (!pre_grown)
      parallel_for(count, exec.threads, [&](int i) {
        grow_fibre(tracks[pores.guide[i]], pores.positions[i], pores.lengths[i], extent[pores.guide[i]], options.wisp,
                   out.points.data() + n * i);
      });
    spread_fibres(out.points, n, options.spread, exec.threads, around.hair_region);
  }
  const bool fibres_ready = pre_grown || (options.spread.passes > 0 && !layered);
  std::vector<std::int8_t>* outside_volume = sides && cutting ? &sides->outside_volume : nullptr;
  std::vector<std::int8_t>* in_head = sides && out_of_head ? &sides->in_head : nullptr;
  if (sides) {
    sides->outside_volume.assign(outside_volume ? slots : 0, 0);
    sides->in_head.assign(in_head ? slots : 0, 0);
  }
  std::vector<std::uint32_t> kept(count, static_cast<std::uint32_t>(n));
  std::vector<char> cut(count, 0);
  std::vector<int> crossing(count, 0);
  std::vector<char> at_scalp(count, 0);
  ProgressCounter progress(exec.progress);
  parallel_for(count, exec.threads, [&](int i) {
    thread_local Scratch scratch;
    scratch.layout.resize(n);
    Vec3* points = out.points.data() + n * i;
    std::int8_t* head = in_head ? in_head->data() + n * i : nullptr;
    const Vec3* root_normal = pores.normals.empty() ? nullptr : &pores.normals[i];
    FibreAdjust place;
    if (layered)
      place = [&](Vec3* fibre, int m) {
        // Each point moves across the fibre as swept, its direction there the chord between its
        // swept neighbours; the moves are then smoothed along the fibre (kLayerMoveSmoothing
        // pass of ¼, ½, ¼), so that where the layer's depth turns between two stations, as in
        // a braid's lobes, the fibre turns smoothly rather than from station to station.
        thread_local std::vector<Vec3> moves;
        moves.assign(m, Vec3::Zero());
        for (int k = 2; k < m; ++k) {
          const Vec3 chord = (k + 1 < m ? fibre[k + 1] : fibre[k]) - fibre[k - 1];
          const double norm = chord.norm();
          const Vec3 along = norm > 0.0 ? Vec3(chord / norm) : Vec3::Zero();
          moves[k] = around.to_layer_depth(fibre[k], along, layer_depths[i], stations[k].w) - fibre[k];
        }
        smooth_along(moves, 2, kLayerMoveSmoothing);
        for (int k = 2; k < m; ++k) fibre[k] += moves[k];
      };
    const ChordsLeft left = fibre_kept_out(tracks[pores.guide[i]], pores.positions[i], pores.lengths[i],
                                           extent[pores.guide[i]], stations, out_of_head, root_normal, points,
                                           scratch.layout.data(), head, fibres_ready, layered ? &place : nullptr);
    // A chord the keep-out pass leaves through the scalp (where both its ends lie clear of the
    // head, as at the scalp's rim, it has nothing to move) ends the fibre before it: the hair
    // stops at the skin. One from the root cannot be cut away: it and the rest are counted.
    if (left.first >= 2) {
      kept[i] = static_cast<std::uint32_t>(left.first);
      cut[i] = true;
      at_scalp[i] = true;
    } else {
      crossing[i] = left.count;
    }
    if (cutting) {
      scratch.distances.resize(n);
      if (head) scratch.before_cut.assign(points, points + n);
      bool was_cut = false;
      double outside_length;
      kept[i] = static_cast<std::uint32_t>(cut_in_place(points, kept[i], scratch.distances.data(), volume,
                                                         options.cut_threshold, options.cut_tips, volume_quick, was_cut,
                                                         outside_length));
      cut[i] = cut[i] || was_cut;
      if (outside_volume)
        for (std::size_t k = 0; k < kept[i]; ++k) (*outside_volume)[n * i + k] = scratch.distances[k] > 0.0;
      if (head && was_cut)  // the side holds where the kept point is the point it was asked about
        for (std::size_t k = 0; k < kept[i]; ++k)
          if (points[k] != scratch.before_cut[k]) head[k] = -1;
    }
    progress.item_done();
  });

  out.offsets.resize(count + 1);
  for (int i = 0; i < count; ++i) out.offsets[i + 1] = out.offsets[i] + kept[i];
  if (out.offsets[count] != slots) {
    // Close up after cut fibres, fibre after fibre: each moves down, never onto one not yet moved.
    for (int i = 0; i < count; ++i) {
      const std::size_t from = n * i, to = out.offsets[i];
      if (from == to) continue;
      std::copy(out.points.begin() + from, out.points.begin() + from + kept[i], out.points.begin() + to);
      for (std::vector<std::int8_t>* v : {outside_volume, in_head})
        if (v) std::copy(v->begin() + from, v->begin() + from + kept[i], v->begin() + to);
    }
    out.points.resize(out.offsets[count]);
    for (std::vector<std::int8_t>* v : {outside_volume, in_head})
      if (v) v->resize(out.offsets[count]);
  }
  out.guide.assign(pores.guide.begin(), pores.guide.end());
  for (int i = 0; i < count; ++i)
    strands.cut_count += cut[i], strands.cut_at_scalp += at_scalp[i], strands.scalp_crossings += crossing[i];
  strands.cut = std::move(cut);
  return result;
}

}  // namespace hairfit
