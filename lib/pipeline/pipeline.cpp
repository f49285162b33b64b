#include "pipeline/pipeline.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <future>
#include <limits>
#include <map>
#include <optional>

#include "core/parallel.h"
#include "density/accumulator.h"
#include "density/statistics.h"
#include "guides/flow_crossing.h"
#include "guides/guide_outputs.h"
#include "io/atomic_file.h"
#include "io/curve_files.h"
#include "field/field_nrrd.h"
#include "field/hair_region.h"
#include "pipeline/scalp_exit.h"
#include "pipeline/stage_cache.h"
#include "pipeline/stage_codec.h"
#include "pipeline/stage_options.h"
#include "pipeline/stage_plan.h"
#include "scalp/growth_field.h"
#include "scalp/relief.h"
#include "scalp/scalp_outputs.h"
#include "scalp/shell_hair.h"
#include "strands/coverage.h"

namespace hairfit {

namespace fs = std::filesystem;

const std::vector<std::string>& stage_names() {
  static const std::vector<std::string> names{"fields", "chart", "roots", "preguides", "guides", "strands", "density"};
  return names;
}

void check_stage_name(const std::string& stage, const std::string& option) {
  const std::vector<std::string>& names = stage_names();
  if (stage.empty() || std::find(names.begin(), names.end(), stage) != names.end()) return;
  std::string valid;
  for (const std::string& n : names) valid += (valid.empty() ? "" : ", ") + n;
  throw InputError(option, "no stage named \"" + stage + "\"; the stages are: " + valid);
}

namespace {


// Diameters along a fibre: a hair of section A at the root, tapering to half at the tip.
void add_widths(Curves& curves, double cross_section, int threads) {
  const double root = 2.0 * std::sqrt(cross_section / M_PI);
  curves.widths.resize(curves.points.size());
  parallel_for(static_cast<int>(curves.count()), threads, [&](int c) {
    const std::size_t n = curves.size(c);
    for (std::size_t i = 0; i < n; ++i)
      curves.widths[curves.offsets[c] + i] = static_cast<float>(root * (1.0 - 0.5 * i / std::max<std::size_t>(1, n - 1)));
  });
}

class Runner {
 public:
  Runner(const Scene& scene, const Inputs& inputs, const RunOptions& options)
      : scene_(scene), inputs_(inputs), options_(options) {
    result_.report.scene = scene.file.string();
    result_.report.seed = scene.seed;
    result_.report.threads = options.threads;
    result_.report.effects = scene.effects.names();
    if (!options.cache_dir.empty()) {
      cache_.emplace(options.cache_dir);
      keys_ = stage_keys(scene, inputs);
    }
    for (const StageDeclaration& d : stage_declarations(scene)) cached_[d.name] = d.cached;
  }

  PipelineResult run() {
    const std::vector<std::string>& names = stage_names();
    const std::size_t last = options_.until.empty()
                                 ? names.size() - 1
                                 : std::find(names.begin(), names.end(), options_.until) - names.begin();
    for (std::size_t s = 0; s <= last; ++s) run_stage(names[s]);
    if (options_.write_outputs)
      write_text_file_atomically(options_.out_dir / "report.json", report_json(result_.report));
    return result_;
  }

 private:
  void run_stage(const std::string& name) {
    if (name == "density" && !density_declared(scene_)) return;  // no trace of a disabled effect
    StageReport stage;
    stage.name = name;
    const StageMeter meter;
    const bool cacheable = cache_ && cached_.at(name);
    if (!(cacheable && load_cached(stage))) {
      if (progress()) progress()->stage_begins(name, loop_items(name));
      compute(stage);
      if (cacheable) {
        await_digest(stage);
        store(stage);
      }
    }
    if (name == "strands") std::vector<Vec3>().swap(deposited_fibres_);  // taken over, or unused (cached strands)
    write_outputs(name);
    await_digest(stage);
    stage.seconds = meter.seconds();
    stage.cpu_seconds = meter.cpu_seconds();
    stage.peak_memory_bytes = meter.peak_memory_bytes();
    if (progress()) progress()->stage_ends(name, stage.status, stage.seconds);
    result_.report.stages.push_back(std::move(stage));
  }

