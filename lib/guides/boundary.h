// The acceptable region (paper §3): outside the scalp and inside the hair volume, as seen through
// the two distance fields (negative behind each oriented surface, so the head is behind the scalp
// and the hair is behind the volume boundary).
#pragma once
#include <memory>

#include "field/distance_field.h"

namespace hairfit {

// Shares the two fields, so a boundary never outlives them.
struct Boundary {
  std::shared_ptr<const DistanceField> scalp;
  std::shared_ptr<const DistanceField> volume;
  // Whether the head's skin past the scalp's hairline is the floor that closes it
  // (fields.skin_beyond_hairline = "floor"), so that below the head the layer's depth runs up to
  // that floor, along hanging hair; false where the skin goes on under the hull as a shell.
  bool floor_past_hairline = true;

  // How far a point lies outside the acceptable region through each surface, cm: positive outside
  // (inside the head / outside the volume), negative inside.
  double beyond_scalp(const Vec3& p) const { return -scalp->value(p); }
  double beyond_volume(const Vec3& p) const { return volume->value(p); }
  bool acceptable(const Vec3& p) const { return beyond_scalp(p) <= 0.0 && beyond_volume(p) <= 0.0; }
};

}  // namespace hairfit
