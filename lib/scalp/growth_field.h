// The roots' growth field (issue 23): one smooth tangent field over the whole scalp, aligned with
// the tangent toward down (hair.tilt_toward = "down") or with the blend of the surface gradient of
// the hair layer's thickness and down ("thicker", the blend of growth_direction_toward_thicker),
// smoothed by scalp/direction_field.h over hair.flow_smoothing. Each root's growth direction is
// its normal tilted toward this field, so neighbouring roots grow alike and the guidance's noise
// (a thickness gradient differenced from a voxel field) is averaged away instead of becoming flow.
#pragma once
#include <vector>

#include "scalp/chart.h"
#include "scalp/direction_field.h"
#include "scalp/roots.h"

namespace hairfit {

// The unit tangent toward down at a point with this normal: down projected onto the tangent
// plane; where down is (nearly) parallel to the normal, −front projected; else any tangent.
Vec3 tangent_toward_down(const Vec3& normal, const Vec3& down, const Vec3& front);

// The normal rotated by `tilt_degrees` toward a unit tangent.
Vec3 tilted(const Vec3& normal, const Vec3& unit_tangent, double tilt_degrees);

// The tangent toward down scaled by |down × normal|: sure on the sides of the head, unsure at the
// crown, where down says nothing.
Vec3 down_guidance(const Vec3& normal, const Vec3& down, const Vec3& front);

// The tangent a root aims at, before smoothing, for TiltToward::thicker (and hanging, before its
// blend): w·ĝ + (1 − w)·t_down with g the tangential part of the thickness gradient and
// w = min(1, |g| / kFlatLayerGradient); its length (≤ 1) is how sure it is. For TiltToward::down:
// down_guidance.
Vec3 growth_guidance(const Vec3& normal, const Vec3& thickness_gradient, const RootOptions& options,
                     const Vec3& down, const Vec3& front);

// The layer's thickness at each scalp vertex.
std::vector<double> vertex_thickness(const ScalpChart& chart, const ThicknessField& thickness, int threads);

// How far off the skin and beyond the hairline the hull is probed for whether the layer goes on (cm).
constexpr double kLayerEndProbe = 0.5;

// Per scalp vertex, the distance along the scalp's edges (cm) to where the hair layer ends: a
// vertex the hull does not cover (thickness ≤ 0), or a hairline vertex beyond which the hull does
// not go on (the field reads outside the hull `probe` beyond it, a quarter of that off the skin).
// Infinite where no end is reachable. `thickness` holds the field's value at each vertex.
// With `from_rim_only`, only the ends joined to the scalp's rim through ends count.
std::vector<double> layer_end_distance(const ScalpChart& chart, const std::vector<double>& thickness,
                                       const ThicknessField& field, double probe, bool from_rim_only = false);

// With FlowModel::relief, inputs.grain (one line per vertex, scalp/relief.h) then takes over by
// its anisotropy, turned to agree with the guidance below.
// Per scalp vertex: growth_guidance with the thickness gradient of the piecewise-linear thickness
// the field gives at the vertices (per triangle, area-weighted at each vertex); with "hanging",
// blended toward down_guidance by the vertex's hang weight φ (scalp/hanging.h, against the longest
// hair); with "thicker" or "hanging", blended toward the direction away from the layer's end (the gradient of layer_end_distance),
// turned clockwise (seen from outside) by options.swirl, by the smoothstep of 1 − distance / hair
// length, since a hair needs its length of layer ahead of it (with "hanging", times 1 − φ: a hair
// that has its length of layer below it falls instead); then the smoothest field aligned with it.
DirectionField make_growth_field(const ScalpChart& chart, const RootInputs& inputs, const RootOptions& options,
                                 const Exec& exec = {});

// The declared style, blended into per-vertex guidance last: a crown whorl at the chart point
// options.whorl (hair grows away from it, turned clockwise by options.swirl) and a parting along
// the chart segment from options.parting to the whorl (hair grows away from it on either side),
// each sure by exp(−d²/r²) at distance d (cm) over its radius; a radius of 0 declares none.
void add_declared_style(const ScalpChart& chart, const RootOptions& options, std::vector<Vec3>& guidance);

}  // namespace hairfit
