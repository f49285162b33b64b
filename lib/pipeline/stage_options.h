// The scene's sections translated into each stage's own options: stages never see the Scene, so
// they can be used and tested without a scene file.
#pragma once
#include "field/distance_field.h"
#include "core/mesh.h"
#include "guides/density_term.h"
#include "guides/guides.h"
#include "scalp/roots.h"
#include "spec/scene.h"
#include "strands/strands.h"

namespace hairfit {

FieldSpec field_spec(const Scene& scene, const std::string& mesh_name);
RootOptions root_options(const Scene& scene, int threads);
// The hair layer's thickness for hair.tilt_toward = "thicker": the depth −Φ_V below the volume
// boundary, its gradient by central differences one voxel wide (the trilinear gradient jumps
// between cells: 3–6° of error in the direction of a 0.2 cm/cm slope at 0.2 cm voxels, against
// under 1° this way; tests/scalp/growth_field_test.cpp).
ThicknessField layer_thickness(const DistanceField& volume);
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
GridGeometry density_geometry(const Scene& scene, const Mesh& volume);
// The batched guide optimisation's options (requires density_declared); `pores` are the fibres'
// pores with their cluster (guide) index, what CDM deposits.
GuideDensityOptions guide_density_options(const Scene& scene, const GridGeometry& grid, Pores pores);

}  // namespace hairfit
