// Hair that hangs (hair.tilt_toward = "hanging", issue 23). Where the hair layer goes on below a
// root for the hair's length (the curtain of a bob, the sides of short hair), a hair falls: it
// grows down along the skull, the paper's pre-guide bends its tip into the layer, and it ends
// where the layer below it ends. Elsewhere (a thin cap that ends at the hairline, the gathered
// hair of a ponytail) it grows toward the thicker layer as with "thicker". How much a root hangs
// is read off a probe from each scalp vertex:
//
//   the hang h: the path a falling hair takes from the root, 0.1 cm off the skin, stepping along
//   down projected onto the skin's level surface while within kHangHug of the skin (the hair lies
//   on the skull) and straight down beyond (it hangs free), for as long as it stays in the layer
//   (inside the hull's region and outside the head), at most the hair's length L;
//
//   for heavy hair (the rod under gravity) also the fall f: the same probe, but straight down
//   where the skin faces down, since a chain stays on a skull only while the skull carries it and
//   hangs free of one that turns under (the occiput over the neck), a shorter path than the skin's;
//
//   the weight φ = smoothstep(h / L): 1 where a hair's length of layer lies below the root, 0
//   where none does;
//
//   the length L − w·max(0, L − h), at least kShortestHangingHair, with w the larger of φ and how
//   far the root's growth points down: a hair that hangs, or grows down toward where the layer
//   ends (at the nape of a short cut), ends where the layer below it ends instead of turning back.
//   Heavy hair takes f for h here: it ends where the layer below its fall ends. Its weight φ and
//   growth still read h, which says whether the layer lies below a root at all (a fall that
//   leaves a thin layer beside the face at once does not mean the hair there stands up).
#pragma once
#include <functional>
#include <vector>

#include "scalp/chart.h"

namespace hairfit {

// How far off the skin the hang's probe starts (cm): inside a layer a few millimetres thin.
constexpr double kHangStart = 0.1;
// Within this distance of the skin (cm) the probe follows the skull (measured on the MakeHuman
// fixtures: 0.25, 0.5 and 1 cm, bench/results/thin_shells.md).
constexpr double kHangHug = 0.5;
// A root whose weight exceeds this hangs: its pre-guide is the paper's tip construction.
constexpr double kHangingPreguide = 0.65;
// No hair is made shorter than this (cm) for the layer ending below it.
constexpr double kShortestHangingHair = 1.0;

// What the probe reads: the signed distance from the skin (the scalp field, negative in the
// head) with its gradient, and whether a point lies in the hull's region (the volume field ≤ 0).
struct HangProbe {
  std::function<void(const Vec3& p, double& distance, Vec3& gradient)> skin;
  std::function<bool(const Vec3& p)> in_volume;
  Vec3 down = Vec3(0.0, -1.0, 0.0);  // unit
  double step = 0.1;                 // cm
  bool falls_free = false;           // the fall f: straight down where the skin faces down
};

// The hang h of a root at `root` with unit outward `normal`, up to `cap` (cm).
double hang_length(const HangProbe& probe, const Vec3& root, const Vec3& normal, double cap);

// The hang at every vertex of the scalp chart, up to `cap`, with the layer taken to end `margin`
// (cm, hair.hang_margin) sooner: probed up to cap + margin, less the margin, so that a layer
// holding cap + margin below a vertex still holds the whole cap.
std::vector<double> vertex_hangs(const ScalpChart& chart, const HangProbe& probe, double cap, int threads,
                                 double margin = 0.0);

// φ = smoothstep(h / L); 0 for L ≤ 0.
double hang_weight(double hang, double length);

// How far a growth direction points down at a root with unit `normal`: the cosine between its
// tangential part and the tangent toward down, times |down × normal| (0 at the crown), at least 0.
double downness(const Vec3& direction, const Vec3& normal, const Vec3& down);

// L − w·max(0, L − h) for a weight w ∈ [0, 1], at least min(L, kShortestHangingHair).
double hanging_length(double length, double hang, double weight);

// The hang at a point of the scalp: the vertices' hangs weighted by its barycentric coordinates.
double hang_at(const ScalpChart& chart, const std::vector<double>& hangs, const SurfacePoint& point);

}  // namespace hairfit
