// The scalp under any hair hull, however it overhangs, folds or lies in tubes: a level set of the
// scan's own signed distance (the first way, made concrete).
//
// With δ(x) the depth below the scan (its signed distance, positive inside: the hull and the bare
// skin together, signed by the scan's winding number) and T(x) the thickness the hair layer should
// have there — T·r(g) with g the distance from the hairline (along the hull's edges, relaxed) at
// x's closest point of the scan, 0 on the bare skin, and r(s) = sin(π/2·min(1, s/ramp)) — the
// scalp is the zero set of T − δ and the floor that closes the volume the zero set of
// T + T·r(3g) − δ (as deep as 2T away from the hairline, but leaving it three times as steeply).
// Both come from marching tetrahedra on the field's grid (marching_tetrahedra.h), so each is free
// of self-intersections, and since the floor's value exceeds the scalp's by T·r(3g) ≥ 0 they cannot
// cross where the sampled thickness is positive. Under the bare skin the thickness is 0, so each
// zero set continues as the skin there; each is clipped where T falls to ε (its value 1.5 voxels
// from the hairline) and its largest part kept. A strip joins the scalp to the hull's hairline,
// vertex for vertex, and the floor joins the scalp's end, so the two strips cannot cross. Where the
// scalp's strip crosses the hull (a noisy hull near its hairline), it is lowered there
// (level_set_strip.h: feet under the hairline). The scalp is then relaxed (relax(): the closest
// point's turns between hull and skin leave creases).
//
// A level set of a distance follows the scan at depth T: a bun thicker than 2T keeps an eroded core
// under it, braids and bows thinner than that leave no trace, and hair folding over the ears with
// air beneath it gets a scalp under the fold, joined to the hairline where the fold meets the skin.
#pragma once
#include <string>

#include "prepare/hair_region.h"
#include "prepare/scalp_offset.h"

namespace hairfit {

// The grid spacing the level set uses: options.voxel, or min(0.25, T / 6) cm when that is 0.
// 0.3 cm gives the sculpted busts' scalps as smooth (the same 95th percentile of mean curvature
// under the hair) in three quarters of the time, but their hair crosses more (flow crossing 0.11 →
// 0.18 on the ears and 0.14 → 0.21 on the tilted bust, means of three seeds), so it is not the default.
double level_set_voxel(const ScalpOptions& options);

// `skin`: the rest of the scan (clipped at the same hairline, f ≤ 0), in cm as the hull is. Throws
// InputError naming `file` when the options are out of range or the level set gives no disk
// under the hull (the message says what it found).
ScalpResult make_level_set_scalp(const Hull& hull, const Mesh& skin, const ScalpOptions& options,
                                 const std::string& file, int threads = 0);

}  // namespace hairfit
