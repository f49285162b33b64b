// The strands stage: a wisp of fibres around each guide, kept out of the head and cut at the
// volume (docs/design.md §7).
#include <cstdio>
#include <limits>

#include "core/parallel.h"
#include "core/triangle_grid.h"
#include "io/curve_files.h"
#include "pipeline/scalp_exit.h"
#include "pipeline/stage.h"
#include "pipeline/stage_codec.h"
#include "pipeline/stage_options.h"
#include "scalp/shell_hair.h"
#include "strands/coverage.h"

namespace hairfit {

namespace {

// The wisps and their cut, the fibres' section, and how far inside the volume fibres are held.
struct StrandsOptions {
  StrandOptions strands;
  double cross_section = 0.0;  // cm², for the fibres' widths
  double contain = 0.0;        // cm (strands.contain; 0: not held); the deposit's fibres are not
  bool depth_from_layer = false;  // strands.depth = "auto": strands.layer_depth decided by the layer
};

void encode(ByteWriter& out, const StrandsOptions& o) {
  encode(out, o.strands);
  out.put(o.cross_section);
  out.put(o.contain);
  out.put<std::uint8_t>(o.depth_from_layer);
}

// A round wisp's width at its tip.
double wisp_tip_width(const StrandOptions& o) { return 2.0 * o.wisp.tip_radius; }

// strands.depth = "auto": a round wisp is wisp_tip_width wide at most, so it fills a layer no
// deeper than that; a deeper layer (its thickness T over the scalp, scalp/shell_hair.h) has its
// fibres spread through it. Reported as a derived key for the resolved scene.
bool spread_through_layer(const StageRun& run, const StrandOptions& o, StageReport& stage) {
  const StageValues& v = run.values;
  const double thickness = shell_thickness(*v.chart, layer_thickness(*v.volume_field), run.options.threads);
  const double width = wisp_tip_width(o);
  const bool spread = thickness > width;
  char source[256];
  std::snprintf(source, sizeof source,
                "auto, the layer's thickness T %.4g cm (90th percentile over the scalp) %s a wisp's width at its "
                "tip, 2·strands.tip_radius = %.4g cm",
                thickness, spread ? "exceeds" : "is within", width);
  stage.derive("strands.depth", spread ? "\"layer\"" : "\"wisp\"", source);
  return spread;
}

std::size_t loop_items(const StageValues& v) { return v.roots->pores.size(); }

void compute(StageRun& run, const StrandsOptions& o, StageReport& stage) {
  const int threads = run.options.threads;
  StageValues& v = run.values;
  const DistanceField* volume = v.volume_field.get();
  const DistanceFunction volume_distance = [volume](const Vec3& p) { return volume->value(p); };
  const DistanceFunction volume_quick = [volume](const Vec3& p) {  // the sign alone where the cell tells it
    const int side = volume->side(p);
    return side != 0 ? side * std::numeric_limits<double>::infinity() : volume->value(p);
  };
  StrandOptions strands = o.strands;
  if (o.depth_from_layer) strands.layer_depth = spread_through_layer(run, strands, stage);
  const TriangleGrid scalp_triangles(v.chart->mesh);
  StrandSurroundings around;
  around.volume = volume_distance;
  around.volume_quick = volume_quick;
  around.out_of_head =
      scalp_exit(*v.scalp_field, &scalp_triangles, v.chart->outward, o.contain > 0.0 ? v.volume_field.get() : nullptr,
                 v.scalp_distance.get());
  if (o.contain > 0.0) around.out_of_head.into_volume = into_volume(*v.volume_field, o.contain);
  const Boundary b = run.boundary();
  // Below the rim of a head closed by its floor the layer's depth runs along the hanging hair;
  // where the skin goes on under the hull as a shell it still runs across it (no rim: no fade).
  // Where the layer is deeper than a wisp is wide at its tip (the width "auto" spreads beyond),
  // the fibres spread through the top wisp's width of it: the hull is what the hair shows. Spread
  // evenly through a bun 6.7 cm deep, only a wisp's top fibre came within the 0.75 cm of the hull
  // that coverage counts; over its top 1.2 cm, two in three do (the carved bun's coverage
  // 0.860 → 0.977, docs/results/carved-flow.md).
  if (strands.layer_depth)
    around.to_layer_depth =
        layer_placement(*v.scalp_field, *v.volume_field, b.floor_past_hairline ? rim_heights(*v.chart) : RimHeights{},
                        wisp_tip_width(strands));
  around.hair_region = [&b](const Vec3& p) { return b.acceptable(p); };
  GrownStrands grown = make_strands(v.guides->curves(), run.pores(), strands, around, run.exec(),
                                    std::move(run.deposited_fibres));
  run.deposited_fibres = {};
  const FibrePointSides& known = grown.sides;  // looked up on the way: the counts need not ask again
  add_fibre_widths(grown.strands.fibres, o.cross_section, threads);
  v.strands = std::make_shared<const Strands>(std::move(grown.strands));
  const Curves& fibres = v.strands->fibres;
  // The digest hashes the 35 MB of points in one serial chain: on a thread of its own, beside the
  // counts and the files (the runner waits for it).
  run.digest = std::async(std::launch::async, [&fibres] { return Digest().add(fibres.points).hex(); });
  // Field values per point after the root (looked up only where make_strands did not): counted
  // per fibre on all threads, then summed (integers, so the totals do not depend on the thread
  // count). A root is its pore, a point of the scalp by construction; through the interpolated
  // fields one near a thin hairline reads either side of it, so roots are not counted
  // (spec/reference.md, report figures).
  std::vector<std::array<int, 3>> counts(fibres.count(), {0, 0, 0});  // inside, in head, outside volume
  parallel_for(static_cast<int>(fibres.count()), threads, [&](int c) {
    for (std::size_t k = fibres.offsets[c] + 1; k < fibres.offsets[c + 1]; ++k) {
      const bool head = !known.in_head.empty() && known.in_head[k] >= 0 ? known.in_head[k] == 1
                                                                        : b.beyond_scalp(fibres.points[k]) > 0.0;
      const bool out = known.outside_volume.empty() ? b.beyond_volume(fibres.points[k]) > 0.0 : known.outside_volume[k] == 1;
      counts[c][0] += !head && !out;
      counts[c][1] += head;
      counts[c][2] += out;
    }
  });
  long long inside = 0, in_head = 0, out_volume = 0;
  for (const std::array<int, 3>& n : counts) inside += n[0], in_head += n[1], out_volume += n[2];
  const double points = std::max<double>(1.0, static_cast<double>(fibres.points.size() - fibres.count()));
  stage.add("fibres", static_cast<std::int64_t>(fibres.count()));
  stage.add("depth", std::string(strands.layer_depth ? "layer" : "wisp"));
  stage.add("points", static_cast<std::int64_t>(fibres.points.size()));
  if (o.strands.cutting) stage.add("cut", static_cast<std::int64_t>(v.strands->cut_count));
  stage.add("inside_fraction", inside / points);
  stage.add("inside_head_fraction", in_head / points);  // the two ways of not being inside
  stage.add("outside_volume_fraction", out_volume / points);
  if (o.strands.cutting)
    stage.add("cut_share", static_cast<double>(v.strands->cut_count) / std::max<std::size_t>(1, fibres.count()));
  // Segments whose chord crosses the scalp's triangles (exact tests): those the lift could not
  // clear, a first segment whose root lies behind a neighbouring triangle's plane.
  stage.add("scalp_crossings", static_cast<std::int64_t>(v.strands->scalp_crossings));
  // Fibres ended before a chord the keep-out pass could not lift off the scalp (also in "cut").
  stage.add("cut_at_scalp", static_cast<std::int64_t>(v.strands->cut_at_scalp));
  CoverageOptions cover;
  cover.threads = threads;
  const Coverage coverage = strand_coverage(
      run.inputs.volume.mesh, fibres.points, [&b](const Vec3& p) { return b.beyond_scalp(p) <= 0.0; }, cover);
  stage.add("coverage", coverage.share);
}

void encode_value(ByteWriter& out, const StageValues& v) { encode(out, *v.strands); }
void decode_value(ByteReader& in, StageValues& v) { v.strands = std::make_shared<const Strands>(decode_strands(in)); }

ConfiguredStage configure(const Scene& scene) {
  StrandsOptions o{strand_options(scene), scene.hair.cross_section, scene.strands.contain,
                   scene.strands.depth == "auto"};
  // cut where fibres leave the volume, held in it, or spread through the layer
  const bool reads_fields = o.strands.cutting || o.contain > 0.0 || o.strands.layer_depth || o.depth_from_layer;
  const bool reads_chart = o.depth_from_layer;
  ConfiguredStage c = configured(std::move(o), compute);
  c.consumes = {"roots", "guides"};
  if (reads_fields) c.consumes.push_back("fields");
  if (reads_chart) c.consumes.push_back("chart");
  // Not stored: the strands (and the density of the final fibres) are hit only when nothing
  // before them changed, while every new weight or strand setting would add the largest entry of
  // all (31 MB for the spheroid's 68 000 fibres, against 15 MB for its guides); rebuilding them
  // from the cached guides takes about a second.
  c.cached = false;
  return c;
}

void write(StageRun& run, const Scene& scene) {
  const Curves& fibres = run.values.strands->fibres;
  Curves guide_curves = run.values.guides->curves();
  add_fibre_widths(guide_curves, scene.hair.cross_section, run.options.threads);
  for (const std::string& format : scene.output.strands) {
    auto write_as = [&](const std::string& base, const Curves& curves) {
      run.output(base + "." + format, [&](const std::filesystem::path& p) {
        if (format == "hair") write_hair_file(p, curves, "hairfit " + base);
        else if (format == "obj") write_obj_curves(p, curves, run.options.threads);
        else if (format == "usda") write_usda_curves(p, curves, 0.007, -scene.units.down);
        else write_ply_curves(p, curves);
      });
    };
    write_as("strands", run.in_scene_frame(fibres));
    if (format != "obj") write_as("guides", run.in_scene_frame(guide_curves));  // guides.obj comes from the guides stage
  }
}

}  // namespace

const StageDescriptor& strands_stage() {
  static const StageDescriptor d{"strands", 1, nullptr, configure, loop_items, encode_value, decode_value, write};
  return d;
}

}  // namespace hairfit
