// Sculpted busts that reproduce what real scans do to `hairfit prepare` and that a radial bust
// cannot: a bun that overhangs the nape, braids lying on the head as tubes, ribbon bows standing
// off the hair, hair folding down over the ears with air beneath, and a tilted head. Each is the
// zero set of an implicit function (negative inside) built on the procedural bust of bust.h (the
// same skull, neck and tapered hair layer, without its radial bumps), extracted by marching
// tetrahedra: a closed raw scan with the irregular triangles a scanner's mesher makes, hair
// painted kHairColor wherever the surface stands off the skin.
#pragma once
#include <string>
#include <vector>

#include "prepare/bust.h"

namespace hairfit {

enum class BustStyle { plain, bun, braids, bows, ears, tilted };

const std::vector<BustStyle>& all_bust_styles();
std::string bust_style_name(BustStyle style);  // "plain", "bun", …

// What a sculpted bust carries: any of the bun, the braids, the bows and the ear flaps at once,
// and the whole bust turned by `tilt` (about the head centre). BustStyle names one feature each.
struct SculptFeatures {
  bool bun = false, braids = false, bows = false, ears = false;
  Mat3 tilt = Mat3::Identity();
};
SculptFeatures sculpt_features(BustStyle style);

// The implicit function of the style's bust at p (cm, y up, face +z): negative inside, within a
// few percent of the signed distance near the surface.
double sculpted_bust_value(BustStyle style, const Vec3& p);
// Whether the surface point p is hair: farther than 0.04 cm off the bare skin (in the bust's own
// frame: a tilted bust is turned back first).
bool sculpted_bust_hair(BustStyle style, const Vec3& p);

// The bust sampled on a grid of `spacing` cm (BustScan::directions: unit position vectors).
BustScan make_sculpted_bust(BustStyle style, double spacing = 0.3);
BustScan make_sculpted_bust(const SculptFeatures& features, double spacing = 0.3);

}  // namespace hairfit
