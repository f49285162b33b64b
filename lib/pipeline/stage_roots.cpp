// The roots stage: pores, guide clusters and pre-guide roots on the scalp, with their growth
// directions (docs/design.md §3).
#include "pipeline/resolved_scene.h"
#include "pipeline/stage.h"
#include "pipeline/stage_codec.h"
#include "scalp/scalp_outputs.h"

namespace hairfit {

namespace {

void compute(StageRun& run, const RootSettings& settings, StageReport& stage) {
  StageValues& v = run.values;
  const StageRun::ResolvedRoots& resolved = run.resolved_roots(settings);
  const RootOptions& o = resolved.options;
  if (settings.from_shell) {
    stage.add("hair_from_shell", resolved.shell.layer_ends);
    stage.add("shell_thickness_cm", resolved.shell.thickness);
    stage.add("shell_reach_cm", resolved.shell.reach);
    stage.add("hair_length_cm", o.length);
    stage.add("hair_tilt_degrees", o.tilt);
    stage.add("hair_hangs_from_hull", resolved.hull.hangs);
    const std::vector<HullHairRegion> regions = hull_hair_regions(*v.chart, resolved.falls, resolved.hull);
    for (const HullHairRegion& g : regions) {
      const std::string key = "hull_" + g.name + "_";
      stage.add(key + "hanging_share", g.hanging_share);
      stage.add(key + "length_cm", g.median_length);
      stage.add(key + "fall_below_rim_cm", g.median_below_rim);
    }
    if (resolved.hull.hangs) derive_hull_keys(stage, regions, o.length, o.tilt);
    else derive_shell_keys(stage, resolved.shell, o.length, o.tilt);
  }
  if (resolved.comb) {
    stage.add("layer_thickening_up_share", resolved.comb->thickening_up);
    stage.add("hanging_area_share", resolved.comb->hanging);
    derive_comb_keys(stage, *resolved.comb, settings.grain_follows_comb);
  }
  ScalpRoots made = make_scalp_roots(*v.chart, resolved.inputs, o, run.exec());
  v.roots = std::make_shared<const Roots>(std::move(made.roots));
  v.clusters = std::make_shared<const Clusters>(std::move(made.clusters));
  v.preguide_roots = std::make_shared<const PreguideRoots>(std::move(made.preguides));
  stage.digest = Digest().add(digest(*v.roots).hex()).add(digest(*v.clusters).hex()).add(digest(*v.preguide_roots).hex()).hex();
  const ScalpFigures f = scalp_figures(*v.chart, *v.roots, *v.clusters, *v.preguide_roots, run.options.threads);
  stage.add("scalp_area_cm2", f.scalp_area);
  stage.add("expected_roots", f.expected_roots);
  stage.add("roots", static_cast<std::int64_t>(f.roots));
  stage.add("guides", static_cast<std::int64_t>(f.guides));
  stage.add("preguide_roots", static_cast<std::int64_t>(f.preguide_roots));
  stage.add("min_spacing_cm", f.min_spacing);
  stage.add("mean_spacing_cm", f.mean_spacing);
  if (o.tilt_toward == TiltToward::hanging) {  // how much of the hair hangs, and how long it is
    const RootSet& pores = v.roots->pores;
    double weight = 0.0, length = 0.0;
    for (int i = 0; i < pores.size(); ++i) weight += pores.hang_weights[i], length += pores.lengths[i];
    stage.add("hang_weight_mean", pores.size() ? weight / pores.size() : 0.0);
    stage.add("hair_length_mean_cm", pores.size() ? length / pores.size() : 0.0);
  }
}

void encode_value(ByteWriter& out, const StageValues& v) {
  encode(out, *v.roots);
  encode(out, *v.clusters);
  encode(out, *v.preguide_roots);
}

void decode_value(ByteReader& in, StageValues& v) {
  v.roots = std::make_shared<const Roots>(decode_roots(in));
  v.clusters = std::make_shared<const Clusters>(decode_clusters(in));
  v.preguide_roots = std::make_shared<const PreguideRoots>(decode_preguide_roots(in));
}

ConfiguredStage configure(const Scene& scene) {
  const RootSettings settings = root_settings(scene);
  const std::vector<std::string> files = root_files(settings);
  const bool fields = roots_read_fields(settings);
  ConfiguredStage c = configured(settings, compute);
  c.files = files;
  c.consumes = {"chart"};
  if (fields) c.consumes.push_back("fields");
  return c;
}

void write(StageRun& run, const Scene&) {
  const StageValues& v = run.values;
  run.output("roots.ply", [&](const std::filesystem::path& p) { write_roots_ply(p, *v.roots, *v.clusters, run.inputs.origin); });
}

}  // namespace

const StageDescriptor& roots_stage() {
  static const StageDescriptor d{"roots", 1, nullptr, configure, nullptr, encode_value, decode_value, write};
  return d;
}

}  // namespace hairfit