  // A stage may hash its value on a thread of its own while it writes its files (digest_).
  void await_digest(StageReport& stage) {
    if (digest_.valid()) stage.digest = digest_.get();
  }

  ProgressReporter* progress() const { return options_.progress; }
  ProgressCallback loop_progress() const { return progress() ? progress()->callback() : ProgressCallback(); }

  // The length of the stage's loop, for the progress bar (0: none worth showing).
  std::size_t loop_items(const std::string& name) const {
    const StageValues& v = result_.values;
    if (name == "preguides") return v.preguide_roots->roots.size();
    if (name == "guides") return v.clusters->size();
    if (name == "strands") return v.roots->pores.size();
    return 0;
  }

  void compute(StageReport& stage) {
    const std::string& name = stage.name;
    if (name == "fields") fields(stage);
    else if (name == "chart") chart(stage);
    else if (name == "roots") roots(stage);
    else if (name == "preguides") preguides(stage);
    else if (name == "guides") guides(stage);
    else if (name == "strands") strands(stage);
    else if (name == "density") density(stage);
  }

  // A cache entry's payload: the stage's digest and figures, then its values.
  void store(const StageReport& stage) {
    const StageValues& v = result_.values;
    ByteWriter out;
    out.put(stage.digest);
    out.put<std::uint64_t>(stage.figures.size());
    for (const auto& [key, value] : stage.figures) {
      out.put(key);
      out.put<std::uint8_t>(static_cast<std::uint8_t>(value.index()));
      std::visit([&out](const auto& x) { out.put(x); }, value);
    }
    const std::string& name = stage.name;
    if (name == "fields") {
      encode(out, *v.scalp_field);
      encode(out, *v.volume_field);
    } else if (name == "chart") {
      encode(out, *v.chart);
    } else if (name == "roots") {
      encode(out, *v.roots);
      encode(out, *v.clusters);
      encode(out, *v.preguide_roots);
    } else if (name == "preguides") {
      encode(out, *v.preguides);
    } else if (name == "guides") {
      encode(out, *v.guides);
      out.put<std::uint8_t>(v.guide_density != nullptr);
      if (v.guide_density) encode(out, *v.guide_density);
    } else if (name == "strands") {
      encode(out, *v.strands);
    } else if (name == "density") {
      encode(out, *v.fibre_density);
    }
    try {
      cache_->store(name, keys_.at(name), out.take());
    } catch (const std::exception& e) {  // a cache that cannot be written costs speed, not the run
      if (progress()) progress()->note(std::string("warning: could not cache ") + name + ": " + e.what());
    }
  }

  // Loads the stage's value, digest and figures from its cache entry. Nothing is changed unless
  // the whole entry decodes; a rejected entry is reported and the stage recomputed.
  bool load_cached(StageReport& stage) {
    const std::string& name = stage.name;
    std::string problem;
    const std::optional<std::string> payload = cache_->load(name, keys_.at(name), problem);
    if (!payload) {
      if (!problem.empty() && progress()) progress()->note("cache: " + problem + "; recomputing " + name);
      return false;
    }
    try {
      ByteReader in(*payload);
      StageReport loaded = stage;
      in.get(loaded.digest);
      const auto figures = in.get<std::uint64_t>();
      if (figures > 1000) throw CodecError("impossible figure count");
      for (std::uint64_t i = 0; i < figures; ++i) {
        std::string key;
        in.get(key);
        switch (in.get<std::uint8_t>()) {
          case 0: loaded.add(key, in.get<bool>()); break;
          case 1: loaded.add(key, in.get<std::int64_t>()); break;
          case 2: loaded.add(key, in.get<double>()); break;
          case 3: {
            std::string text;
            in.get(text);
            loaded.add(key, text);
            break;
          }
          default: throw CodecError("unknown figure type");
        }
      }
      StageValues v = result_.values;
      if (name == "fields") {
        v.scalp_field = std::make_shared<const DistanceField>(decode_distance_field(in));
        v.volume_field = std::make_shared<const DistanceField>(decode_distance_field(in));
      } else if (name == "chart") {
        v.chart = std::make_shared<const ScalpChart>(decode_scalp_chart(in));
      } else if (name == "roots") {
        v.roots = std::make_shared<const Roots>(decode_roots(in));
        v.clusters = std::make_shared<const Clusters>(decode_clusters(in));
        v.preguide_roots = std::make_shared<const PreguideRoots>(decode_preguide_roots(in));
      } else if (name == "preguides") {
        v.preguides = std::make_shared<const PreGuides>(decode_preguides(in));
      } else if (name == "guides") {
        v.guides = std::make_shared<const Guides>(decode_guides(in));
        if (in.get<std::uint8_t>()) v.guide_density = std::make_shared<const DensityGrid>(decode_density_grid(in));
      } else if (name == "strands") {
        v.strands = std::make_shared<const Strands>(decode_strands(in));
      } else if (name == "density") {
        v.fibre_density = std::make_shared<const DensityGrid>(decode_density_grid(in));
      }
      in.expect_end();
      loaded.status = "cached";
      stage = std::move(loaded);
      result_.values = std::move(v);
      return true;
    } catch (const CodecError& e) {
      if (progress())
        progress()->note("cache: " + cache_->entry_path(name, keys_.at(name)).string() + ": " + e.what() +
                         "; recomputing " + name);
      return false;
    }
  }

