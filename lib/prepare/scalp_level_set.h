// The scalp under any hair hull, however it overhangs, folds or lies in tubes: a level set of the
// scan's own signed distance (the first way, made concrete).
//
// With δ(x) the depth below the scan (its signed distance, positive inside: the hull and the bare
// skin together) and T(x) the thickness the hair layer should have there — T·r(g) at the closest
// point of the hull, g its distance from the hairline along the hull's edges and r a ramp rising
// from 0 with slope π/(2·ramp), 0 at the closest point of the bare skin — the scalp is the zero set
// of T − δ and the floor that closes the volume the zero set of 2T − δ. Both come from marching
// tetrahedra on the field's grid (marching_tetrahedra.h), so each is free of self-intersections,
// and since 2T − δ − (T − δ) = T ≥ 0 they cannot cross where the sampled thickness is positive.
// Under the bare skin the thickness is 0, so each zero set continues as the skin there; each is
// clipped where T falls to ε (1.5 voxels up the ramp), its largest part kept, and a strip joins it
// to the hull's hairline, vertex for vertex.
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
double level_set_voxel(const ScalpOptions& options);

// `skin`: the rest of the scan (clipped at the same hairline, f ≤ 0), in cm as the hull is. Throws
// InputError naming `file` when the options are out of range or the level set gives no disk
// under the hull (the message says what it found).
ScalpResult make_level_set_scalp(const Hull& hull, const Mesh& skin, const ScalpOptions& options,
                                 const std::string& file, int threads = 0);

}  // namespace hairfit
