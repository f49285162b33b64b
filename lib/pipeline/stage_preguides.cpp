// The preguides stage: sparse rods bent into the hair volume (docs/design.md §4).
#include "guides/flow_crossing.h"
#include "io/curve_files.h"
#include "pipeline/stage.h"
#include "pipeline/stage_codec.h"
#include "pipeline/stage_options.h"

namespace hairfit {

namespace {

// The pre-guides' options, and when they follow the growth field the roots grew along
// (immersion = layer, flow ≠ local), the roots' settings that field is made from.
struct PreguidesOptions {
  PreguideOptions preguides;
  std::optional<RootSettings> growth;
};

void encode(ByteWriter& out, const PreguidesOptions& o) {
  encode(out, o.preguides);
  encode(out, o.growth);
}

std::size_t loop_items(const StageValues& v) { return v.preguide_roots->roots.size(); }

void compute(StageRun& run, const PreguidesOptions& options, StageReport& stage) {
  StageValues& v = run.values;
  PreguideOptions o = options.preguides;
  if (options.growth) o.flow = run.growth_lookup(*options.growth);  // for the pre-guides to follow
  v.preguides = std::make_shared<const PreGuides>(make_preguides(v.preguide_roots->roots, run.boundary(), o, run.exec()));
  stage.digest = digest(*v.preguides).hex();
  const Boundary b = run.boundary();
  int reached = 0, partial_weight = 0, tip_outside = 0;
  double solves = 0;
  for (const PreGuide& g : v.preguides->items) {
    reached += g.reached;
    solves += g.solves;
    partial_weight += g.weight_share < 1.0;
    tip_outside += !g.reached && b.beyond_volume(g.shape.nodes.back()) > 0.0;
  }
  stage.add("preguides", static_cast<std::int64_t>(v.preguides->size()));
  if (!v.preguide_roots->roots.hang_weights.empty()) {  // hair.tilt_toward = "hanging"
    std::int64_t hanging = 0;
    for (int i = 0; i < v.preguide_roots->roots.size(); ++i) hanging += hangs(v.preguide_roots->roots, i);
    stage.add("hanging", hanging);
  }
  stage.add("reached_depth", static_cast<std::int64_t>(reached));
  stage.add("flagged", static_cast<std::int64_t>(v.preguides->size() - reached));
  // Of those, the ones whose tip ends beyond the volume: hair longer than the volume holds there.
  stage.add("flagged_tip_outside", static_cast<std::int64_t>(tip_outside));
  stage.add("mean_newton_steps", v.preguides->size() ? solves / v.preguides->size() : 0.0);
  stage.add("shared_newton_steps", static_cast<std::int64_t>(v.preguides->shared_solves));
  // Under gravity: pre-guides whose weight continuation met a fold short of the full weight.
  if (!o.material.gravity.isZero(0.0)) stage.add("weight_not_followed", static_cast<std::int64_t>(partial_weight));
  // Nodes after the root in the acceptable region (the root is a point of the scalp).
  long long inside = 0, nodes = 0;
  for (const PreGuide& g : v.preguides->items)
    for (std::size_t k = 1; k < g.shape.nodes.size(); ++k, ++nodes) inside += b.acceptable(g.shape.nodes[k]);
  stage.add("inside_fraction", nodes ? static_cast<double>(inside) / nodes : 0.0);
  Curves curves;
  for (const PreGuide& g : v.preguides->items) curves.add(g.shape.nodes);
  FlowCrossingOptions flow;
  flow.threads = run.options.threads;
  stage.add("flow_crossing", flow_crossing(curves, flow).crossing_share);
}

void encode_value(ByteWriter& out, const StageValues& v) { encode(out, *v.preguides); }
void decode_value(ByteReader& in, StageValues& v) { v.preguides = std::make_shared<const PreGuides>(decode_preguides(in)); }

ConfiguredStage configure(const Scene& scene) {
  PreguidesOptions o{preguide_options(scene), std::nullopt};
  if (o.preguides.immersion == PreguideImmersion::layer && scene.hair.flow != "local") o.growth = root_settings(scene);
  const bool follows = o.growth.has_value(), relief = follows && o.growth->options.flow == FlowModel::relief;
  ConfiguredStage c = configured(std::move(o), compute);
  c.consumes = {"fields", "roots"};
  if (follows) c.consumes.push_back("chart");
  if (relief) c.files = {"volume"};  // the hull's grain steers the growth field
  return c;
}

void write(StageRun& run, const Scene&) {
  const PreGuides& preguides = *run.values.preguides;
  Curves curves;
  for (int i = 0; i < preguides.size(); ++i) curves.add(preguides.items[i].shape.nodes, i);
  run.output("preguides.obj", [&](const std::filesystem::path& p) { write_obj_curves(p, run.in_scene_frame(curves), run.options.threads); });
}

}  // namespace

const StageDescriptor& preguides_stage() {
  static const StageDescriptor d{"preguides", 1, nullptr, configure, loop_items, encode_value, decode_value, write};
  return d;
}

}  // namespace hairfit