  void write_outputs(const std::string& name) {
    if (!options_.write_outputs) return;
    if (name == "fields") write_fields();
    else if (name == "chart") write_chart();
    else if (name == "roots") write_roots();
    else if (name == "preguides") write_preguides();
    else if (name == "guides") write_guides();
    else if (name == "strands") write_strands();
    else if (name == "density") write_density();
  }

  template <class Write>
  void output(const std::string& relative, Write write) {
    const fs::path path = options_.out_dir / relative;
    write(path);
    result_.report.outputs.push_back({relative, static_cast<std::uint64_t>(fs::file_size(path))});
  }

  void fields(StageReport& stage) {
    StageValues& v = result_.values;
    // The scalp's field: the distance to the head closed under the scalp by a floor across the
    // hairline, negative inside it.
    const Mesh head = closed_head(inputs_.scalp.mesh);
    const FastWindingNumber head_winding(head, HairRegion::kFirstBeta, options_.threads);
    const InsideTest inside_head = [&head_winding](const Vec3& p) { return winding_above_half(head_winding, p); };
    v.scalp_field = std::make_shared<const DistanceField>(make_distance_field(
        head, field_spec(scene_, scene_.inputs.scalp.string()), options_.threads, inside_head));
    // The volume's inside is the region's (HairRegion) together with the head, so that its field
    // keeps its sign across the scalp, as a prepared volume's floor under the scalp makes it: the
    // acceptable region, inside the volume and not behind the scalp, is the region's shell.
    const HairRegion region(inputs_.volume.mesh, inputs_.scalp.mesh, inputs_.volume_report.closed(), options_.threads);
    const DistanceField& scalp = *v.scalp_field;
    const InsideTest inside_volume = [&region, &scalp](const Vec3& p) { return scalp.value(p) < 0.0 || region.inside_hull(p); };
    v.volume_field = std::make_shared<const DistanceField>(make_distance_field(
        inputs_.volume.mesh, field_spec(scene_, scene_.inputs.volume.string()), options_.threads, inside_volume));
    Digest d;
    std::array<NrrdVolume, 2> volumes{field_to_nrrd(*v.scalp_field, options_.threads), field_to_nrrd(*v.volume_field, options_.threads)};
    for (const NrrdVolume& volume : volumes) d.add_bytes(volume.data.data(), volume.data.size() * sizeof(float));
    if (options_.write_outputs) field_volumes_ = std::move(volumes);  // the files hold the same samples
    stage.digest = d.hex();
    stage.add("voxel_cm", scene_.fields.voxel);
    stage.add("scalp_grid", std::to_string(v.scalp_field->dims().x()) + "x" + std::to_string(v.scalp_field->dims().y()) +
                                "x" + std::to_string(v.scalp_field->dims().z()));
    stage.add("volume_grid", std::to_string(v.volume_field->dims().x()) + "x" +
                                 std::to_string(v.volume_field->dims().y()) + "x" + std::to_string(v.volume_field->dims().z()));
    stage.add("band_voxels", static_cast<std::int64_t>(v.scalp_field->band_voxels() + v.volume_field->band_voxels()));
    stage.add("memory_bytes", static_cast<std::int64_t>(v.scalp_field->memory_bytes() + v.volume_field->memory_bytes()));
    // What the inputs were found to be, and how much of the scalp the region covers.
    const MeshReport& hull = inputs_.volume_report;
    stage.add("volume_closed", hull.closed());
    stage.add("volume_parts", static_cast<std::int64_t>(hull.parts));
    stage.add("volume_boundary_loops", static_cast<std::int64_t>(hull.boundary_loops));
    stage.add("volume_nonmanifold_edges", static_cast<std::int64_t>(hull.nonmanifold_edges));
    stage.add("volume_flipped_patches", static_cast<std::int64_t>(hull.flipped_patches));
    stage.add("volume_reversed", inputs_.volume_reversed);
    stage.add("scalp_inside_share", inputs_.scalp_inside_share);
    stage.add("scalp_outside_share", 1.0 - inputs_.scalp_inside_share);
  }

