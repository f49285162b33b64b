// The skin beyond the scalp's hairline (fields.skin_beyond_hairline = "shell", issue 23).
//
// The scalp's field knows the head as the scalp closed by a floor across its hairline
// (closed_head). A hull that goes on past the hairline (the sides and the nape of short hair, a
// bob's curtain) then encloses, beyond the floor, the ears, the neck and the face as if they were
// hair layer, and hair sinks into them. A hair shell follows the skin at about the offset it has
// at the hairline, so beyond the floor the skin is taken to lie the hairline's layer thickness T
// under the hull:
//
//   skin(p) = min( S(p), max( T(p) + V(p), −B(p) ) )
//
// S the closed head's field (positive in front of the scalp), V the volume's (negative inside the
// hull's region), B the signed distance beyond the floor's plane (positive beyond it, the side
// away from the scalp), T(p) the layer's thickness at the hairline near p. In solids: the head,
// together with what lies beyond the floor deeper than T inside the hull's region. Where the
// floor's plane lies farther from p than the scalp (everywhere in the layer but by the hairline)
// the skin is S; beyond the floor it is T + V, the hull's offset; where the hull's region does not
// reach past the hairline nothing changes. The two solids meet at the floor, inside the union,
// where the value is near zero but negative: the sign, which the stages read, is the union's.
// (Letting the solid beyond the floor begin 1 cm inside the head instead thins the layer above
// the hairline wherever T is below the local thickness: bob01's guides crossed at 0.10–0.11
// instead of 0.07, bench/results/thin_shells.md.)
//
// T(p): the thickness −V at each hairline vertex (0 where the hull misses the hairline), averaged
// with Gaussian weights of the distance from p (σ = kHairlineReach), at least kThinnestLayer.
#pragma once
#include "core/mesh.h"
#include "field/distance_field.h"

namespace hairfit {

// The Gaussian reach (cm) over which hairline vertices lend p their layer's thickness.
constexpr double kHairlineReach = 2.0;
// The thinnest layer (cm) taken to lie under the hull beyond the hairline.
constexpr double kThinnestLayer = 0.25;

// The skin field on a grid of the volume field's spacing covering both fields' grids. `scalp` is
// the head's mesh as the scalp field was built from (a disk: its one boundary loop is the
// hairline). The result is a signed implicit function, not a distance: its samples carry no band
// of exact distances, so exact tests against the scalp read no bound from it. `threads` changes
// only the speed.
struct SkinBeyondHairline {
  DistanceField field;
  double hairline_thickness = 0.0;  // cm: the median of the thickness at the hairline's vertices
};
SkinBeyondHairline skin_beyond_hairline(const Mesh& scalp, const DistanceField& scalp_field,
                                        const DistanceField& volume_field, int threads);

}  // namespace hairfit
