#include "field/layer_soup.h"

namespace hairfit {

Mesh hair_layer_soup(const Mesh& hull, const Mesh& scalp) {
  Mesh layer = hull;
  const Vec3i offset = Vec3i::Constant(static_cast<int>(hull.positions.size()));
  layer.positions.insert(layer.positions.end(), scalp.positions.begin(), scalp.positions.end());
  for (const Vec3i& t : scalp.triangles) layer.triangles.push_back(Vec3i(t[0], t[2], t[1]) + offset);
  return layer;
}

}  // namespace hairfit
