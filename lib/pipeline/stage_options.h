// The scene's sections translated into each stage's own options: stages never see the Scene, so
// they can be used and tested without a scene file.
#pragma once
#include "field/distance_field.h"
#include "guides/guides.h"
#include "scalp/roots.h"
#include "spec/scene.h"
#include "strands/strands.h"

namespace hairfit {

FieldSpec field_spec(const Scene& scene, const std::string& mesh_name);
RootOptions root_options(const Scene& scene, int threads);
HairMaterial hair_material(const Scene& scene);
RodDiscretisation rod_discretisation(const Scene& scene);
PreguideOptions preguide_options(const Scene& scene, int threads);
GuideOptions guide_options(const Scene& scene, int threads);
StrandOptions strand_options(const Scene& scene, int threads);

}  // namespace hairfit
