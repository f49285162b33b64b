#include "scalp/roots.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>

#include "core/huge_pages.h"
#include "core/parallel.h"
#include "core/random.h"
#include "scalp/growth_field.h"
#include "scalp/hanging.h"
#include "scalp/hull_hair.h"
#include "scalp/sample_elimination.h"

namespace hairfit {

namespace {

// (1 − w)·a + w·b normalised, for unit a and b; b where they cancel.
Vec3 blend_unit(const Vec3& a, const Vec3& b, double w) {
  const Vec3 v = (1.0 - w) * a + w * b;
  return v.norm() > 1e-9 ? Vec3(v.normalized()) : b;
}

// A map's value at a chart point; 1 when the map is not used.
double map_value(const GreyMap* map, const Vec2& chart) { return map ? map->sample(chart_to_image(chart)) : 1.0; }

double lerp(const std::array<double, 2>& range, double t) { return range[0] + (range[1] - range[0]) * t; }

// The density map over one triangle, by the centroid rule on s² equal sub-triangles, s chosen so
// a sub-triangle is no wider than about half a pixel (the map is bilinear between pixel centres).
struct TriangleDensity {
  double mean = 1.0;              // mean map value (area-weighted)
  double max = 1.0;               // largest sampled value
  double nonzero_fraction = 1.0;  // share of the samples with a non-zero value
};

TriangleDensity triangle_density(const ScalpChart& ch, int t, const GreyMap* map) {
  TriangleDensity d;
  if (!map) return d;
  const Vec3i& f = ch.mesh.triangles[t];
  const Vec2 a = ch.chart[f[0]], b = ch.chart[f[1]], c = ch.chart[f[2]];
  const double longest = std::max({(b - a).norm(), (c - b).norm(), (a - c).norm()});
  const int s = std::clamp(static_cast<int>(std::ceil(longest * std::max(map->width, map->height))), 1, 16);
  double sum = 0.0, top = 0.0;
  int nonzero = 0;
  auto sample = [&](double u, double w) {  // barycentric weights of b and c
    const double v = map->sample(chart_to_image((1 - u - w) * a + u * b + w * c));
    sum += v;
    top = std::max(top, v);
    nonzero += v > 0;
  };
  for (int i = 0; i < s; ++i)
    for (int j = 0; i + j < s; ++j) {
      sample((3 * i + 1) / (3.0 * s), (3 * j + 1) / (3.0 * s));
      if (i + j < s - 1) sample((3 * i + 2) / (3.0 * s), (3 * j + 2) / (3.0 * s));
    }
  for (int k = 0; k < 3; ++k) top = std::max(top, map->sample(chart_to_image(ch.chart[f[k]])));
  d.mean = sum / (s * s);
  d.max = top;
  d.nonzero_fraction = static_cast<double>(nonzero) / (s * s);
  return d;
}

// Candidate-sized arrays live in huge pages (core/huge_pages.h): fresh memory is expensive.
struct Candidates {
  HugeVector<SurfacePoint> where;
  HugeVector<Vec3> positions;
  HugeVector<double> values;  // map value at each candidate
};

// Candidates uniform over the 3D area with `per_area` candidates per cm² where the map is at
// `reference`, thinned by value/reference (binary: kept where value > 0). Each triangle draws
// from its own stream Random(seed, stage, triangle), so the set is the same for any thread count.
Candidates make_candidates(const ScalpChart& ch, const GreyMap* map, const std::vector<TriangleDensity>& density,
                           double per_area, bool binary, RandomStage stage, std::uint64_t seed, int threads) {
  const int nf = static_cast<int>(ch.mesh.triangles.size());
  auto reference = [&](int t) {
    const TriangleDensity& d = density[t];
    return binary ? (d.max > 0 ? 1.0 : 0.0) : d.max;
  };
  // Each triangle's number of draws (the first value of its stream) bounds what it keeps, so the
  // triangles write straight into one array at those offsets, which is then closed up: one copy
  // of the candidates in memory instead of per-triangle lists gathered into a second.
  std::vector<std::size_t> first(nf + 1, 0);
  for (int t = 0; t < nf; ++t) {
    int count = 0;
    if (reference(t) > 0) {
      Random rng(seed, stage, static_cast<std::uint64_t>(t));
      const double expected = per_area * triangle_area(ch.mesh, t) * reference(t);
      const double whole = std::floor(expected);
      count = static_cast<int>(whole) + (rng.uniform() < expected - whole ? 1 : 0);
    }
    first[t + 1] = first[t] + count;
  }
  Candidates all;
  all.where.resize(first[nf]);
  all.positions.resize(first[nf]);
  all.values.resize(first[nf]);
  std::vector<std::size_t> kept(nf, 0);
  parallel_for(nf, threads, [&](int t) {
    const double top = reference(t);
    const std::size_t count = first[t + 1] - first[t];
    if (count == 0) return;
    Random rng(seed, stage, static_cast<std::uint64_t>(t));
    rng.uniform();  // the draw count, above
    std::size_t at = first[t];
    for (std::size_t k = 0; k < count; ++k) {
      const double r = std::sqrt(rng.uniform()), w = rng.uniform();
      SurfacePoint sp;
      sp.triangle = t;
      sp.barycentric = Vec3(1 - r, r * (1 - w), r * w);
      const double accept = rng.uniform();
      const double value = map_value(map, chart_position(ch, sp));
      if (!(value > 0)) continue;  // black: never a root
      if (!binary && accept * top >= value) continue;
      all.where[at] = sp;
      all.positions[at] = surface_position(ch, sp);
      all.values[at] = value;
      ++at;
    }
    kept[t] = at - first[t];
  });
  // Closed up in triangle order (each share moves toward the front, never over one not yet moved).
  std::size_t end = 0;
  for (int t = 0; t < nf; ++t) {
    if (end != first[t]) {
      const std::size_t from = first[t], to = first[t] + kept[t];
      std::copy(all.where.begin() + from, all.where.begin() + to, all.where.begin() + end);
      std::copy(all.positions.begin() + from, all.positions.begin() + to, all.positions.begin() + end);
      std::copy(all.values.begin() + from, all.values.begin() + to, all.values.begin() + end);
    }
    end += kept[t];
  }
  all.where.resize(end);
  all.positions.resize(end);
  all.values.resize(end);
  return all;
}

std::vector<TriangleDensity> density_of_triangles(const ScalpChart& ch, const GreyMap* map, int threads) {
  std::vector<TriangleDensity> density(ch.mesh.triangles.size());
  parallel_for(static_cast<int>(density.size()), threads, [&](int t) { density[t] = triangle_density(ch, t, map); });
  return density;
}

// `flow`: the growth field (FlowModel::field), or null for each root's own direction.
RootSet make_root_set(const ScalpChart& ch, const RootInputs& maps, const RootOptions& o, const DirectionField* flow,
                      std::vector<SurfacePoint> where, int threads) {
  RootSet s;
  const int n = static_cast<int>(where.size());
  s.where = std::move(where);
  s.positions.resize(n);
  s.normals.resize(n);
  s.directions.resize(n);
  s.lengths.resize(n);
  s.chart.resize(n);
  s.heights.resize(n);
  if (o.tilt_toward == TiltToward::hanging) s.hang_weights.resize(n);
  parallel_for(n, threads, [&](int i) {
    const SurfacePoint& sp = s.where[i];
    s.positions[i] = surface_position(ch, sp);
    s.normals[i] = surface_normal(ch, sp);
    s.chart[i] = chart_position(ch, sp);
    const double tilt = maps.tilt ? lerp(o.tilt_range, map_value(maps.tilt.get(), s.chart[i])) : o.tilt;
    const bool from_hull = !maps.vertex_lengths.empty();
    s.lengths[i] = from_hull    ? hang_at(ch, maps.vertex_lengths, sp)
                   : maps.length ? lerp(o.length_range, map_value(maps.length.get(), s.chart[i]))
                                 : o.length;
    double hang = 0.0, hanging = 0.0;
    if (o.tilt_toward == TiltToward::hanging) {
      hang = from_hull ? 0.0 : hang_at(ch, maps.hangs, sp);
      hanging = s.hang_weights[i] = from_hull ? hang_at(ch, maps.vertex_hang_weights, sp) : hang_weight(hang, s.lengths[i]);
    }
    if (flow) {
      const Vec3 fallback = tangent_toward_down(s.normals[i], ch.down, ch.front);
      s.directions[i] = tilted(s.normals[i], field_direction(ch.mesh, *flow, sp.triangle, sp.barycentric, s.normals[i], fallback), tilt);
    } else if (o.tilt_toward == TiltToward::down) {
      s.directions[i] = growth_direction(s.normals[i], ch.down, ch.front, tilt);
    } else {
      // Toward the thicker layer; a hanging root turns toward down by its weight.
      const Vec3 thicker = growth_direction_toward_thicker(s.normals[i], maps.thickness(s.positions[i]).gradient, ch.down,
                                                           ch.front, tilt);
      s.directions[i] = hanging > 0.0 ? blend_unit(thicker, growth_direction(s.normals[i], ch.down, ch.front, tilt), hanging)
                                      : thicker;
    }
    if (o.tilt_toward == TiltToward::hanging && !from_hull)  // hair that hangs, or grows down, ends where the layer below ends
      s.lengths[i] = hanging_length(s.lengths[i], maps.falls.empty() ? hang : hang_at(ch, maps.falls, sp),
                                    std::max(hanging, downness(s.directions[i], s.normals[i], ch.down)));
    if (maps.layer_run && from_hull && s.lengths[i] < maps.stubble_length)
      s.lengths[i] = fitted_stubble(s.lengths[i], maps.layer_run(s.positions[i], s.directions[i], s.lengths[i] / kStubbleShare));
    s.heights[i] = height_of(ch, s.positions[i]);
  });
  return s;
}

void check_options(const ScalpChart& ch, const RootInputs& maps, const RootOptions& o, const Exec& exec) {
  if (exec.threads < 1) throw std::invalid_argument("roots: threads must be ≥ 1");
  if (!(o.density >= 0) || !std::isfinite(o.density)) throw std::invalid_argument("roots: density must be ≥ 0");
  if (!(o.oversampling >= 1)) throw std::invalid_argument("roots: oversampling must be ≥ 1");
  if (o.tilt_toward != TiltToward::down && !maps.thickness)
    throw std::invalid_argument("roots: tilting toward the thicker layer needs the layer's thickness field");
  const std::size_t vertices = ch.mesh.positions.size();
  if ((maps.vertex_lengths.size() != maps.vertex_hang_weights.size()) ||
      (!maps.vertex_lengths.empty() && maps.vertex_lengths.size() != vertices))
    throw std::invalid_argument("roots: hair from the hull needs its length and weight at every scalp vertex");
  if (o.tilt_toward == TiltToward::hanging && maps.vertex_lengths.empty() && maps.hangs.size() != vertices)
    throw std::invalid_argument("roots: hanging hair needs the hang at every scalp vertex");
  if (!maps.falls.empty() && maps.falls.size() != ch.mesh.positions.size())
    throw std::invalid_argument("roots: the hang as hair falls is needed at every scalp vertex, or not at all");
}

std::vector<SurfacePoint> pick(const HugeVector<SurfacePoint>& all, const std::vector<int>& kept) {
  std::vector<SurfacePoint> out;
  out.reserve(kept.size());
  for (int i : kept) out.push_back(all[i]);
  return out;
}

}  // namespace

double fitted_stubble(double length, double run) {
  return std::max(kShortestStubble, std::min(length, kStubbleShare * run));
}

Vec3 growth_direction(const Vec3& normal, const Vec3& down, const Vec3& front, double tilt_degrees) {
  return tilted(normal, tangent_toward_down(normal, down, front), tilt_degrees);
}

Vec3 growth_direction_toward_thicker(const Vec3& normal, const Vec3& thickness_gradient, const Vec3& down,
                                     const Vec3& front, double tilt_degrees) {
  const Vec3 toward_down = tangent_toward_down(normal, down, front);
  const Vec3 g = thickness_gradient - thickness_gradient.dot(normal) * normal;
  const double slope = g.norm();
  if (!(slope > 1e-12)) return tilted(normal, toward_down, tilt_degrees);  // also NaN gradients
  const double w = std::min(1.0, slope / kFlatLayerGradient);
  Vec3 tangent = w * (g / slope) + (1.0 - w) * toward_down;
  // Opposite halves cancel only at w = ½ with ĝ = −down: the gradient decides.
  tangent = tangent.norm() < 1e-9 ? Vec3(g / slope) : Vec3(tangent.normalized());
  return tilted(normal, tangent, tilt_degrees);
}

namespace {

Roots make_roots(const ScalpChart& ch, const RootInputs& maps, const RootOptions& o,
                 const std::vector<TriangleDensity>& density, const DirectionField* flow, int threads) {
  Roots roots;
  double top = 0.0;
  for (int t = 0; t < static_cast<int>(density.size()); ++t) {
    const double area = triangle_area(ch.mesh, t);
    roots.expected_count += o.density * area * density[t].mean;
    roots.hair_area += area * density[t].nonzero_fraction;
    top = std::max(top, density[t].max);
  }
  const long long target = std::llround(roots.expected_count);
  if (target == 0 || !(top > 0)) return roots;
  if (target > 50'000'000) throw std::invalid_argument("roots: more than 50 million roots requested");

  // Candidates at oversampling × the local target density; rounded up so a small set still has
  // enough to choose from.
  const double per_area = o.oversampling * o.density * (1.0 + 1.0 / std::sqrt(static_cast<double>(target)));
  Candidates c = make_candidates(ch, maps.density.get(), density, per_area, false, RandomStage::roots, o.seed, threads);
  const int count = static_cast<int>(c.positions.size());
  roots.candidates = count;
  HugeVector<double>& radius = c.values;  // each value becomes the radius for it, in place
  for (double& r : radius) {
    const double rho = o.density * std::max(r, top / 16.0);  // hairs/cm² here
    r = 1.0 / std::sqrt(2.0 * std::sqrt(3.0) * rho);
  }
  const std::vector<int> kept = eliminate_samples(c.positions.data(), radius.data(), count, static_cast<int>(target), threads);
  roots.pores = make_root_set(ch, maps, o, flow, pick(c.where, kept), threads);
  return roots;
}

PreguideRoots make_preguide_roots(const ScalpChart& ch, const RootInputs& maps, const RootOptions& o,
                                  const std::vector<TriangleDensity>& density, const DirectionField* flow, int threads) {
  PreguideRoots pre;
  pre.spacing = o.preguide_spacing;
  double hair_area = 0.0;
  for (int t = 0; t < static_cast<int>(density.size()); ++t) hair_area += triangle_area(ch.mesh, t) * density[t].nonzero_fraction;
  // Hexagonal packing at spacing s holds one point per (√3/2)s².
  const double rho = 2.0 / (std::sqrt(3.0) * o.preguide_spacing * o.preguide_spacing);
  const long long target = std::llround(hair_area * rho);
  if (target == 0) return pre;
  const double per_area = o.oversampling * rho * (1.0 + 1.0 / std::sqrt(static_cast<double>(target)));
  const Candidates c = make_candidates(ch, maps.density.get(), density, per_area, true, RandomStage::preguides, o.seed, threads);
  const std::vector<double> radius(c.positions.size(), 1.0 / std::sqrt(2.0 * std::sqrt(3.0) * rho));
  const std::vector<int> kept =
      eliminate_samples(c.positions.data(), radius.data(), static_cast<int>(radius.size()), static_cast<int>(target), threads);
  pre.roots = make_root_set(ch, maps, o, flow, pick(c.where, kept), threads);
  return pre;
}

void check_preguide_options(const ScalpChart& ch, const RootInputs& maps, const RootOptions& o, const Exec& exec) {
  check_options(ch, maps, o, exec);
  if (!(o.preguide_spacing > 0)) throw std::invalid_argument("roots: preguide_spacing must be > 0");
}

std::optional<DirectionField> growth_field_for(const ScalpChart& ch, const RootInputs& maps, const RootOptions& o,
                                              const Exec& exec) {
  if (o.flow == FlowModel::local) return std::nullopt;
  return make_growth_field(ch, maps, o, exec);
}

const DirectionField* pointer(const std::optional<DirectionField>& f) { return f ? &*f : nullptr; }

}  // namespace

Roots make_roots(const ScalpChart& ch, const RootInputs& maps, const RootOptions& o, const Exec& exec) {
  check_options(ch, maps, o, exec);
  return make_roots(ch, maps, o, density_of_triangles(ch, maps.density.get(), exec.threads),
                    pointer(growth_field_for(ch, maps, o, exec)), exec.threads);
}

PreguideRoots make_preguide_roots(const ScalpChart& ch, const RootInputs& maps, const RootOptions& o, const Exec& exec) {
  check_preguide_options(ch, maps, o, exec);
  return make_preguide_roots(ch, maps, o, density_of_triangles(ch, maps.density.get(), exec.threads),
                             pointer(growth_field_for(ch, maps, o, exec)), exec.threads);
}

ScalpRoots make_scalp_roots(const ScalpChart& ch, const RootInputs& maps, const RootOptions& o, const Exec& exec) {
  check_preguide_options(ch, maps, o, exec);
  const std::vector<TriangleDensity> density = density_of_triangles(ch, maps.density.get(), exec.threads);
  const std::optional<DirectionField> flow = growth_field_for(ch, maps, o, exec);
  ScalpRoots r;
  r.roots = make_roots(ch, maps, o, density, pointer(flow), exec.threads);
  r.clusters = make_clusters(ch, r.roots, o, exec);
  // Hair from the hull: a fibre runs at most kFibrePastGuide past its guide's tip, which was
  // fitted to the layer. Its pore's length is interpolated between vertices whose falls may part
  // (one down the back, one to the floor beside the ear), and past the guide's tip it would run
  // on straight out of the layer (MakeHuman braid01: 0.4 % of the fibres ended over 6 cm from
  // every guide).
  if (!maps.vertex_lengths.empty())
    for (int i = 0; i < r.roots.pores.size(); ++i)
      r.roots.pores.lengths[i] = std::min(r.roots.pores.lengths[i],
                                          r.clusters.bases.lengths[r.clusters.pore_cluster[i]] + kFibrePastGuide);
  r.preguides = make_preguide_roots(ch, maps, o, density, pointer(flow), exec.threads);
  return r;
}

double longest_hair(const RootInputs& inputs, const RootOptions& o) {
  return inputs.length ? std::max(o.length_range[0], o.length_range[1]) : o.length;
}

bool hangs(const RootSet& roots, int i) {
  return !roots.hang_weights.empty() && roots.hang_weights[i] > kHangingPreguide;
}

Digest digest(const RootSet& s) {
  Digest d;
  d.add(std::string_view("RootSet/1")).add(static_cast<std::int64_t>(s.size()));
  for (const SurfacePoint& sp : s.where) {
    d.add(static_cast<std::int64_t>(sp.triangle));
    d.add(sp.barycentric);
  }
  d.add(s.positions).add(s.normals).add(s.directions).add(s.lengths).add(s.heights);
  for (const Vec2& c : s.chart) d.add_bytes(c.data(), 2 * sizeof(double));
  if (!s.hang_weights.empty()) d.add(s.hang_weights);
  return d;
}

Digest digest(const Roots& r) {
  Digest d = digest(r.pores);
  return d.add(r.expected_count).add(r.hair_area).add(static_cast<std::int64_t>(r.candidates));
}

Digest digest(const PreguideRoots& p) { return digest(p.roots).add(p.spacing); }

}  // namespace hairfit