  void write_fields() {
    const StageValues& v = result_.values;
    if (!field_volumes_)  // a cached stage: converted again rather than stored
      field_volumes_ = {field_to_nrrd(*v.scalp_field, options_.threads), field_to_nrrd(*v.volume_field, options_.threads)};
    output("fields/scalp.nrrd", [&](const fs::path& p) { write_nrrd(p, (*field_volumes_)[0]); });
    output("fields/volume.nrrd", [&](const fs::path& p) { write_nrrd(p, (*field_volumes_)[1]); });
    field_volumes_.reset();
  }

  void chart(StageReport& stage) {
    StageValues& v = result_.values;
    v.chart = std::make_shared<const ScalpChart>(
        make_scalp_chart(inputs_.scalp.mesh, scene_.units.front, scene_.units.down, scene_.inputs.scalp.string()));
    stage.digest = digest(*v.chart).hex();
    stage.add("scalp_area_cm2", v.chart->area);
    stage.add("flipped_triangles", static_cast<std::int64_t>(v.chart->flipped_triangles));
    stage.add("hairline_vertices", static_cast<std::int64_t>(v.chart->boundary.size()));
    stage.add("solver", v.chart->solver);
  }

  void write_chart() { output("chart.obj", [&](const fs::path& p) { write_chart_obj(p, *result_.values.chart); }); }

  ScalpMaps maps() const {
    return ScalpMaps{inputs_.density_map ? &*inputs_.density_map : nullptr, inputs_.tilt_map ? &*inputs_.tilt_map : nullptr,
                     inputs_.length_map ? &*inputs_.length_map : nullptr};
  }

  void roots(StageReport& stage) {
    StageValues& v = result_.values;
    const RootOptions& o = resolved_root_options();
    if (scene_.hair.from_shell) {
      const ShellHair& shell = resolved_roots_->shell;
      stage.add("hair_from_shell", shell.layer_ends);
      stage.add("shell_thickness_cm", shell.thickness);
      stage.add("shell_reach_cm", shell.reach);
      stage.add("hair_length_cm", o.length);
      stage.add("hair_tilt_degrees", o.tilt);
    }
    ScalpRoots made = make_scalp_roots(*v.chart, maps(), o);
    v.roots = std::make_shared<const Roots>(std::move(made.roots));
    v.clusters = std::make_shared<const Clusters>(std::move(made.clusters));
    v.preguide_roots = std::make_shared<const PreguideRoots>(std::move(made.preguides));
    stage.digest = Digest().add(digest(*v.roots).hex()).add(digest(*v.clusters).hex()).add(digest(*v.preguide_roots).hex()).hex();
    const ScalpFigures f = scalp_figures(*v.chart, *v.roots, *v.clusters, *v.preguide_roots, options_.threads);
    stage.add("scalp_area_cm2", f.scalp_area);
    stage.add("expected_roots", f.expected_roots);
    stage.add("roots", static_cast<std::int64_t>(f.roots));
    stage.add("guides", static_cast<std::int64_t>(f.guides));
    stage.add("preguide_roots", static_cast<std::int64_t>(f.preguide_roots));
    stage.add("min_spacing_cm", f.min_spacing);
    stage.add("mean_spacing_cm", f.mean_spacing);
  }

