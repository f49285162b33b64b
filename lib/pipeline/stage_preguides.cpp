// The preguides stage: sparse rods bent into the hair volume (docs/design.md §4).
#include "guides/flow_crossing.h"
#include "io/curve_files.h"
#include "pipeline/stage.h"
#include "pipeline/stage_codec.h"
#include "pipeline/stage_options.h"
#include "scalp/growth_field.h"

namespace hairfit {

namespace {

// Whether the pre-guides follow the growth field the roots grew along.
bool follows_growth_field(const Scene& scene) { return scene.preguides.immersion == "layer" && scene.hair.flow != "local"; }

StageDeclaration declare(const Scene& scene) {
  StageDeclaration d;
  declare_rod_reads(scene, d);
  d.reads.push_back("preguides");  // preguide_options()
  d.consumes = {"fields", "roots"};
  if (follows_growth_field(scene)) {
    d.reads.insert(d.reads.end(), {"hair", "roots"});
    d.consumes.push_back("chart");
    if (scene.hair.flow == "relief") d.files.push_back("volume");
  }
  return d;
}

std::size_t loop_items(const StageValues& v) { return v.preguide_roots->roots.size(); }

void compute(StageRun& run, StageReport& stage) {
  StageValues& v = run.values;
  PreguideOptions o = preguide_options(run.scene);
  if (follows_growth_field(run.scene)) {
    // The growth field the roots grew along (one solve on the scalp), for the pre-guides to follow.
    const ScalpChart& chart = *v.chart;
    o.flow = std::make_shared<const FlowLookup>(chart.mesh, chart.vertex_normals,
                                                make_growth_field(chart, run.resolved_roots().inputs, run.resolved_roots().options), kFlowLookupRadius);
  }
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

void write(StageRun& run) {
  const PreGuides& preguides = *run.values.preguides;
  Curves curves;
  for (int i = 0; i < preguides.size(); ++i) curves.add(preguides.items[i].shape.nodes, i);
  run.output("preguides.obj", [&](const std::filesystem::path& p) { write_obj_curves(p, curves, run.options.threads); });
}

}  // namespace

const StageDescriptor& preguides_stage() {
  static const StageDescriptor d{"preguides", declare, nullptr, loop_items, compute, encode_value, decode_value, write};
  return d;
}

}  // namespace hairfit
