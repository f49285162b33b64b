// The depth coordinate of a hair layer between the scalp and the hull, read from their two signed
// distance fields S (positive in front of the scalp) and V (negative inside the hull):
//
//   λ(p) = S(p) / (S(p) − V(p))   0 on the scalp, 1 on the hull, < 0 in the head, > 1 beyond the hull,
//   ∇λ = (S ∇V − V ∇S) / (S − V)²,
//
// defined wherever S − V > 0 (the two surfaces are not both at p). Where the surfaces are parallel
// at distance T, λ is the share of T a point lies above the scalp, and |∇λ| = 1/T.
#pragma once
#include "field/distance_field.h"

namespace hairfit {

constexpr int kLayerDepthSteps = 3;

struct LayerDepth {
  double value = 0.0;            // λ
  Vec3 gradient = Vec3::Zero();  // ∇λ (1/cm)
  double thickness = 0.0;        // S − V (cm): the layer's thickness through p where it is parallel
};

// λ and its gradient from the two fields' values and gradients; thickness ≤ 0 (and λ = 0, no
// gradient) where S − V ≤ 0 or is not finite.
LayerDepth layer_depth(const FieldValueGradient& scalp, const FieldValueGradient& volume);

// The point p, where the layer reads `at_p`, moved down ∇λ toward where λ = `target`: a fixed
// number of Newton steps (kLayerDepthSteps) on the interpolated fields, each at most one layer
// thickness long. A fixed count, with no test of convergence, keeps the result a continuous
// function of p, so that a fibre's length stays continuous in how far it reaches along its guide
// (the strands' length solve). Between parallel surfaces the first step is exact. p itself where
// the layer is not defined at p; the last point reached where a step would leave it.
// With a unit `along` (a fibre's direction at p), every step moves in the plane normal to it, down
// the part of ∇λ across the fibre: a point keeps its place along the hair and changes only its
// depth across it.
Vec3 to_layer_depth(const DistanceField& scalp, const DistanceField& volume, const Vec3& p, const LayerDepth& at_p,
                    double target, const Vec3* along = nullptr);

// The layer depth λ of a fibre given the share `share` of the layer's depth (0 scalp, 1 hull)
// where the layer is `thickness` thick, its wisp's fibres spread through no more than the top
// `spread` cm of it: 1 − (1 − share)·min(1, spread / thickness). A layer no deeper than `spread`
// (and a spread that is not positive and finite) gives the share itself; a deeper one is filled
// from the hull down, so that a fibre keeps as near the hull as it would in a layer `spread` thick.
double spread_layer_depth(double share, double thickness, double spread);

}  // namespace hairfit