  // The roots' options with what they read from the fields and the hull: the layer's thickness,
  // the hull's grain, and the length and tilt of hair that suits its shell. Worked out once a run,
  // for the roots and for pre-guides that follow the growth field.
  const RootOptions& resolved_root_options() {
    if (resolved_roots_) return resolved_roots_->options;
    const StageValues& v = result_.values;
    ResolvedRoots r;
    RootOptions& o = r.options;
    o = root_options(scene_, options_.threads);
    if (o.tilt_toward == TiltToward::thicker) o.thickness = layer_thickness(*v.volume_field);
    if (o.flow == FlowModel::relief) o.grain = relief_grain(*v.chart, inputs_.volume.mesh, scene_.hair.relief_radius, options_.threads);
    if (scene_.hair.from_shell) {  // hair that suits its shell: length and tilt from the layer
      r.shell = shell_hair(*v.chart, layer_thickness(*v.volume_field), options_.threads);
      if (r.shell.layer_ends) {
        o.length = r.shell.length;
        o.tilt = r.shell.tilt;
      }
    }
    resolved_roots_ = std::move(r);
    return resolved_roots_->options;
  }

  void write_roots() {
    const StageValues& v = result_.values;
    output("roots.ply", [&](const fs::path& p) { write_roots_ply(p, *v.roots, *v.clusters); });
  }

  Boundary boundary() const { return Boundary{result_.values.scalp_field.get(), result_.values.volume_field.get()}; }

  void preguides(StageReport& stage) {
    StageValues& v = result_.values;
    PreguideOptions o = preguide_options(scene_, options_.threads);
    o.progress = loop_progress();
    if (o.immersion == PreguideImmersion::layer && scene_.hair.flow != "local") {
      // The growth field the roots grew along (one solve on the scalp), for the pre-guides to follow.
      const ScalpChart& chart = *v.chart;
      o.flow = std::make_shared<const FlowLookup>(chart.mesh, chart.vertex_normals,
                                                  make_growth_field(chart, resolved_root_options()), kFlowLookupRadius);
    }
    v.preguides = std::make_shared<const PreGuides>(make_preguides(v.preguide_roots->roots, boundary(), o));
    stage.digest = digest(*v.preguides).hex();
    const Boundary b = boundary();
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
    flow.threads = options_.threads;
    stage.add("flow_crossing", flow_crossing(curves, flow).crossing_share);
  }

  void write_preguides() {
    const PreGuides& preguides = *result_.values.preguides;
    Curves curves;
    for (int i = 0; i < preguides.size(); ++i) curves.add(preguides.items[i].shape.nodes, i);
    output("preguides.obj", [&](const fs::path& p) { write_obj_curves(p, curves, options_.threads); });
  }

  // The fibres' pores: one fibre per pore, grown along its cluster's guide.
  Pores pores() const {
    const StageValues& v = result_.values;
    Pores p;
    p.positions = v.roots->pores.positions;
    p.lengths = v.roots->pores.lengths;
    p.guide = v.clusters->pore_cluster;
    for (const SurfacePoint& w : v.roots->pores.where)
      p.normals.push_back(v.chart->outward * triangle_normal(v.chart->mesh, w.triangle));
    return p;
  }

