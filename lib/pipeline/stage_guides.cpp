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

StageDeclaration declare(const Scene& scene) {
  StageDeclaration d;
  declare_rod_reads(scene, d);
  d.reads.insert(d.reads.end(), {"guides", "effects.density"});  // guide_options()
  d.consumes = {"fields", "roots", "preguides"};
  if (density_declared(scene)) {  // guide_density_options(): the batches, the grid, the wisps they deposit
    d.reads.insert(d.reads.end(), {"density", "fields.max_memory"});
    declare_strand_reads(scene, d);
    d.files.push_back("volume");
  }
  return d;
}

std::size_t loop_items(const StageValues& v) { return v.clusters->size(); }

void compute(StageRun& run, StageReport& stage) {
  const Scene& scene = run.scene;
  StageValues& v = run.values;
  const GuideOptions o = guide_options(scene);
  Digest density_digest;
  if (density_declared(scene)) {
    const GuideDensityOptions d = guide_density_options(scene, density_geometry(scene, run.inputs.volume.mesh), run.pores());
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
  stage.digest = density_declared(scene) ? Digest().add(digest(*v.guides).hex()).add(density_digest.hex()).hex()
                                         : digest(*v.guides).hex();
  const GuideFigures f = guide_figures(*v.guides, *v.preguides, run.boundary(), o, scene.fields.voxel);
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
  if (scene.effects.contact) {
    stage.add("max_contact_force", f.max_contact_force);
    stage.add("contact_share", f.contact_share);
    stage.add("guides_in_contact", static_cast<std::int64_t>(f.guides_in_contact));
  }
  stage.add("start", scene.guides.start);
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

void write(StageRun& run) {
  const Guides& guides = *run.values.guides;
  run.output("guides.obj", [&](const std::filesystem::path& p) { write_obj_curves(p, guides.curves(), run.options.threads); });
  run.output("guides.csv", [&](const std::filesystem::path& p) { write_guides_csv(p, guides); });
}

}  // namespace

const StageDescriptor& guides_stage() {
  static const StageDescriptor d{"guides", declare, nullptr, loop_items, compute, encode_value, decode_value, write};
  return d;
}

}  // namespace hairfit
