#include "pipeline/scalp_exit.h"

#include <limits>

#include "core/smoothstep.h"
#include "field/layer_depth.h"

namespace hairfit {

namespace {

// Where the layer is thinner than kHeadExitClearance, the nearer levels a point moved out of the
// head may take instead (cm): no nearer than a chord of 0.7 cm sags over a head of 5 cm radius.
constexpr double kThinLayerLevels[] = {0.025, 0.0125};

// The repair's test counts chords that pass within this much (barycentric) of a triangle, or end
// within this share of their length of it, as crossing it, so that a chord it leaves is clear of
// the scalp by more than round-off: the exact count then finds it clear too, also after the
// length solve shortens its last chord. A chord from a root, which lies on the scalp, meets it
// there: only what it meets beyond this share of its length from the root counts.
constexpr double kChordSlack = 1e-6;

// p moved along the field's gradient until the field reads `level` there, or within 10 % of it on
// the side `sense` (+1: above, −1: below) points to: up to four Newton steps.
Vec3 to_level(const DistanceField& field, const Vec3& p, double level, double sense) {
  Vec3 q = p;
  for (int step = 0; step < 4; ++step) {
    const FieldValueGradient vg = field.value_and_gradient(q);
    const double g2 = vg.gradient.squaredNorm();
    if (sense * (vg.value - level) >= -0.1 * std::abs(level) || !(g2 > 1e-12)) break;
    q -= (vg.value - level) / g2 * vg.gradient;
  }
  return q;
}

}  // namespace

std::function<Vec3(const Vec3&)> into_volume(const DistanceField& volume, double reach) {
  return [&volume, reach](const Vec3& p) {
    if (volume.side(p) < 0) return p;
    const double value = volume.value(p);
    if (!(value > 0.0) || value > reach) return p;
    return to_level(volume, p, -kVolumeClearance, -1.0);
  };
}

std::function<Vec3(const Vec3&, const Vec3&, double, double)> layer_placement(const DistanceField& scalp,
                                                                             const DistanceField& volume,
                                                                             RimHeights rim, double spread) {
  return [&scalp, &volume, rim = std::move(rim), spread](const Vec3& p, const Vec3& along, double depth, double weight) {
    const FieldValueGradient s = scalp.value_and_gradient(p), v = volume.value_and_gradient(p);
    const LayerDepth here = layer_depth(s, v);
    if (!(here.thickness > 0.0)) return p;
    if (v.value > 0.0) weight *= 1.0 - smoothstep(v.value / kLayerDepthReach);
    weight *= 1.0 - smoothstep(rim.below(p) / kLayerBelowRim);
    if (!(weight > 0.0)) return p;
    depth = spread_layer_depth(depth, here.thickness, spread);
    return to_layer_depth(scalp, volume, p, here, here.value + weight * (depth - here.value), &along);
  };
}

// The clearance (0.5 mm) is the sagitta of a 2 cm chord over a head of 10 cm radius: a fibre
// lying along the scalp has its points that far out, so the straight segments between them
// seldom dip under it. Most points are well in front of the scalp, which the field's side() tells
// without interpolating (reported as +infinity).
HeadExit scalp_exit(const DistanceField& scalp, const TriangleGrid* scalp_triangles, int outward,
                    const DistanceField* volume, const DistanceField* scalp_distance) {
  HeadExit exit = [&scalp, volume](const Vec3& p, double& value_at_p) {
    if (scalp.side(p) > 0) {
      value_at_p = std::numeric_limits<double>::infinity();
      return p;
    }
    value_at_p = scalp.value(p);  // = value_and_gradient(p).value; the gradient only when it is near
    if (!(value_at_p < kHeadExitClearance)) return p;
    const Vec3 out = to_level(scalp, p, kHeadExitClearance, 1.0);
    if (!volume || !(volume->value(out) > 0.0)) return out;
    // The layer in front of the scalp is thinner than the clearance here: nearer the scalp, where
    // the layer holds the point, if it does so within kThinLayerLevels.
    for (double level : kThinLayerLevels) {
      if (value_at_p >= level) {  // never moved inward: p itself, and no lower level does better
        if (!(volume->value(p) > 0.0)) return p;
        break;
      }
      const Vec3 q = to_level(scalp, p, level, 1.0);
      if (!(volume->value(q) > 0.0)) return q;
    }
    return out;
  };
  if (scalp_triangles) {
    const DistanceField& bound = scalp_distance ? *scalp_distance : scalp;
    exit.clearance = [&bound](const Vec3& p) { return bound.distance_lower_bound(p); };
    exit.chord_crossing = [scalp_triangles, outward](const Vec3& a, const Vec3& b, bool from_root, ChordCrossing& first) {
      const SegmentHit hit =
          scalp_triangles->first_crossing(a, b, kChordSlack, from_root ? kChordSlack : -kChordSlack, 1 + kChordSlack);
      if (!hit.found()) return false;
      first.t = hit.t;
      first.point = a + hit.t * (b - a);
      first.normal = outward * triangle_normal(scalp_triangles->mesh(), hit.triangle);
      return true;
    };
  }
  return exit;
}

}  // namespace hairfit
