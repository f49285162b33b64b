// The guides stage: one principal guide per cluster, its six load parameters optimised
// (docs/design.md §5), in batches against the density of the earlier ones when the scene declares
// a density model (§6).
#include "guides/flow_crossing.h"
#include "guides/guide_outputs.h"
#include "io/curve_files.h"
#include "pipeline/stage.h"
#include "pipeline/stage_codec.h"
#include "pipeline/stage_options.h"

namespace hairfit {

namespace {

// The guides' options, with a density model the batches, the grid and the wisps they deposit,
// and for hair styled along its flow (hair.rest_shape = "flow") the roots' settings its growth
// field is made from.
struct GuidesOptions {
  GuideOptions guides;
  std::optional<GuideDensitySettings> density;
  std::optional<RootSettings> growth;
};

void encode(ByteWriter& out, const GuidesOptions& o) {
  encode(out, o.guides);
  encode(out, o.density);
  encode(out, o.growth);
}

std::size_t loop_items(const StageValues& v) { return v.clusters->size(); }

void compute(StageRun& run, const GuidesOptions& options, StageReport& stage) {
  StageValues& v = run.values;
  GuideOptions o = options.guides;
  if (options.growth) o.styled = run.growth_lookup(*options.growth);
  Digest density_digest;
  if (options.density) {
    const GuideDensityOptions d = guide_density_options(*options.density, run.inputs.volume.mesh, run.pores());
    DensityGuides result = make_guides_with_density(v.clusters->bases, *v.preguides, run.boundary(), o, d, run.exec());
    v.guides = std::make_shared<const Guides>(std::move(result.guides));
    v.guide_density = std::make_shared<const DensityGrid>(std::move(result.density));
    run.deposited_fibres = std::move(result.fibres);
    const std::vector<double>& values = v.guide_density->values();
    density_digest.add_bytes(values.data(), values.size() * sizeof(double));
    stage.add("density_batches", static_cast<std::int64_t>(result.batches));
    double f4 = 0.0;
    for (const Guide& g : v.guides->items) f4 += g.f4;
    stage.add("mean_f4", v.guides->size() ? f4 / v.guides->size() : 0.0);
  } else {
    v.guides = std::make_shared<const Guides>(make_guides(v.clusters->bases, *v.preguides, run.boundary(), o, run.exec()));
  }
  stage.digest = options.density ? Digest().add(digest(*v.guides).hex()).add(density_digest.hex()).hex()
                                         : digest(*v.guides).hex();
  const GuideFigures f = guide_figures(*v.guides, *v.preguides, run.boundary(), o, v.volume_field->voxel());
  stage.add("guides", static_cast<std::int64_t>(f.guides));
  stage.add("failures", static_cast<std::int64_t>(f.failures));
  stage.add("mean_iterations", f.mean_iterations);
  stage.add("max_iterations", static_cast<std::int64_t>(f.max_iterations));
  stage.add("mean_evaluations", f.mean_evaluations);
  stage.add("inside_fraction", f.inside_fraction);
  stage.add("inside_head_fraction", f.inside_head_fraction);
  stage.add("outside_volume_fraction", f.outside_volume_fraction);
  stage.add("outside_tip_fraction", f.outside_tip_fraction);
  stage.add("guides_ending_outside", static_cast<std::int64_t>(f.guides_ending_outside));
  stage.add("mean_direction_mismatch", f.mean_direction_mismatch);
  stage.add("followed_direction_mismatch", f.followed_direction_mismatch);
  stage.add("max_weight", f.max_weight);
  stage.add("unresolved_weight", static_cast<std::int64_t>(f.unresolved_weight));
  stage.add("shorter_than_voxel", static_cast<std::int64_t>(f.shorter_than_voxel));
  if (o.material.contact.active()) {
    stage.add("max_contact_force", f.max_contact_force);
    stage.add("contact_share", f.contact_share);
    stage.add("guides_in_contact", static_cast<std::int64_t>(f.guides_in_contact));
  }
  if (o.point_forces > 0) {
    stage.add("point_forces", static_cast<std::int64_t>(o.point_forces));
    stage.add("guides_held", static_cast<std::int64_t>(f.guides_held));
    stage.add("max_point_force", f.max_point_force);
  }
  stage.add("start", std::string(o.warm_start ? "warm" : "straight"));
  FlowCrossingOptions flow;
  flow.threads = run.options.threads;
  const FlowCrossing crossing = flow_crossing(v.guides->curves(), flow);
  stage.add("flow_crossing", crossing.crossing_share);
  stage.add("flow_median_degrees", crossing.median_degrees);
  stage.add("flow_sampled_points", static_cast<std::int64_t>(crossing.sampled_points));  // 0: every pair counted
}

void encode_value(ByteWriter& out, const StageValues& v) {
  encode(out, *v.guides);
  out.put<std::uint8_t>(v.guide_density != nullptr);
  if (v.guide_density) encode(out, *v.guide_density);
}

void decode_value(ByteReader& in, StageValues& v) {
  v.guides = std::make_shared<const Guides>(decode_guides(in));
  if (in.get<std::uint8_t>()) v.guide_density = std::make_shared<const DensityGrid>(decode_density_grid(in));
}

ConfiguredStage configure(const Scene& scene) {
  GuidesOptions o{guide_options(scene), std::nullopt, std::nullopt};
  if (density_declared(scene)) o.density = guide_density_settings(scene);
  if (scene.hair.rest_shape == "flow") o.growth = root_settings(scene);
  const bool density = o.density.has_value(), styled = o.growth.has_value();
  const bool relief = styled && o.growth->options.flow == FlowModel::relief;
  ConfiguredStage c = configured(std::move(o), compute);
  c.consumes = {"fields", "roots", "preguides"};
  if (styled) c.consumes.push_back("chart");
  if (density || relief) c.files = {"volume"};  // the density grid spans the hull; its grain steers the field
  return c;
}

void write(StageRun& run, const Scene&) {
  const Guides& guides = *run.values.guides;
  run.output("guides.obj", [&](const std::filesystem::path& p) {
    write_obj_curves(p, run.in_scene_frame(guides.curves()), run.options.threads);
  });
  run.output("guides.csv", [&](const std::filesystem::path& p) { write_guides_csv(p, guides, run.inputs.origin); });
}

}  // namespace

const StageDescriptor& guides_stage() {
  static const StageDescriptor d{"guides", 1, nullptr, configure, loop_items, encode_value, decode_value, write};
  return d;
}

}  // namespace hairfit
