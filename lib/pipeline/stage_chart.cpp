// The chart stage: the scalp's Floater map onto the unit disk (docs/design.md §3).
#include "pipeline/stage.h"
#include "pipeline/stage_codec.h"
#include "scalp/scalp_outputs.h"

namespace hairfit {

namespace {

StageDeclaration declare(const Scene&) {
  StageDeclaration d;
  d.reads = {"units.front", "units.down"};
  d.files = {"scalp"};
  return d;
}

void compute(StageRun& run, StageReport& stage) {
  StageValues& v = run.values;
  v.chart = std::make_shared<const ScalpChart>(make_scalp_chart(run.inputs.scalp.mesh, run.scene.units.front,
                                                                run.scene.units.down, run.scene.inputs.scalp.string()));
  stage.digest = digest(*v.chart).hex();
  stage.add("scalp_area_cm2", v.chart->area);
  stage.add("flipped_triangles", static_cast<std::int64_t>(v.chart->flipped_triangles));
  stage.add("hairline_vertices", static_cast<std::int64_t>(v.chart->boundary.size()));
  stage.add("solver", v.chart->solver);
}

void encode_value(ByteWriter& out, const StageValues& v) { encode(out, *v.chart); }
void decode_value(ByteReader& in, StageValues& v) { v.chart = std::make_shared<const ScalpChart>(decode_scalp_chart(in)); }

void write(StageRun& run) {
  run.output("chart.obj", [&](const std::filesystem::path& p) { write_chart_obj(p, *run.values.chart); });
}

}  // namespace

const StageDescriptor& chart_stage() {
  static const StageDescriptor d{"chart", declare, nullptr, nullptr, compute, encode_value, decode_value, write};
  return d;
}

}  // namespace hairfit
