// The chart stage: the scalp's Floater map onto the unit disk (docs/design.md §3).
#include "pipeline/stage.h"
#include "pipeline/stage_codec.h"
#include "scalp/scalp_outputs.h"

namespace hairfit {

namespace {

// The head's axes, which orient the chart.
struct ChartOptions {
  Vec3 front, down;
  std::string name;  // the scalp's file, for messages
};

void encode(ByteWriter& out, const ChartOptions& o) {
  out.put(o.front);
  out.put(o.down);
}

void compute(StageRun& run, const ChartOptions& o, StageReport& stage) {
  StageValues& v = run.values;
  v.chart = std::make_shared<const ScalpChart>(make_scalp_chart(run.inputs.scalp.mesh, o.front, o.down, o.name));
  stage.digest = digest(*v.chart).hex();
  stage.add("scalp_area_cm2", v.chart->area);
  stage.add("flipped_triangles", static_cast<std::int64_t>(v.chart->flipped_triangles));
  stage.add("hairline_vertices", static_cast<std::int64_t>(v.chart->boundary.size()));
  stage.add("solver", v.chart->solver);
}

void encode_value(ByteWriter& out, const StageValues& v) { encode(out, *v.chart); }
void decode_value(ByteReader& in, StageValues& v) { v.chart = std::make_shared<const ScalpChart>(decode_scalp_chart(in)); }

ConfiguredStage configure(const Scene& scene) {
  ConfiguredStage c = configured(ChartOptions{scene.units.front, scene.units.down, scene.inputs.scalp.string()}, compute);
  c.files = {"scalp"};
  return c;
}

void write(StageRun& run, const Scene&) {
  run.output("chart.obj", [&](const std::filesystem::path& p) { write_chart_obj(p, *run.values.chart, run.inputs.origin); });
}

}  // namespace

const StageDescriptor& chart_stage() {
  static const StageDescriptor d{"chart", 1, nullptr, configure, nullptr, encode_value, decode_value, write};
  return d;
}

}  // namespace hairfit
