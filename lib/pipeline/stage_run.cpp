#include <algorithm>
#include <cmath>

#include "core/parallel.h"
#include "pipeline/stage.h"
#include "pipeline/stage_options.h"
#include "guides/fall_rest.h"
#include "guides/guide_solve.h"
#include "guides/preguides.h"
#include "scalp/growth_field.h"
#include "scalp/hanging.h"
#include "scalp/hull_hair.h"
#include "scalp/relief.h"

namespace hairfit {

Exec StageRun::exec() const {
  return Exec{options.threads, options.progress ? options.progress->callback() : ProgressCallback()};
}

// The skin goes on past the hairline as a shell exactly where the fields stage replaced the closed
// head's field by it.
Boundary StageRun::boundary() const {
  return Boundary{values.scalp_field, values.volume_field, values.scalp_field == values.scalp_distance};
}

Pores StageRun::pores() const {
  Pores p;
  p.positions = values.roots->pores.positions;
  p.lengths = values.roots->pores.lengths;
  p.guide = values.clusters->pore_cluster;
  for (const SurfacePoint& w : values.roots->pores.where)
    p.normals.push_back(values.chart->outward * triangle_normal(values.chart->mesh, w.triangle));
  return p;
}

const StageRun::ResolvedRoots& StageRun::resolved_roots(const RootSettings& settings) {
  if (resolved_) return *resolved_;
  ResolvedRoots r;
  RootOptions& o = r.options;
  o = settings.options;
  r.inputs.density = inputs.density_map;
  r.inputs.tilt = inputs.tilt_map;
  r.inputs.length = inputs.length_map;
  if (settings.from_shell) {  // where the hair falls from every scalp vertex (scalp/fall.h)
    const ScalpChart& chart = *values.chart;
    const std::array<double, 2> depth_range = settings.fall_depth_range;
    r.falls = vertex_falls(chart, fall_region(boundary(), chart.down, chart.front), kLongestFall,
                           [&](const Vec3& p) { return immersion_share(depth_range, height_of(chart, p)); },
                           options.threads);
  }
  if (settings.comb_from_hull && settings.from_shell) {
    r.comb = comb_from_hull(*values.chart, layer_thickness(*values.volume_field), r.falls);
    o.comb = r.comb->comb;
  }
  if (o.flow == FlowModel::relief) {
    const ScalpChart& chart = *values.chart;
    if (settings.grain_of_normals || (settings.grain_follows_comb && o.comb == Comb::from_crown)) {
      const std::vector<double> lift = vertex_thickness(chart, layer_thickness(*values.volume_field), options.threads);
      r.inputs.grain = relief_grain_of_normals(chart, inputs.volume.mesh, lift, settings.relief_radius, options.threads);
    } else {
      r.inputs.grain = relief_grain(chart, inputs.volume.mesh, settings.relief_radius, options.threads);
    }
  }
  if (settings.from_shell) {  // hair that suits its shell: length and tilt from the layer
    r.shell = shell_hair(*values.chart, layer_thickness(*values.volume_field), options.threads);
    if (r.shell.layer_ends) {
      o.length = r.shell.length;
      o.tilt = r.shell.tilt;
    }
  }
  if (settings.from_shell) {  // where the layer carries the hair on below the rim, it hangs there
    const ScalpChart& chart = *values.chart;
    // Hair combed from the crown lies as far as the layer ahead of it goes.
    r.hull = o.comb == Comb::from_crown
                 ? hull_hair(r.falls, combed_lengths(chart, layer_thickness(*values.volume_field), o.length, options.threads))
                 : hull_hair(r.falls, o.length);
    if (r.hull.hangs || o.comb == Comb::from_crown) {
      r.inputs.vertex_hang_weights = r.hull.hang_weights;
      r.inputs.vertex_lengths = r.hull.lengths;
      o.tilt_toward = TiltToward::hanging;
      if (!r.shell.layer_ends) o.tilt = kMaxShellTilt;
    }
  }
  // Hair from the hull shorter than stubble_length is stubble, as long as its layer holds it
  // straight. A root's length interpolates its triangle's vertices', so only where some vertex's
  // hair is stubble can a root's be, and only then are the layer's trees built.
  const double stubble = stubble_length(*values.volume_field);
  const std::vector<double>& lengths = r.inputs.vertex_lengths;
  if (settings.from_shell && std::any_of(lengths.begin(), lengths.end(), [&](double l) { return l < stubble; })) {
    r.inputs.layer_run = exact_layer_run(inputs.volume.mesh, values.chart->mesh, inputs.volume_report.closed());
    r.inputs.stubble_length = stubble;
  }
  // After the hull has had its say: hanging hair tilts as "thicker" does where it does not hang.
  if (o.tilt_toward != TiltToward::down) r.inputs.thickness = layer_thickness(*values.volume_field);
  // Combed hair of a declared length ends where the layer ahead of it does, if that comes sooner.
  if (o.comb == Comb::from_crown && r.inputs.vertex_lengths.empty() && !r.inputs.length) {
    r.inputs.vertex_lengths = combed_lengths(*values.chart, layer_thickness(*values.volume_field), o.length, options.threads);
    for (double& l : r.inputs.vertex_lengths) l = std::min(l, o.length);
    r.inputs.vertex_hang_weights.assign(r.inputs.vertex_lengths.size(), 0.0);
  }
  if (o.tilt_toward == TiltToward::hanging && r.inputs.vertex_lengths.empty()) {  // after the length is known
    const double longest = longest_hair(r.inputs, o);
    r.inputs.hangs = vertex_hangs(*values.chart, hang_probe(boundary(), values.chart->down, false), longest,
                                  options.threads, o.hang_margin);
    if (o.hang_falls_free)
      r.inputs.falls = vertex_hangs(*values.chart, hang_probe(boundary(), values.chart->down, true), longest,
                                    options.threads, o.hang_margin);
  }
  resolved_ = std::move(r);
  return *resolved_;
}

std::shared_ptr<const FlowLookup> StageRun::growth_lookup(const RootSettings& settings) {
  if (growth_lookup_) return growth_lookup_;
  const ScalpChart& chart = *values.chart;
  const ResolvedRoots& roots = resolved_roots(settings);
  growth_lookup_ = std::make_shared<const FlowLookup>(chart.mesh, chart.vertex_normals,
                                                      make_growth_field(chart, roots.inputs, roots.options, exec()),
                                                      kFlowLookupRadius);
  return growth_lookup_;
}

void add_fibre_widths(Curves& curves, double cross_section, int threads) {
  const double root = 2.0 * std::sqrt(cross_section / M_PI);
  curves.widths.resize(curves.points.size());
  parallel_for(static_cast<int>(curves.count()), threads, [&](int c) {
    const std::size_t n = curves.size(c);
    for (std::size_t i = 0; i < n; ++i)
      curves.widths[curves.offsets[c] + i] = static_cast<float>(root * (1.0 - 0.5 * i / std::max<std::size_t>(1, n - 1)));
  });
}

const std::vector<const StageDescriptor*>& stage_table() {
  static const std::vector<const StageDescriptor*> table{&fields_stage(),    &chart_stage(),  &roots_stage(),
                                                         &preguides_stage(), &guides_stage(), &strands_stage(),
                                                         &density_stage()};
  return table;
}

}  // namespace hairfit