  void guides(StageReport& stage) {
    StageValues& v = result_.values;
    GuideOptions o = guide_options(scene_, options_.threads);
    o.progress = loop_progress();
    Digest density_digest;
    if (density_declared(scene_)) {
      const GuideDensityOptions d =
          guide_density_options(scene_, density_geometry(scene_, inputs_.volume.mesh), pores());
      DensityGuides result = make_guides_with_density(v.clusters->bases, *v.preguides, boundary(), o, d);
      v.guides = std::make_shared<const Guides>(std::move(result.guides));
      v.guide_density = std::make_shared<const DensityGrid>(std::move(result.density));
      deposited_fibres_ = std::move(result.fibres);
      const std::vector<double>& values = v.guide_density->values();
      density_digest.add_bytes(values.data(), values.size() * sizeof(double));
      stage.add("density_batches", static_cast<std::int64_t>(result.batches));
      double f4 = 0.0;
      for (const Guide& g : v.guides->items) f4 += g.f4;
      stage.add("mean_f4", v.guides->size() ? f4 / v.guides->size() : 0.0);
    } else {
      v.guides = std::make_shared<const Guides>(make_guides(v.clusters->bases, *v.preguides, boundary(), o));
    }
    stage.digest = density_declared(scene_) ? Digest().add(digest(*v.guides).hex()).add(density_digest.hex()).hex()
                                            : digest(*v.guides).hex();
    const GuideFigures f = guide_figures(*v.guides, *v.preguides, boundary(), o, scene_.fields.voxel);
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
    if (scene_.effects.contact) {
      stage.add("max_contact_force", f.max_contact_force);
      stage.add("contact_share", f.contact_share);
      stage.add("guides_in_contact", static_cast<std::int64_t>(f.guides_in_contact));
    }
    stage.add("start", scene_.guides.start);
    FlowCrossingOptions flow;
    flow.threads = options_.threads;
    const FlowCrossing crossing = flow_crossing(v.guides->curves(), flow);
    stage.add("flow_crossing", crossing.crossing_share);
    stage.add("flow_median_degrees", crossing.median_degrees);
    stage.add("flow_sampled_points", static_cast<std::int64_t>(crossing.sampled_points));  // 0: every pair counted
  }

  void write_guides() {
    const Guides& guides = *result_.values.guides;
    output("guides.obj", [&](const fs::path& p) { write_obj_curves(p, guides.curves(), options_.threads); });
    output("guides.csv", [&](const fs::path& p) { write_guides_csv(p, guides); });
  }

