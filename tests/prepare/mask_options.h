// The options a prepare test uses for a scan painted as a user paints it: the hair selected by
// the mask colour (kHairColor) of the procedural busts, on 2 threads.
#pragma once
#include "prepare/bust.h"
#include "prepare/prepare.h"

namespace hairfit::testing {

inline PrepareOptions mask_options() {
  PrepareOptions o;
  o.selection.kind = HairSelection::Kind::mask;
  o.selection.color = Vec3(kHairColor[0], kHairColor[1], kHairColor[2]);
  o.threads = 2;
  return o;
}

}  // namespace hairfit::testing
