// Hair roots (pores), guide clusters and pre-guide roots on the scalp (paper §3.3, docs/design.md §3).
#pragma once
#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

#include "core/digest.h"
#include "core/exec.h"
#include "core/grey_map.h"
#include "scalp/chart.h"

namespace hairfit {


// Which way the normal tilts at a root: toward down (the scene's default); up the surface
// gradient of the hair layer's thickness, so hair at a thin hairline grows into the hair mass; or
// hanging: toward down where the layer below the root holds a hanging hair, toward the thicker
// layer elsewhere (scalp/hanging.h).
enum class TiltToward { down, thicker, hanging };

// Where the tangent a root tilts toward comes from: one smooth growth field over the scalp
// (scalp/growth_field.h), the same field steered by the hull's grain (relief, scalp/relief.h), or
// each root's own down or thickness gradient (local, the paper's rule, root by root).
enum class FlowModel { field, local, relief };
// Which way along the growth field's lines hair grows (hair.comb).
enum class Comb { into_layer, from_crown };

// The hair layer's thickness at a point (cm) and its gradient (world axes), for TiltToward::thicker:
// the pipeline passes −Φ_volume, the depth below the hair-volume boundary.
struct LayerThickness {
  double value = 0.0;
  Vec3 gradient = Vec3::Zero();
};
using ThicknessField = std::function<LayerThickness(const Vec3&)>;

// What the roots read besides the chart and their options: the grey maps the scene uses,
// addressed through the chart (chart_to_image; null = not used), and what the fields and the hull
// say about the hair layer.
struct RootInputs {
  std::shared_ptr<const GreyMap> density;  // × RootOptions::density; 0 (black) = no hair at all
  std::shared_ptr<const GreyMap> tilt;     // black → tilt_range[0], white → tilt_range[1]
  std::shared_ptr<const GreyMap> length;   // black → length_range[0], white → length_range[1]
  ThicknessField thickness;                // required with TiltToward::thicker and hanging
  std::vector<double> hangs;               // TiltToward::hanging: per scalp vertex, up to longest_hair (scalp/hanging.h)
  std::vector<double> falls;               // the same along the path heavy hair falls (HangProbe::falls_free), for
                                           // the hanging hair's length; empty: `hangs`
  std::vector<Vec3> grain;                 // FlowModel::relief: per scalp vertex (relief_grain)
  // Hair from the hull (scalp/hull_hair.h), per scalp vertex, both or neither: how much the hair
  // hangs, φ ∈ [0, 1], in place of hang_weight(hang, length), and its length (cm), in place of the
  // options' length and the hanging length.
  std::vector<double> vertex_hang_weights;
  std::vector<double> vertex_lengths;
  // Stubble from the hull: a root whose hair from the hull is shorter than `stubble_length` (cm,
  // guides/guide_solve.h, whose guides keep such hair straight at rest) is at most kStubbleShare of
  // how far its straight hair stays in the layer, `layer_run`(root, direction, reach), up to
  // `reach` (the pipeline's is exact_layer_run, pipeline/stage_options.h; null: no fit).
  std::function<double(const Vec3& root, const Vec3& direction, double reach)> layer_run;
  double stubble_length = 0.0;
};

// The share of its straight run in the layer a stubble keeps (RootInputs::layer_run), and the
// shortest stubble (a hair's width), where the root lies at the layer's very edge.
constexpr double kStubbleShare = 0.5;
constexpr double kShortestStubble = 0.01;
// A stubble of `length` (cm) whose straight hair stays `run` cm in the layer (RootInputs::layer_run
// with reach length / kStubbleShare): min(length, kStubbleShare·run), at least kShortestStubble.
double fitted_stubble(double length, double run);

struct RootOptions {
  double density = 200.0;                     // hairs per cm² of 3D scalp area (white density map)
  double tilt = 0.0;                          // degrees from the normal (toward tilt_toward), without tilt map
  TiltToward tilt_toward = TiltToward::down;
  FlowModel flow = FlowModel::local;
  Comb comb = Comb::into_layer;
  double flow_smoothing = 6.0;                // cm: the growth field averages its guidance over this
  double swirl = 0.0;                         // degrees: growth away from the layer's end turns clockwise by this
  Vec2 whorl = Vec2::Zero();                  // chart point of a declared crown whorl
  double whorl_radius = 0.0;                  // cm it reaches (0: no whorl)
  Vec2 parting = Vec2(0.0, 1.0);              // chart point where a declared parting starts (it runs to the whorl)
  double parting_radius = 0.0;                // cm it reaches (0: no parting)
  std::array<double, 2> tilt_range{0.0, 90.0};  // degrees, tilt map black → white
  double length = 25.0;                       // cm, without length map
  std::array<double, 2> length_range{15.0, 35.0};  // cm, length map black → white
  double hang_margin = 0.0;                   // cm, TiltToward::hanging: the layer below a root counts as ending this much sooner
  bool hang_falls_free = false;               // TiltToward::hanging: heavy hair (gravity) ends where its fall ends (scalp/hanging.h)
  int guides = 3000;                          // clusters = principal guides (paper: 3000)
  double preguide_spacing = 1.0;              // cm between pre-guide roots (paper: about 1 per cm)
  double cluster_overlap = 1.3;               // cluster circle radius / covering radius (≥ 1)
  std::uint64_t seed = 0;
  double oversampling = 3.0;                  // candidates per kept point for sample elimination
};

// Per-root columns (same length). Roots are ordered by the scalp triangle they lie in.
struct RootSet {
  std::vector<SurfacePoint> where;   // triangle and barycentric coordinates on the scalp
  std::vector<Vec3> positions;       // cm
  std::vector<Vec3> normals;         // unit outward surface normal (interpolated vertex normals)
  std::vector<Vec3> directions;      // unit growth direction: normal tilted toward down (or thicker)
  std::vector<double> lengths;       // cm
  std::vector<Vec2> chart;           // chart coordinates (unit disk)
  std::vector<double> heights;       // [0, 1] along up: 0 lowest scalp vertex, 1 top of the head
  std::vector<double> hang_weights;  // TiltToward::hanging: how much each root hangs, φ ∈ [0, 1]; else empty
  int size() const { return static_cast<int>(positions.size()); }
};

struct Roots {
  RootSet pores;
  double expected_count = 0.0;  // ∫ density dA over the scalp (hairs)
  double hair_area = 0.0;       // cm² of scalp where the density map is non-zero
  int candidates = 0;           // candidates generated for sample elimination
};

struct Clusters {
  RootSet bases;                         // guide base per cluster (a pore at the circle's centre)
  std::vector<int> centre_pore;          // pore index of each cluster's centre
  std::vector<double> radius;            // chart radius of each cluster's circle
  std::vector<int> pore_cluster;         // cluster of each pore
  std::vector<std::vector<int>> members; // pores of each cluster, ascending
  std::vector<int> candidate_clusters;   // per pore: how many circles contain it (≥ 1)
  int size() const { return static_cast<int>(centre_pore.size()); }
};

struct PreguideRoots {
  RootSet roots;
  double spacing = 0.0;  // cm, as requested
};

// The longest hair the options give a root: the length, or the long end of the length map's range.
double longest_hair(const RootInputs& inputs, const RootOptions& options);

// Whether root i of the set hangs (TiltToward::hanging, weight above kHangingPreguide).
bool hangs(const RootSet& roots, int i);

// Pores: blue noise on the 3D surface with density options.density × density map (hairs/cm²).
// Exactly round(∫ρ dA) roots (the integral by subdivided-triangle quadrature of the map), by
// weighted sample elimination from ~oversampling× candidates (Poisson-disk radius 1/sqrt(2√3ρ)
// adapted to the local density, down to 1/16 of the maximum). No root where the map is 0.
Roots make_roots(const ScalpChart& chart, const RootInputs& inputs, const RootOptions& options, const Exec& exec = {});

// Clusters (paper §3.3): min(guides, pores) centres chosen among the pores as a blue-noise set on
// the surface; in the chart, circle c has radius cluster_overlap × (largest chart distance from c
// to a pore whose nearest centre is c), so the circles cover every pore; a pore inside several
// circles goes to one of them uniformly at random (Random(seed, clusters, pore)).
Clusters make_clusters(const ScalpChart& chart, const Roots& roots, const RootOptions& options, const Exec& exec = {});

// Pre-guide roots: blue noise on the surface at about preguide_spacing (hexagonal packing density
// 2/(√3 s²)) wherever the density map is non-zero, with growth directions and lengths.
PreguideRoots make_preguide_roots(const ScalpChart& chart, const RootInputs& inputs, const RootOptions& options,
                                  const Exec& exec = {});

// What the roots stage makes: the pores, their clusters and the pre-guide roots, equal to
// make_roots, make_clusters and make_preguide_roots called one after the other, with the density
// map's integral over the triangles (shared by pores and pre-guide roots) computed once.
struct ScalpRoots {
  Roots roots;
  Clusters clusters;
  PreguideRoots preguides;
};
ScalpRoots make_scalp_roots(const ScalpChart& chart, const RootInputs& inputs, const RootOptions& options,
                            const Exec& exec = {});

// Unit growth direction (docs/design.md §3): the normal rotated by `tilt_degrees` toward down projected
// onto the tangent plane; where down is (nearly) parallel to the normal, toward −front projected,
// else any tangent. Never NaN for a unit normal.
Vec3 growth_direction(const Vec3& normal, const Vec3& down, const Vec3& front, double tilt_degrees);

// Thickness gradients (cm/cm) along the surface below this count as a flat layer.
constexpr double kFlatLayerGradient = 0.1;

// Unit growth direction for TiltToward::thicker: the normal rotated by `tilt_degrees` toward the
// tangential part g of `thickness_gradient`; where |g| < kFlatLayerGradient, toward the blend
// (|g|/k)·ĝ + (1 − |g|/k)·(growth_direction's tangent toward down), so a flat layer falls back to
// down continuously. Never NaN for a unit normal.
Vec3 growth_direction_toward_thicker(const Vec3& normal, const Vec3& thickness_gradient, const Vec3& down,
                                     const Vec3& front, double tilt_degrees);

// Figures for report.json.
struct ScalpFigures {
  double scalp_area = 0.0;       // cm²
  double expected_roots = 0.0;   // ∫ density dA
  int roots = 0;
  int guides = 0;
  int preguide_roots = 0;
  double min_spacing = 0.0;      // cm, smallest nearest-neighbour distance between pores (3D)
  double mean_spacing = 0.0;     // cm, mean nearest-neighbour distance
};
ScalpFigures scalp_figures(const ScalpChart& chart, const Roots& roots, const Clusters& clusters,
                           const PreguideRoots& preguides, int threads);

// Nearest-neighbour distance (3D, cm) of every point of a set (0 for a single point).
std::vector<double> nearest_neighbour_distances(const std::vector<Vec3>& points, int threads);

Digest digest(const RootSet& roots);
Digest digest(const Roots& roots);
Digest digest(const Clusters& clusters);
Digest digest(const PreguideRoots& preguides);

}  // namespace hairfit