  void strands(StageReport& stage) {
    StageValues& v = result_.values;
    const DistanceField* volume = v.volume_field.get();
    const DistanceFunction volume_distance = [volume](const Vec3& p) { return volume->value(p); };
    const DistanceFunction volume_quick = [volume](const Vec3& p) {  // the sign alone where the cell tells it
      const int side = volume->side(p);
      return side != 0 ? side * std::numeric_limits<double>::infinity() : volume->value(p);
    };
    StrandOptions o = strand_options(scene_, options_.threads);
    o.progress = loop_progress();
    FibrePointSides known;  // looked up on the way: the counts need not ask again
    const TriangleGrid scalp_triangles(v.chart->mesh);
    HeadExit exit = scalp_exit(*v.scalp_field, &scalp_triangles, v.chart->outward);
    if (scene_.strands.contain > 0.0) exit.into_volume = into_volume(*v.volume_field, scene_.strands.contain);
    Strands s = make_strands(v.guides->curves(), pores(), o, volume_distance, exit, &known, volume_quick,
                             deposited_fibres_.empty() ? nullptr : &deposited_fibres_);
    add_widths(s.fibres, scene_.hair.cross_section, options_.threads);
    v.strands = std::make_shared<const Strands>(std::move(s));
    const Curves& fibres = v.strands->fibres;
    // The digest hashes the 35 MB of points in one serial chain: on a thread of its own, beside the
    // counts and the files (run_stage waits for it).
    digest_ = std::async(std::launch::async, [&fibres] { return Digest().add(fibres.points).hex(); });
    // Field values per point after the root (looked up only where make_strands did not): counted
    // per fibre on all threads, then summed (integers, so the totals do not depend on the thread
    // count). A root is its pore, a point of the scalp by construction; through the interpolated
    // fields one near a thin hairline reads either side of it, so roots are not counted
    // (spec/reference.md, report figures).
    const Boundary b = boundary();
    std::vector<std::array<int, 3>> counts(fibres.count(), {0, 0, 0});  // inside, in head, outside volume
    parallel_for(static_cast<int>(fibres.count()), options_.threads, [&](int c) {
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
    stage.add("points", static_cast<std::int64_t>(fibres.points.size()));
    if (scene_.effects.cutting) stage.add("cut", static_cast<std::int64_t>(v.strands->cut_count));
    stage.add("inside_fraction", inside / points);
    stage.add("inside_head_fraction", in_head / points);  // the two ways of not being inside
    stage.add("outside_volume_fraction", out_volume / points);
    if (scene_.effects.cutting) stage.add("cut_share", static_cast<double>(v.strands->cut_count) / std::max<std::size_t>(1, fibres.count()));
    // Segments whose chord crosses the scalp's triangles (exact tests): those the lift could not
    // clear, a first segment whose root lies behind a neighbouring triangle's plane.
    stage.add("scalp_crossings", static_cast<std::int64_t>(v.strands->scalp_crossings));
    CoverageOptions cover;
    cover.threads = options_.threads;
    const Coverage coverage = strand_coverage(
        inputs_.volume.mesh, fibres.points, [&b](const Vec3& p) { return b.beyond_scalp(p) <= 0.0; }, cover);
    stage.add("coverage", coverage.share);
  }

  void write_strands() {
    const Curves& fibres = result_.values.strands->fibres;
    Curves guide_curves = result_.values.guides->curves();
    add_widths(guide_curves, scene_.hair.cross_section, options_.threads);
    for (const std::string& format : scene_.output.strands) {
      auto write = [&](const std::string& base, const Curves& curves) {
        output(base + "." + format, [&](const fs::path& p) {
          if (format == "hair") write_hair_file(p, curves, "hairfit " + base);
          else if (format == "obj") write_obj_curves(p, curves, options_.threads);
          else if (format == "usda") write_usda_curves(p, curves, 0.007, -scene_.units.down);
          else write_ply_curves(p, curves);
        });
      };
      write("strands", fibres);
      if (format != "obj") write("guides", guide_curves);  // guides.obj comes from the guides stage
    }
  }

  // Paper §3.5, Fig. 5–6: what the final fibres' density looks like, measured the same way for
  // every model (a CDM deposit of the final, cut fibres) so models can be compared. Runs after
  // strands because the fibres exist only then.
  void density(StageReport& stage) {
    StageValues& v = result_.values;
    const GridGeometry grid = density_geometry(scene_, inputs_.volume.mesh);
    DensityAccumulator accumulator(grid);
    std::vector<std::int32_t> segment_counts;  // the histogram's, from the deposit's traversal
    accumulator.add_fibres(v.strands->fibres, options_.threads, &segment_counts);
    v.fibre_density = std::make_shared<const DensityGrid>(std::move(accumulator).freeze());
    // The digest (one serial chain over the grid) beside the region test and the files.
    const std::vector<double>& values = v.fibre_density->values();
    digest_ = std::async(std::launch::async, [&values] {
      return Digest().add_bytes(values.data(), values.size() * sizeof(double)).hex();
    });
    // Boundary::acceptable(p) at every cell centre (beyond_volume(p) = volume(p) ≤ 0 and
    // beyond_scalp(p) = −scalp(p) ≤ 0): where a field's lookup cell settles the sign
    // (sides_on_lattice, per-axis tables), no value is interpolated; elsewhere it is, at the same
    // centre (GridGeometry::cell_centre, coordinate by coordinate).
    const DistanceField& volume = *v.volume_field;
    const DistanceField& scalp = *v.scalp_field;
    const GridGeometry& g = v.fibre_density->geometry();
    std::vector<double> centres[3];
    for (int d = 0; d < 3; ++d)
      for (int n = 0; n < g.dims[d]; ++n) centres[d].push_back(g.origin[d] + g.voxel * (n + 0.5));
    const std::vector<std::int8_t> volume_sides = volume.sides_on_lattice(centres[0], centres[1], centres[2], options_.threads);
    const std::vector<std::int8_t> scalp_sides = scalp.sides_on_lattice(centres[0], centres[1], centres[2], options_.threads);
    std::vector<char> in_region(static_cast<std::size_t>(g.count()), 0);
    parallel_for(g.dims.z(), options_.threads, [&](int k) {
      for (int j = 0; j < g.dims.y(); ++j)
        for (int i = 0; i < g.dims.x(); ++i) {
          const std::int64_t c = g.index(i, j, k);
          const int in_volume = volume_sides[c], in_front = scalp_sides[c];
          if (in_volume > 0 || in_front < 0) continue;
          const Vec3 p = g.cell_centre(i, j, k);
          if (in_volume == 0 && !(volume.value(p) <= 0.0)) continue;
          in_region[c] = in_front > 0 || -scalp.value(p) <= 0.0;
        }
    });
    const DensityStatistics s = density_statistics(*v.fibre_density, in_region);
    stage.add("model", scene_.effects.density == DensityModel::binary ? std::string("binary") : std::string("continuous"));
    stage.add("voxel_cm", grid.voxel);
    stage.add("grid", std::to_string(grid.dims.x()) + "x" + std::to_string(grid.dims.y()) + "x" + std::to_string(grid.dims.z()));
    stage.add("region_cells", s.region_cells);
    stage.add("occupied_cells", s.occupied_cells);
    stage.add("mean_density", s.mean);
    stage.add("coefficient_of_variation", s.coefficient_of_variation);
    stage.add("empty_share", s.empty_share);
    histogram_ = histogram_of_counts(segment_counts);
    stage.add("max_segments_per_cell",
              static_cast<std::int64_t>(histogram_->cells_with.empty() ? 0 : histogram_->cells_with.size() - 1));
  }

  void write_density() {
    if (!histogram_)  // a cached stage: recomputed from the fibres rather than stored
      histogram_ = segment_histogram_of_curves(density_geometry(scene_, inputs_.volume.mesh),
                                               result_.values.strands->fibres, options_.threads);
    output("density/histogram.csv", [&](const fs::path& p) { write_text_file_atomically(p, histogram_csv(*histogram_)); });
    // Centre sagittal slice (Fig. 6): normal = the head's left–right axis = front × up.
    const Vec3 up = -scene_.units.down;
    const Vec3 left_right = scene_.units.front.cross(up);
    output("density/sagittal.nrrd", [&](const fs::path& p) {
      write_nrrd(p, slice_to_nrrd(centre_slice(*result_.values.fibre_density, left_right, up)));
    });
  }

  const Scene& scene_;
  const Inputs& inputs_;
  const RunOptions& options_;
  std::optional<StageCache> cache_;
  std::map<std::string, std::string> keys_;
  std::map<std::string, bool> cached_;
  std::optional<SegmentHistogram> histogram_;  // the density stage's, for its file
  std::optional<std::array<NrrdVolume, 2>> field_volumes_;  // the fields stage's samples (scalp, volume), for its files
  std::future<std::string> digest_;  // the current stage's digest, when computed beside its files
  // The fibres the guides stage's CDM deposit grew, as the strands stage grows them before the head
  // exit and the cut (DensityGuides::fibres): handed on within one run only, so that the strands
  // stage need not grow them again. Never cached; the results do not depend on it.
  std::vector<Vec3> deposited_fibres_;
  // The roots' options with what the fields and the hull say (resolved_root_options), once a run.
  struct ResolvedRoots {
    RootOptions options;
    ShellHair shell;
  };
  std::optional<ResolvedRoots> resolved_roots_;
  PipelineResult result_;
};

}  // namespace

PipelineResult run_pipeline(const Scene& scene, const Inputs& inputs, const RunOptions& options) {
  check_stage_name(options.until);
  if (options.until == "density" && !density_declared(scene))
    throw InputError(scene.file.string(), "declares no density model (effects.density = \"none\"), so there is no "
                                          "density stage to stop after; declare one or stop after strands");
  return Runner(scene, inputs, options).run();
}

std::filesystem::path default_cache_dir(const Scene& scene) { return scene.file.parent_path() / ".hairfit-cache"; }

}  // namespace hairfit
