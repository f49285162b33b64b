#include "scalp/fall.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/parallel.h"
#include "scalp/growth_field.h"
#include "scalp/hanging.h"

namespace hairfit {

namespace {

constexpr double kTwoPi = 2.0 * M_PI;

double bin_angle(int k) { return (k + 0.5) * kTwoPi / kRimBins; }

int angle_bin(double angle) {
  const double a = angle - kTwoPi * std::floor(angle / kTwoPi);
  return std::min(kRimBins - 1, static_cast<int>(a * kRimBins / kTwoPi));
}

}  // namespace

RimHeights rim_heights(const ScalpChart& ch) {
  RimHeights r;
  r.up = -ch.down.normalized();
  r.e1 = r.up.unitOrthogonal();
  r.e2 = r.up.cross(r.e1);
  for (int v : ch.boundary) r.centre += ch.mesh.positions[v];
  if (!ch.boundary.empty()) r.centre /= static_cast<double>(ch.boundary.size());
  const double none = std::numeric_limits<double>::infinity();
  r.heights.assign(kRimBins, none);
  const int n = static_cast<int>(ch.boundary.size());
  for (int k = 0; k < n; ++k) {
    const Vec3 a = ch.mesh.positions[ch.boundary[k]] - r.centre, b = ch.mesh.positions[ch.boundary[(k + 1) % n]] - r.centre;
    const double ta = std::atan2(a.dot(r.e2), a.dot(r.e1)), ha = a.dot(r.up), hb = b.dot(r.up);
    double span = std::atan2(b.dot(r.e2), b.dot(r.e1)) - ta;  // the shorter way round
    if (span > M_PI) span -= kTwoPi;
    if (span < -M_PI) span += kTwoPi;
    r.heights[angle_bin(ta)] = std::min(r.heights[angle_bin(ta)], ha);
    // Every bin whose centre the edge passes: its height interpolated in angle.
    const double lo = std::min(ta, ta + span), hi = std::max(ta, ta + span);
    const int first = static_cast<int>(std::ceil(lo * kRimBins / kTwoPi - 0.5));
    const int last = static_cast<int>(std::floor(hi * kRimBins / kTwoPi - 0.5));
    for (int j = first; j <= last; ++j) {
      const double t = span != 0.0 ? (bin_angle(j) - ta) / span : 0.0;
      const int bin = ((j % kRimBins) + kRimBins) % kRimBins;
      r.heights[bin] = std::min(r.heights[bin], ha + std::clamp(t, 0.0, 1.0) * (hb - ha));
    }
  }
  // Directions the hairline never passes (a rim that does not go round the axis) take the
  // nearest bin's height that it does, the lower one at a tie.
  const std::vector<double> filled = r.heights;
  for (int k = 0; k < kRimBins; ++k) {
    if (std::isfinite(filled[k])) continue;
    for (int d = 1; d <= kRimBins / 2; ++d) {
      const double lower = filled[(k + d) % kRimBins], upper = filled[(k - d + kRimBins) % kRimBins];
      if (std::isfinite(lower) || std::isfinite(upper)) {
        r.heights[k] = std::min(lower, upper);
        break;
      }
    }
  }
  return r;
}

double RimHeights::below(const Vec3& p) const {
  const Vec3 q = p - centre;
  if (heights.empty()) return -std::numeric_limits<double>::infinity();
  return heights[angle_bin(std::atan2(q.dot(e2), q.dot(e1)))] - q.dot(up);
}

namespace {

struct Sample {
  double skin = 0.0, hull = 0.0;
  Vec3 skin_gradient = Vec3::Zero(), hull_gradient = Vec3::Zero();
  bool inside() const { return skin >= 0.0 && hull <= 0.0; }  // false where a field says NaN
};

Sample sample(const FallRegion& r, const Vec3& p) {
  Sample s;
  r.skin(p, s.skin, s.skin_gradient);
  r.hull(p, s.hull, s.hull_gradient);
  return s;
}

// The unit normal out of the region through the surface that s lies beyond (zero if none or if
// its gradient vanishes), and by how much it lies beyond.
Vec3 crossed(const Sample& s, double& excess) {
  Vec3 n = Vec3::Zero();
  excess = 0.0;
  if (!(s.skin >= 0.0)) {
    n = -s.skin_gradient, excess = -s.skin;
  } else if (!(s.hull <= 0.0)) {
    n = s.hull_gradient, excess = s.hull;
  }
  const double g = n.norm();
  return g > 1e-9 && std::isfinite(excess) ? Vec3(n / g) : Vec3::Zero();
}

bool crossed_skin(const Sample& s) { return !(s.skin >= 0.0); }

// The length of the segment a → b that lies below the rim, the rim's height taken as linear
// along it (exact within one of the rim's bins).
double length_below(const RimHeights& rim, const Vec3& a, const Vec3& b) {
  const double ba = rim.below(a), bb = rim.below(b), length = (b - a).norm();
  if (ba > 0.0 && bb > 0.0) return length;
  if (!(ba > 0.0) && !(bb > 0.0)) return 0.0;
  return length * std::max(ba, bb) / std::fabs(bb - ba);
}

constexpr int kExitBisections = 20;  // the last step's exit, to 2⁻²⁰ of a step

// How much deeper than `target` below the hull s lies (cm; 0 without a target).
double depth_miss(const Sample& s, double target) {
  return std::isfinite(target) ? -s.hull - target * std::max(0.0, s.skin - s.hull) : 0.0;
}

// The way the bead heads from s: down, pulled toward the depth `target` below the hull along the
// hull field's gradient by miss/kFallDepthReach (at most 1). With `level`, the pull does not lift
// the bead: only its level part acts (fall_from asks for that first below a head closed by its
// floor, where the layer's depth runs up to that floor, along the hair, not across it; over the
// crown it keeps the bead on the skin until its way turns down). Unit.
Vec3 heading(const Sample& s, const Vec3& down, bool level, double target) {
  const double g = s.hull_gradient.norm();
  if (!std::isfinite(target) || !(g > 1e-12)) return down;
  const double pull = std::clamp(depth_miss(s, target) / kFallDepthReach, -1.0, 1.0);
  Vec3 toward = pull * s.hull_gradient / g;
  if (level && toward.dot(down) < 0.0) toward -= toward.dot(down) * down;
  const Vec3 w = down + toward;
  return w.norm() > 1e-9 ? Vec3(w.normalized()) : down;
}

// One step of the bead from p (inside, sample s) heading w, sliding where it would leave the
// region: along the surface the step crosses, then, if the slide crosses another (the crease
// where a thin layer's skin and hull meet), along the line both leave open. Returns whether it
// moved, and then q and its sample.
bool slide_step(const FallRegion& region, const Vec3& p, const Vec3& w, double h, bool leaning, Vec3& q, Sample& t) {
  q = p + h * w;
  t = sample(region, q);
  if (t.inside()) return true;
  double excess = 0.0;
  const Vec3 n1 = crossed(t, excess);
  if (n1.isZero(0.0)) return false;
  // The skin carries the hair down a slope as shallow as kFallSlope; the hull only guides it
  // down a wall steeper than kHullWallSlope, and where it turns flatter the hair ends on it.
  const double least = crossed_skin(t) ? kFallSlope : kHullWallSlope;
  Vec3 d = w - std::max(0.0, w.dot(n1)) * n1;
  for (int slide = 0; slide < 2; ++slide) {
    if (d.dot(region.down) < least * d.norm() || d.norm() < least) {
      if (!leaning) return false;  // resting on a floor
      d = tangent_toward_down(-n1, region.down, region.front);  // the crown's lean
    }
    q = p + h * d.normalized();
    t = sample(region, q);
    if (t.inside()) return true;
    const Vec3 n = crossed(t, excess);  // pulled back inside the surface it leaves, by the clearance
    if (n.isZero(0.0)) return false;
    if (excess < h) {
      const Vec3 back = q - (excess + kFallClearance) * n;
      const Sample b = sample(region, back);
      if (b.inside()) {
        q = back, t = b;
        return true;
      }
    }
    const Vec3 along = n1.cross(n);
    if (slide == 1 || !(along.norm() > 1e-6)) return false;
    d = along.normalized().dot(region.down) * along.normalized();  // down along the crease
  }
  return false;
}

}  // namespace

Fall fall_from(const FallRegion& region, const RimHeights& rim, const Vec3& root, const Vec3& normal, double cap,
               double target, bool keep_nodes) {
  Fall f;
  if (!(cap > 0.0) || !(region.step > 0.0)) return f;
  Vec3 p = root + kHangStart * normal;
  Sample s = sample(region, p);
  if (!s.inside()) return f;
  if (keep_nodes) f.nodes.push_back(p);
  const Vec3& down = region.down;
  // A kept step moves the bead at least a quarter step, so the way ends within this many.
  const long steps = static_cast<long>(std::ceil(4.0 * cap / region.step)) + 4;
  // Where it last fell: a way that has not gone on down at the least slope, kFallSlope, over
  // kFallStall rests there. In the bowl at the bottom of a bag-shaped hull the bead, pulled toward
  // its depth, can wander round for many centimetres while it still finds ever slightly lower
  // points; the hair ends where it reached the bottom, not at the end of that wander. The crown's
  // lean, however flat, counts as falling.
  double lowest = p.dot(down), length_at_lowest = 0.0, below_at_lowest = 0.0;
  std::size_t nodes_at_lowest = f.nodes.size();
  for (long k = 0; k < steps && f.length < cap; ++k) {
    if (f.length > kCrownLean && f.length - length_at_lowest > kFallStall) {
      f.length = length_at_lowest, f.below_rim = below_at_lowest;
      if (keep_nodes) f.nodes.resize(nodes_at_lowest);
      return f;
    }
    const double h = std::min(region.step, cap - f.length);
    const bool leaning = f.length < kCrownLean;
    // It must get on: down by at least half the least slope, or nearer its depth. Where the pull
    // may not lift the bead (below a head closed by its floor) and the level pull leaves it
    // resting, the whole pull is tried: a ledge of a braid's lobes is got round, not rested on;
    // the wander that lifting starts in a bowl ends by the rest rule above.
    Vec3 w, q;
    Sample t;
    bool moved = false;
    for (const bool level : {region.floor_past_hairline, false}) {
      w = heading(s, down, level, target);
      moved = slide_step(region, p, w, h, leaning, q, t);
      if (moved) {
        const double miss = std::fabs(depth_miss(s, target)), next_miss = std::fabs(depth_miss(t, target));
        moved = (q - p).norm() >= 0.25 * h &&
                (leaning || (q - p).dot(down) >= 0.5 * kFallSlope * h || next_miss < miss - kFallDepthProgress);
      }
      if (moved || !level) break;
    }
    if (!moved) {
      // Falling off the layer's edge or resting on its floor: where the heading leaves it.
      double in = 0.0, out = h;
      for (int b = 0; b < kExitBisections; ++b) {
        const double mid = 0.5 * (in + out);
        (sample(region, p + mid * w).inside() ? in : out) = mid;
      }
      f.below_rim += length_below(rim, p, p + in * w);
      f.length += in;
      if (keep_nodes && in > 0.0) f.nodes.push_back(p + in * w);
      break;
    }
    const double moved_by = (q - p).norm();
    f.length += moved_by;
    f.below_rim += length_below(rim, p, q);
    p = q, s = t;
    if (keep_nodes) f.nodes.push_back(p);
    if (leaning || p.dot(down) > lowest + kFallSlope * (f.length - length_at_lowest))
      lowest = p.dot(down), length_at_lowest = f.length, below_at_lowest = f.below_rim, nodes_at_lowest = f.nodes.size();
  }
  f.length = std::min(f.length, cap);
  f.below_rim = std::min(f.below_rim, f.length);
  return f;
}

std::vector<Fall> vertex_falls(const ScalpChart& chart, const FallRegion& region, double cap,
                               const std::function<double(const Vec3&)>& target, int threads) {
  const RimHeights rim = rim_heights(chart);
  const int n = static_cast<int>(chart.mesh.positions.size());
  std::vector<Fall> falls(n);
  parallel_for(n, threads, [&](int v) {
    const Vec3& root = chart.mesh.positions[v];
    falls[v] = fall_from(region, rim, root, chart.vertex_normals[v], cap, target ? target(root) : kNoDepth);
  });
  return falls;
}

}  // namespace hairfit
