// The scene's sections translated into each stage's own options: the library never sees the Scene,
// so it can be used and tested without a scene file, and each stage of the pipeline reads the
// scene only through these (its cache key hashes what they return, options_codec.h). Keys of an
// effect that is off are not read: their options keep the library's defaults.
#pragma once
#include "field/distance_field.h"
#include "core/mesh.h"
#include "guides/density_term.h"
#include "guides/guides.h"
#include "guides/boundary.h"
#include "scalp/hanging.h"
#include "scalp/roots.h"
#include "spec/scene.h"
#include "strands/strands.h"

namespace hairfit {

FieldSpec field_spec(const Scene& scene, const std::string& mesh_name);
// What the roots stage reads of the scene: the root options, and how it resolves them against the
// fields and the hull (StageRun::resolved_roots).
struct RootSettings {
  RootOptions options;
  std::vector<std::string> maps;  // the grey maps it reads (effects.maps: density, tilt, length)
  bool from_shell = false;        // length and tilt from the shell (hair.length and hair.tilt unset)
  double relief_radius = 0.0;     // cm around a scalp point the hull's grain is read (flow = relief)
  bool grain_of_normals = false;  // hair.relief_grain = "normals" (scalp/relief.h relief_grain_of_normals)
  // hair.comb = "auto": for hair that suits its shell the comb chosen from the hull
  // (scalp/hull_hair.h comb_from_hull), else into_layer; hair.relief_grain = "auto": the normals'
  // grain where the hair is combed from the crown, else the edges'.
  bool comb_from_hull = false;
  bool grain_follows_comb = false;
  // Hair from the hull: the share of the layer's depth the hair falls at, crown → rim (the
  // pre-guides' immersion, preguides.depth_range).
  std::array<double, 2> fall_depth_range{0.15, 0.6};
};
RootSettings root_settings(const Scene& scene);
// The input files and earlier stages those settings read beyond the chart.
std::vector<std::string> root_files(const RootSettings& settings);
bool roots_read_fields(const RootSettings& settings);
// The hair layer's thickness for hair.tilt_toward = "thicker": the depth −Φ_V below the volume
// boundary, its gradient by central differences one voxel wide (the trilinear gradient jumps
// between cells: 3–6° of error in the direction of a 0.2 cm/cm slope at 0.2 cm voxels, against
// under 1° this way; tests/scalp/growth_field_test.cpp).
ThicknessField layer_thickness(const DistanceField& volume);
// RootInputs::layer_run, exact: how far the straight hair from the root runs before it first
// crosses the hull's or the scalp's triangles (TriangleGrid::first_crossing), or, sooner, the last
// of kLayerRunSamples points evenly spaced up to the reach before the first one outside the layer
// by the fields' own robust regions, exactly: outside the hull (HairRegion::inside_hull, the
// winding number of a closed hull alone or of an open one less the scalp's) or in the head (the
// scalp closed by its floor, closed_head); the reach if neither. The crossings see a hair leave
// through either surface away from its root; the winding numbers see it leave right at the root,
// and leave a carved cap between the hull's rim and the scalp's, where the two part at a hairline
// and it crosses neither.
constexpr int kLayerRunSamples = 16;
std::function<double(const Vec3&, const Vec3&, double)> exact_layer_run(const Mesh& hull, const Mesh& scalp,
                                                                        bool hull_closed);
// What the hang of hair.tilt_toward = "hanging" reads (scalp/hanging.h): the scalp field's value
// and trilinear gradient, the volume field's side, in steps of half the volume's voxel.
HangProbe hang_probe(const Boundary& boundary, const Vec3& down, bool falls_free);
HairMaterial hair_material(const Scene& scene);
RodDiscretisation rod_discretisation(const Scene& scene);
PreguideOptions preguide_options(const Scene& scene);
GuideOptions guide_options(const Scene& scene);
// The wisp the strands stage grows and the density model deposits.
WispShape wisp_shape(const Scene& scene);
StrandOptions strand_options(const Scene& scene);

// Whether the scene declares a density model (effects.density ≠ none).
bool density_declared(const Scene& scene);
// The density grid: the hair-volume mesh's bounding box plus two voxels on every side, at
// density.voxel cm, within fields.max_memory.
struct DensityGridSpec {
  double voxel = 0.5;       // cm (density.voxel)
  double max_memory = 4.0;  // GiB (fields.max_memory)
};
DensityGridSpec density_grid_spec(const Scene& scene);
GridGeometry density_geometry(const DensityGridSpec& spec, const Mesh& volume);
// The batched guide optimisation's options as the scene gives them (requires density_declared);
// guide_density_options completes them with the grid over the hull and the pores to deposit.
struct GuideDensitySettings {
  DensityTermOptions term;
  DensityGridSpec grid;
  int batch = 64;
  StallTest stall;
  WispShape wisp;
  WispDeposit deposit = WispDeposit::tubes;
};
GuideDensitySettings guide_density_settings(const Scene& scene);
// `pores` are the fibres' pores with their cluster (guide) index, what CDM deposits.
GuideDensityOptions guide_density_options(const GuideDensitySettings& settings, const Mesh& volume, Pores pores);

}  // namespace hairfit
