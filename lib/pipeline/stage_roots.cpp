// The roots stage: pores, guide clusters and pre-guide roots on the scalp, with their growth
// directions (docs/design.md §3).
#include "pipeline/stage.h"
#include "pipeline/stage_codec.h"
#include "scalp/scalp_outputs.h"

namespace hairfit {

namespace {

StageDeclaration declare(const Scene& scene) {
  StageDeclaration d;
  d.reads = {"seed", "hair.density", "hair.length", "hair.tilt", "roots", "effects.maps"};  // root_options()
  if (scene.effects.uses_map("density")) d.files.push_back("density map");
  if (scene.effects.uses_map("tilt")) {
    d.files.push_back("tilt map");
    d.reads.push_back("hair.tilt_range");
  }
  if (scene.effects.uses_map("length")) {
    d.files.push_back("length map");
    d.reads.push_back("hair.length_range");
  }
  d.consumes = {"chart"};
  d.reads.push_back("hair.flow");
  if (scene.hair.flow != "local")
    d.reads.insert(d.reads.end(), {"hair.flow_smoothing", "hair.swirl", "hair.whorl", "hair.whorl_radius", "hair.parting",
                                   "hair.parting_radius"});
  if (scene.hair.flow == "relief") {  // the hull's grain
    d.reads.push_back("hair.relief_radius");
    d.files.push_back("volume");
  }
  // Tilting toward the thicker layer reads the volume's distance field at each root.
  if (scene.hair.tilt_toward == "thicker") {
    d.reads.push_back("hair.tilt_toward");
    d.consumes.push_back("fields");
  }
  return d;
}

void compute(StageRun& run, StageReport& stage) {
  StageValues& v = run.values;
  const StageRun::ResolvedRoots& resolved = run.resolved_roots();
  const RootOptions& o = resolved.options;
  if (run.scene.hair.from_shell) {
    stage.add("hair_from_shell", resolved.shell.layer_ends);
    stage.add("shell_thickness_cm", resolved.shell.thickness);
    stage.add("shell_reach_cm", resolved.shell.reach);
    stage.add("hair_length_cm", o.length);
    stage.add("hair_tilt_degrees", o.tilt);
  }
  ScalpRoots made = make_scalp_roots(*v.chart, resolved.inputs, o);
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

void write(StageRun& run) {
  const StageValues& v = run.values;
  run.output("roots.ply", [&](const std::filesystem::path& p) { write_roots_ply(p, *v.roots, *v.clusters); });
}

}  // namespace

const StageDescriptor& roots_stage() {
  static const StageDescriptor d{"roots", declare, nullptr, nullptr, compute, encode_value, decode_value, write};
  return d;
}

}  // namespace hairfit
