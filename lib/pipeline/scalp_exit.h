// How the strands stage keeps fibres out of the head: points moved out along the scalp field's
// gradient, and chords tested exactly against the scalp's triangles.
#pragma once
#include <limits>

#include "core/triangle_grid.h"
#include "field/distance_field.h"
#include "scalp/fall.h"
#include "strands/strands.h"

namespace hairfit {

// A point behind the scalp (or within kHeadExitClearance of it) moves along the field's gradient
// to kHeadExitClearance in front of it (up to four Newton steps on the interpolated field).
// With `scalp_triangles` (the scalp the field closes under its floor; `outward` turns its
// triangles' normals out of the head, ScalpChart::outward), chords are tested exactly wherever
// the field's lower bound on the distance at their ends does not rule a crossing out. Both must
// outlive the result. With `volume` (fibres held in the layer, strands.contain), where the layer
// in front of the scalp is thinner than the clearance a point stops nearer the scalp, where the
// layer holds it (at half or a quarter of the clearance), if it does anywhere. The chords' tests
// skip what `scalp_distance` (the closed head's distance field, which bounds the distance to the
// triangles) rules out; without it, what `scalp` does, which must then be that field.
HeadExit scalp_exit(const DistanceField& scalp, const TriangleGrid* scalp_triangles = nullptr, int outward = 1,
                    const DistanceField* volume = nullptr, const DistanceField* scalp_distance = nullptr);

// The clearance (cm) inside the volume that contained points move to.
constexpr double kVolumeClearance = 0.05;

// HeadExit::into_volume from the volume's distance field: a point outside it by less than `reach`
// (cm) moves along the field's gradient to kVolumeClearance inside (up to four Newton steps on
// the interpolated field); `volume` must outlive the result.
std::function<Vec3(const Vec3&)> into_volume(const DistanceField& volume, double reach);

// How far beyond the hull (cm) a fibre point is still moved into its layer depth: the move fades
// from full at the hull to none this far out, where the layer has ended.
constexpr double kLayerDepthReach = 1.0;

// How far below the scalp's rim (cm) a fibre point is still moved into its layer depth. The
// layer's depth λ is a depth across the hair where the layer lies over the scalp; below the rim,
// where the hair hangs, it runs along it (down to the floor of a closed hull), and a hanging
// wisp's fibres moved to their shares of it would be thrown across the hair mass.
constexpr double kLayerBelowRim = 2.0;

// StrandSurroundings::to_layer_depth from the two fields (field/layer_depth.h): p moves, across
// the fibre's unit direction `along`, to the layer depth λ(p) + w·(depth − λ(p)), with w the given
// weight faded by the smoothstep beyond the hull over kLayerDepthReach and below the scalp's rim
// (`rim`, RimHeights::below; none for empty heights) over kLayerBelowRim. Where the layer through
// p is deeper than `spread` cm, `depth` is a share of its top `spread` cm (spread_layer_depth;
// infinite: of the whole layer). Both fields must outlive the result.
std::function<Vec3(const Vec3& p, const Vec3& along, double depth, double weight)> layer_placement(
    const DistanceField& scalp, const DistanceField& volume, RimHeights rim,
    double spread = std::numeric_limits<double>::infinity());

}  // namespace hairfit
