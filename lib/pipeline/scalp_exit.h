// How the strands stage keeps fibres out of the head: points moved out along the scalp field's
// gradient, and chords tested exactly against the scalp's triangles.
#pragma once
#include "core/triangle_grid.h"
#include "field/distance_field.h"
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

// StrandSurroundings::to_layer_depth from the two fields (field/layer_depth.h): p moves to the
// layer depth λ(p) + w·(depth − λ(p)), with w the given weight faded by the smoothstep beyond the
// hull over kLayerDepthReach. Both fields must outlive the result.
std::function<Vec3(const Vec3&, double, double)> layer_placement(const DistanceField& scalp, const DistanceField& volume);

}  // namespace hairfit
