#include "field/layer_depth.h"

#include <algorithm>
#include <cmath>

namespace hairfit {

LayerDepth layer_depth(const FieldValueGradient& s, const FieldValueGradient& v) {
  LayerDepth out;
  const double thickness = s.value - v.value;
  if (!(thickness > 0.0) || !std::isfinite(thickness)) return out;
  out.thickness = thickness;
  out.value = s.value / thickness;
  out.gradient = (s.value * v.gradient - v.value * s.gradient) / (thickness * thickness);
  return out;
}

Vec3 to_layer_depth(const DistanceField& scalp, const DistanceField& volume, const Vec3& p, const LayerDepth& at_p,
                    double target, const Vec3* along) {
  Vec3 q = p;
  for (int step = 0; step < kLayerDepthSteps; ++step) {
    const LayerDepth d = step == 0 ? at_p : layer_depth(scalp.value_and_gradient(q), volume.value_and_gradient(q));
    const Vec3 g = along ? Vec3(d.gradient - d.gradient.dot(*along) * *along) : d.gradient;
    const double g2 = g.squaredNorm();
    if (!(d.thickness > 0.0) || !(g2 > 0.0) || !std::isfinite(g2)) return q;
    Vec3 move = ((target - d.value) / g2) * g;
    const double length = move.norm();
    if (length > d.thickness) move *= d.thickness / length;  // never more than a layer at once
    const Vec3 next = q + move;
    if (!next.allFinite()) return q;
    q = next;
  }
  return q;
}

double spread_layer_depth(double share, double thickness, double spread) {
  if (!(spread > 0.0) || !std::isfinite(spread) || !(thickness > spread)) return share;
  return 1.0 - (1.0 - share) * (spread / thickness);
}

}  // namespace hairfit
