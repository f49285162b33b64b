#include "pipeline/stage_options.h"

#include "core/triangle_grid.h"
#include "field/hair_region.h"

namespace hairfit {

FieldSpec field_spec(const Scene& scene, const std::string& mesh_name) {
  FieldSpec spec;
  spec.voxel = scene.fields.voxel;
  spec.band = scene.fields.band;
  spec.margin = scene.fields.margin;
  spec.max_memory_gib = scene.fields.max_memory / 2.0;  // the budget covers both fields
  spec.name = mesh_name;
  return spec;
}

RootSettings root_settings(const Scene& scene) {
  RootSettings s;
  RootOptions& o = s.options;
  o.density = scene.hair.density;
  o.tilt = scene.hair.tilt;
  if (scene.effects.uses_map("tilt")) o.tilt_range = scene.hair.tilt_range;
  o.tilt_toward = scene.hair.tilt_toward == "thicker"   ? TiltToward::thicker
                  : scene.hair.tilt_toward == "hanging" ? TiltToward::hanging
                                                        : TiltToward::down;
  o.flow = scene.hair.flow == "field" ? FlowModel::field : scene.hair.flow == "relief" ? FlowModel::relief : FlowModel::local;
  if (o.flow != FlowModel::local) {  // the growth field's guidance
    o.comb = scene.hair.comb == "from_crown" ? Comb::from_crown : Comb::into_layer;
    s.comb_from_hull = scene.hair.comb == "auto";
    o.flow_smoothing = scene.hair.flow_smoothing;
    o.swirl = scene.hair.swirl;
    o.whorl = Vec2(scene.hair.whorl[0], scene.hair.whorl[1]);
    o.whorl_radius = scene.hair.whorl_radius;
    o.parting = Vec2(scene.hair.parting[0], scene.hair.parting[1]);
    o.parting_radius = scene.hair.parting_radius;
  }
  o.length = scene.hair.length;
  if (scene.effects.uses_map("length")) o.length_range = scene.hair.length_range;
  if (o.tilt_toward == TiltToward::hanging) {
    o.hang_margin = scene.hair.hang_margin;
    o.hang_falls_free = scene.effects.gravity;
  }
  o.guides = scene.roots.guides;
  o.preguide_spacing = scene.roots.preguide_spacing;
  o.cluster_overlap = scene.roots.cluster_overlap;
  o.seed = static_cast<std::uint64_t>(scene.seed);
  for (const char* map : {"density", "tilt", "length"})
    if (scene.effects.uses_map(map)) s.maps.push_back(map);
  s.from_shell = scene.hair.from_shell;
  if (s.from_shell) s.fall_depth_range = scene.preguides.depth_range;
  if (o.flow == FlowModel::relief) {
    s.relief_radius = scene.hair.relief_radius;
    s.grain_of_normals = scene.hair.relief_grain == "normals";
    s.grain_follows_comb = scene.hair.relief_grain == "auto";
  }
  return s;
}

std::vector<std::string> root_files(const RootSettings& s) {
  std::vector<std::string> files;
  for (const std::string& map : s.maps) files.push_back(map + " map");
  // The hull's grain; the stubble of hair from the hull, as long as the hull lets it run.
  if (s.options.flow == FlowModel::relief || s.from_shell) files.push_back("volume");
  return files;
}

// Tilting toward the thicker layer or hanging, hair that suits its shell, and combed hair (its
// length from the layer ahead) read the fields.
bool roots_read_fields(const RootSettings& s) {
  return s.options.tilt_toward != TiltToward::down || s.from_shell || s.options.comb == Comb::from_crown;
}

ThicknessField layer_thickness(const DistanceField& volume) {
  return [&volume](const Vec3& p) {
    const double h = volume.voxel();
    Vec3 gradient;
    for (int axis = 0; axis < 3; ++axis) {
      const Vec3 step = h * Vec3::Unit(axis);
      gradient[axis] = (volume.value(p - step) - volume.value(p + step)) / (2.0 * h);
    }
    return LayerThickness{-volume.value(p), gradient};
  };
}

std::function<double(const Vec3&, const Vec3&, double)> exact_layer_run(const Mesh& hull, const Mesh& scalp,
                                                                        bool hull_closed) {
  struct Layer {
    Layer(const Mesh& h, const Mesh& s, bool closed)
        : hull(h), scalp(s), hull_grid(hull), scalp_grid(scalp), region(hull, scalp, closed), head(closed_head(scalp)) {}
    bool inside(const Vec3& p) const { return region.inside_hull(p) && !winding_above_half(head, p); }
    Mesh hull, scalp;  // the grids refer to them
    TriangleGrid hull_grid, scalp_grid;
    HairRegion region;
    FastWindingNumber head;
  };
  const auto layer = std::make_shared<const Layer>(hull, scalp, hull_closed);
  return [layer](const Vec3& root, const Vec3& direction, double reach) {
    double run = reach;
    for (const TriangleGrid* grid : {&layer->hull_grid, &layer->scalp_grid}) {
      const SegmentHit hit = grid->first_crossing(root, root + reach * direction);
      if (hit.found()) run = std::min(run, hit.t * reach);
    }
    for (int k = 1; k <= kLayerRunSamples && reach * k / kLayerRunSamples <= run; ++k)
      if (!layer->inside(root + (reach * k / kLayerRunSamples) * direction))
        return reach * (k - 1) / kLayerRunSamples;
    return run;
  };
}

HangProbe hang_probe(const Boundary& boundary, const Vec3& down, bool falls_free) {
  HangProbe probe;
  probe.falls_free = falls_free;
  probe.skin = [scalp = boundary.scalp](const Vec3& p, double& distance, Vec3& gradient) {
    const FieldValueGradient v = scalp->value_and_gradient(p);
    distance = v.value;
    gradient = v.gradient;
  };
  probe.in_volume = [volume = boundary.volume](const Vec3& p) { return volume->value(p) <= 0.0; };
  probe.down = down.normalized();
  probe.step = 0.5 * boundary.volume->voxel();
  return probe;
}

HairMaterial hair_material(const Scene& scene) {
  HairMaterial m;
  m.youngs_modulus = scene.hair.youngs_modulus;
  m.shear_modulus = scene.hair.shear_modulus;
  m.cross_section = scene.hair.cross_section;
  if (scene.effects.gravity) {
    m.mass_density = scene.hair.mass_density;
    m.gravity = scene.rod.gravity * scene.units.down;
  }
  if (scene.effects.contact) m.contact = ContactLaw{scene.contact.stiffness, scene.contact.layer};
  return m;
}

RodDiscretisation rod_discretisation(const Scene& scene) {
  return RodDiscretisation{parse_rod_integrator(scene.rod.integrator), scene.rod.segments};
}

PreguideOptions preguide_options(const Scene& scene) {
  PreguideOptions o;
  o.material = hair_material(scene);
  o.rod = rod_discretisation(scene);
  o.depth_range = scene.preguides.depth_range;
  o.max_load = scene.preguides.max_load;
  o.immersion = scene.preguides.immersion == "layer" ? PreguideImmersion::layer : PreguideImmersion::tip;
  o.styled = scene.hair.rest_shape == "flow";
  o.down = scene.units.down;
  o.front = scene.units.front;
  return o;
}

GuideOptions guide_options(const Scene& scene) {
  GuideOptions o;
  o.material = hair_material(scene);
  o.rod = rod_discretisation(scene);
  o.samples = scene.guides.samples;
  o.neighbours = scene.guides.neighbours;
  o.max_iterations = scene.guides.max_iterations;
  o.tolerance = scene.guides.tolerance;
  o.boundary = scene.guides.boundary == "paper"   ? BoundaryForm::paper
               : scene.guides.boundary == "layer" ? BoundaryForm::layer
                                                  : BoundaryForm::smooth;
  o.outside_penalty = scene.guides.outside_penalty;
  o.boundary_width = scene.guides.boundary_width;
  o.point_forces = scene.guides.point_forces;
  o.point_force_weight = scene.guides.point_force_weight;
  o.weights = GuideWeights{scene.guides.weights.direction, scene.guides.weights.similarity,
                           scene.guides.weights.boundary, scene.guides.weights.density};
  o.warm_start = scene.guides.start == "warm";
  o.depth_range = scene.preguides.depth_range;
  o.down = scene.units.down;
  o.front = scene.units.front;
  return o;
}

WispShape wisp_shape(const Scene& scene) {
  WispShape w;
  w.points = scene.strands.points;
  w.root_radius = scene.strands.root_radius;
  w.tip_radius = scene.strands.tip_radius;
  w.turns = scene.effects.winding ? scene.strands.turns : 0.0;
  return w;
}

StrandOptions strand_options(const Scene& scene) {
  StrandOptions o;
  o.wisp = wisp_shape(scene);
  o.cutting = scene.effects.cutting;
  if (o.cutting) {
    o.cut_threshold = scene.strands.cut_threshold;
    o.cut_tips = scene.strands.cut_tips;
  }
  o.layer_depth = scene.strands.depth == "layer";
  if (scene.effects.density != DensityModel::none) {  // the models' fibre part (strands/density_spread.h)
    o.spread.passes = scene.density.spread;
    o.spread.voxel = scene.density.voxel;
  }
  return o;
}

bool density_declared(const Scene& scene) { return scene.effects.density != DensityModel::none; }

DensityGridSpec density_grid_spec(const Scene& scene) { return DensityGridSpec{scene.density.voxel, scene.fields.max_memory}; }

GridGeometry density_geometry(const DensityGridSpec& spec, const Mesh& volume) {
  const auto [lower, upper] = bounding_box(volume);
  return make_density_geometry(lower, upper, spec.voxel, 2.0 * spec.voxel, spec.max_memory);
}

GuideDensitySettings guide_density_settings(const Scene& scene) {
  GuideDensitySettings s;
  s.term.model = scene.effects.density == DensityModel::binary ? GuideDensityModel::binary : GuideDensityModel::continuous;
  s.term.strength = scene.density.strength;
  s.term.threshold = scene.density.threshold;
  s.term.surcharge = scene.density.surcharge;
  s.grid = density_grid_spec(scene);
  s.batch = scene.density.batch;
  s.stall = StallTest{scene.density.stall_iterations, scene.density.stall_tolerance};
  s.wisp = wisp_shape(scene);
  s.deposit = scene.density.deposit == "fibres" ? WispDeposit::fibres : WispDeposit::tubes;
  return s;
}

GuideDensityOptions guide_density_options(const GuideDensitySettings& s, const Mesh& volume, Pores pores) {
  GuideDensityOptions o;
  o.term = s.term;
  o.grid = density_geometry(s.grid, volume);
  o.batch = s.batch;
  o.stall = s.stall;
  o.pores = std::move(pores);
  o.wisp = s.wisp;
  o.deposit = s.deposit;
  return o;
}

}  // namespace hairfit
