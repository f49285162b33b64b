// The scene of the round trip against reference hair (issue 47): the scalp and the hull made from
// the reference, the directions, and the two keys a new user sets (guides and hairs per cm²);
// every hair key at its default, so the run shows what the method makes of the hull alone. The
// strands are written as cyHair (strands.hair) for the comparison; no pictures.
#pragma once
#include <cstdint>
#include <string>

#include "core/types.h"

namespace hairfit {

struct RoundTripScene {
  std::string scalp = "scalp.obj", volume = "hull.obj";  // paths from the scene's folder; meshes in cm
  Vec3 down = Vec3(0, -1, 0), front = Vec3(0, 0, 1);
  int guides = 600;
  double density = 50.0;  // hairs per cm²
  std::int64_t seed = 1;
};

std::string round_trip_scene_text(const RoundTripScene& scene);

}  // namespace hairfit
