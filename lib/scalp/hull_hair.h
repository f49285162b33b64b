// Hair from the hull (issue 47): with no hair length or tilt in the scene, the hull decides per
// scalp vertex whether the hair hangs and how long it is, from the way the hair falls through the
// region the hull and the skin enclose (scalp/fall.h). Where the layer carries that way on below
// the scalp's rim (shoulder-length hulls, a ponytail, a curtain), the hair hangs, and is as long
// as the way; where the way ends at or above the rim (a cap that ends at the hairline) the hair
// keeps the length and tilt of hair that suits its shell (scalp/shell_hair.h). Between the two,
// over the first kHangRamp of the way below the rim, it blends smoothly, so that a region's hair
// turns from lying to hanging without a seam.
#pragma once
#include <string>
#include <vector>

#include "scalp/fall.h"
#include "scalp/roots.h"

namespace hairfit {

// cm of the fall below the rim over which hair turns from lying to hanging (smoothstep). MakeHuman
// bob01 / braid01 at 600 guides, coverage: 0.907 / 0.965 over 4 cm, 0.921 / 0.980 over 8 cm.
constexpr double kHangRamp = 8.0;
// cm: the longest fall followed (four times a waist-length hair).
constexpr double kLongestFall = 200.0;
// cm the tip of a hanging hair stays short of where its fall ends (the layer's floor), so that
// the tip lies in the layer; and the shortest hair that comes of it.
constexpr double kFallTipMargin = 1.0;
constexpr double kShortestHullHair = 1.0;
// cm a fibre of hair from the hull may run past the tip of its guide (scalp/roots.h make_scalp_roots).
constexpr double kFibrePastGuide = 1.0;

struct HullHair {
  std::vector<double> hang_weights;  // φ ∈ [0, 1] per scalp vertex
  std::vector<double> lengths;       // cm per scalp vertex
  bool hangs = false;                // some vertex has φ > 0
};

// φ = smoothstep(below_rim / kHangRamp), ℓ = max(min(kShortestHullHair, `lying_length`),
// φ·(fall length − kFallTipMargin) + (1 − φ)·`lying_length`), per fall: lying hair shorter than
// kShortestHullHair (combed stubble at a hairline) keeps its length.
HullHair hull_hair(const std::vector<Fall>& falls, double lying_length);
// The same with a lying length per fall (per scalp vertex).
HullHair hull_hair(const std::vector<Fall>& falls, const std::vector<double>& lying_lengths);

// cm a combed hair's tip stays short of where the layer ahead of it ends (the carved hulls of
// reference/carved_hull.h, flow crossing: 0.14–0.20 at 1 cm, 0.14–0.18 at 2 cm, 0.15–0.19 at 3 cm),
// and the longest such hair.
constexpr double kCombedTipMargin = 2.0;
constexpr double kLongestCombedHair = 40.0;
// Nearer the end than kCombedTipMargin + kShortestHullHair (3 cm), a combed hair runs this share
// of the way there instead (the two meet at 3 cm), and is no shorter than kShortestCombedHair:
// the hair at a hairline where the layer thins out is stubble that ends before the layer does.
// Held at kShortestHullHair, the 40 % of roots within 3 cm of the carved hulls' hairlines grew
// 1 cm hairs that ran out of the layer and were bent back into it, across each other: 95 % of
// the guides' flow crossing (docs/results/carved-flow.md).
constexpr double kCombedShareNearEnd = 1.0 / 3.0;
constexpr double kShortestCombedHair = 0.15;

// Hair combed from the crown (hair.comb = "from_crown"): per scalp vertex, as long as the layer
// ahead of it, the distance d along the scalp to where the layer ends (layer_end_distance, ends
// joined to the rim only), less kCombedTipMargin, or kCombedShareNearEnd·d where that is longer,
// in [kShortestCombedHair, kLongestCombedHair]; `fallback` where the layer does not end.
std::vector<double> combed_lengths(const ScalpChart& chart, const ThicknessField& thickness, double fallback,
                                   int threads = 1);

// hair.comb = "auto": which way hair that suits its shell grows along the growth field, from the
// hull. A layer that thickens toward the crown over most of the scalp and does not carry the hair
// on below the rim is a carved cap (a sculpture's hair, cut from a scan): grown toward the thicker
// layer (the paper's rule) all its hair runs up into the crown and meets there head on, so it is
// combed from the crown instead. The share is of the scalp's area (a third of each triangle to
// each corner) where the layer's thickness gradient along the scalp points up, against the
// tangent toward down; hanging is φ > ½ (hull_hair). Measured on every hull the project has
// (docs/results/carved-flow.md): the seven carved hulls 0.905–0.958 thickening up, 0 hanging;
// the MakeHuman shells and long hulls 0.19–0.72, the grooved fixture 0.49; the straight bag 0.83,
// all of it hanging.
constexpr double kCombedThickeningShare = 0.8;
constexpr double kCombedHangingShare = 0.25;
struct CombChoice {
  Comb comb = Comb::into_layer;
  double thickening_up = 0.0;  // the share of the scalp's area where the layer thickens upward
  double hanging = 0.0;        // the share of the scalp's area whose hair hangs (φ > ½)
};
CombChoice comb_from_hull(const ScalpChart& chart, const ThicknessField& thickness, const std::vector<Fall>& falls);

// What a region of the scalp derived from the hull: its roots' share that hangs (φ > ½), and the
// median length and median fall below the rim of its vertices.
struct HullHairRegion {
  std::string name;  // "front", "left", "back", "right"
  int vertices = 0;
  double hanging_share = 0.0;
  double median_length = 0.0;     // cm
  double median_below_rim = 0.0;  // cm
};

// The four quarters of the scalp seen from above, about the hairline's centre, `front` and the
// viewer's left and right as the head sees them (left = up × front).
std::vector<HullHairRegion> hull_hair_regions(const ScalpChart& chart, const std::vector<Fall>& falls,
                                              const HullHair& hair);

}  // namespace hairfit
