#include "guides/guide_solve.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "guides/fall_rest.h"
#include "guides/styled_rest.h"

namespace hairfit {

// Weights of followed neighbours at these distances, nearest first: inverse distance, softened
// so that a neighbour at the very root does not take all the weight; they sum to 1.
std::vector<double> follow_weights(std::vector<double> distances) {
  if (distances.empty()) return distances;
  const double soften = 0.25 * distances.back() + 1e-6;
  double total = 0.0;
  for (double& d : distances) total += d = 1.0 / (d + soften);
  for (double& w : distances) w /= total;
  return distances;
}

// How far to follow a pre-guide at a point: fully inside the acceptable region, not at all once
// it is a boundary width beyond the scalp or the volume (smoothstep in between). A pre-guide that
// could not reach its depth pokes out of the volume; there its direction and curvature would pull
// the guide out after it, so there the boundary term and the rod alone decide.
double follow_trust(const Boundary& boundary, const Vec3& p, double width) {
  const double beyond = std::max(boundary.beyond_scalp(p), boundary.beyond_volume(p));
  if (beyond <= 0.0) return 1.0;
  if (beyond >= width) return 0.0;
  const double x = beyond / width;
  return 1.0 - x * x * (3.0 - 2.0 * x);
}

std::vector<int> all_indices(int count) {
  std::vector<int> all(count);
  std::iota(all.begin(), all.end(), 0);
  return all;
}

namespace {

// The neighbours' quantities at the guide's sample nodes (same normalised arc lengths, since
// every rod has the same number of segments).
GuideTargets make_targets(const RootSet& bases, int b, const PreGuides& preguides, const Boundary& boundary,
                          const GuideOptions& o, std::vector<int>& chosen, std::vector<double>& weights) {
  GuideTargets t;
  t.root = bases.positions[b];
  t.length = bases.lengths[b];
  t.rod = o.rod;
  t.point_forces = o.point_forces;
  t.point_force_weight = o.point_force_weight;
  const Vec3 bend = bending_direction(bases.normals[b], bases.directions[b], o.down, o.front);
  t.model = hair_rod_model(t.length, o.material, RodRoot{t.root, root_frame(bases.directions[b], bend)}, boundary.scalp.get());
  // Styled along its path: a hanging hair along its fall (weightless), the rest along the flow;
  // stubble stays straight, since its path would read the fields within a cell or two of its root
  // (see rests_unloaded).
  const bool styled = o.styled && t.length >= stubble_length(*boundary.volume);
  const bool along_fall = styled && hangs(bases, b) && o.material.gravity.isZero(0.0) && !o.material.contact.active();
  if (along_fall) {
    t.model.kappa_hat = fall_rest(fall_region(boundary, o.down, o.front), t.root, bases.normals[b], t.model.root_frame,
                                  t.length, immersion_share(o.depth_range, bases.heights[b]),
                                  o.rod.segments);
  } else if (styled && !hangs(bases, b)) {
    t.model.kappa_hat = styled_rest(*o.styled, boundary, t.root, t.model.root_frame, t.length,
                                    immersion_share(o.depth_range, bases.heights[b]), o.rod.segments);
  }
  const int segments = o.rod.segments;
  const int k_max = std::min(o.samples, segments);
  for (int k = 0; k <= k_max; ++k) {
    t.sample_nodes.push_back(static_cast<int>(std::lround(static_cast<double>(k) * segments / k_max)));
    t.sample_weights.push_back((k == 0 || k == k_max ? 0.5 : 1.0) / k_max);
  }

  // The nearest pre-guides by root distance, weighted by inverse distance (softened so a
  // pre-guide at the very root does not take all the weight).
  chosen = nearest(all_indices(preguides.size()), [&](int j) { return preguides.items[j].root; }, t.root, o.neighbours);
  const int count = static_cast<int>(chosen.size());
  weights.clear();
  for (int j : chosen) weights.push_back((preguides.items[j].root - t.root).norm());
  weights = follow_weights(weights);
  for (int i = 0; i < count; ++i) {
    GuideTargets::Neighbour nb;
    nb.weight = weights[i];
    // At the same arc length from the root (cm), not the same share of the length: hair from
    // the hull is as long as its layer lets it, so neighbours differ in length, and a share of
    // theirs would put a guide's hanging part beside a neighbour's part on the skull. Past a
    // neighbour's tip its tip says where it went. Darboux vectors are per unit normalised arc
    // length, so they scale by the ratio of the lengths.
    const PreGuide& pre = preguides.items[chosen[i]];
    const double ratio = pre.length > 0.0 ? t.length / pre.length : 1.0;  // exactly 1 for equal lengths
    const FibreShape& shape = pre.shape;
    for (int node : t.sample_nodes) {
      const double at = std::min(node * ratio, static_cast<double>(segments));
      const int k = static_cast<int>(at);
      const double u = at - k;
      const auto lerp = [&](const std::vector<Vec3>& v) { return u == 0.0 ? v[k] : Vec3((1.0 - u) * v[k] + u * v[k + 1]); };
      nb.tangents.push_back(u == 0.0 ? shape.tangents[k] : Vec3(lerp(shape.tangents).normalized()));
      nb.darboux.push_back(ratio * lerp(shape.darboux));
      nb.trust.push_back(follow_trust(boundary, lerp(shape.nodes), o.boundary_width));
    }
    t.neighbours.push_back(std::move(nb));
  }
  // A hair at rest along its fall keeps to its own rest curvature in F2: its neighbours rest along
  // their own falls, whose corners (where a fall meets the skin or the hull) lie at other arc
  // lengths, and matching their curvature bent the guides off their falls into a tangle (the
  // straight fixture at default keys: F2 was 4.2 of a cost of 4.4).
  if (along_fall) {
    const FibreShape rest = fibre_shape(t.model, t.root, t.length, t.rod, Vec3::Zero(), Vec3::Zero());
    for (GuideTargets::Neighbour& nb : t.neighbours)
      for (std::size_t k = 0; k < t.sample_nodes.size(); ++k) nb.darboux[k] = rest.darboux[t.sample_nodes[k]];
  }
  t.boundary = &boundary;
  t.weights = o.weights;
  t.form = o.boundary;
  t.outside_penalty = o.outside_penalty;
  t.boundary_width = o.boundary_width;
  return t;
}

// Whether a solved shape folds onto itself: its ends closer than kFoldedChord of its length (a
// hair that curls through a whole turn; MakeHuman bob01's hanging guides keep 0.3–1).
constexpr double kFoldedChord = 0.25;
bool folded(const FibreShape& shape, double length) {
  return (shape.nodes.back() - shape.nodes.front()).norm() < kFoldedChord * length;
}

// How far (cm) a shape's worst node after the root lies beyond the scalp or the volume (≤ 0: none
// does; the root lies on the scalp by construction).
double worst_excursion(const FibreShape& shape, const Boundary& boundary) {
  double worst = -std::numeric_limits<double>::infinity();
  for (std::size_t i = 1; i < shape.nodes.size(); ++i)
    worst = std::max({worst, boundary.beyond_scalp(shape.nodes[i]), boundary.beyond_volume(shape.nodes[i])});
  return worst;
}

// Iterations the retry of a guide that grazes the boundary (ends outside by less than the
// boundary width) may take from its other start. MakeHuman ponytail01, hair styled along its flow,
// seeds 11 / 2: guide nodes inside 0.9867 / 0.9898 without the retry, 0.9940 / 0.9939 with it
// uncapped (33.6 / 27.7 evaluations a guide), 0.9911 / 0.9939 capped at 10 (29.6 / 24.1); short04's
// seed 11 0.9823 → 0.9897 at 10 (29.0 → 32.6 evaluations), 0.9857 at 5 (30.9)
// (bench/results/thin_shells.md).
constexpr int kInsideRetryIterations = 10;

// The relative cost decrease at which the six-load stage of a guide with point forces stops. A
// guide that stays inside keeps that solve, so this is the price of the stage: on the MakeHuman
// fixtures evaluations per guide fall from 17–43 (stage at guides.tolerance, 1e-5) to 12–29, the
// followed direction mismatch rises by at most 15 % (ponytail01 0.058 → 0.067), and guide nodes
// inside stay within 0.003 (bench/results/thin_shells.md).
constexpr double kTerminalStageTolerance = 1e-3;

// optimise_guide, in two stages for a start without point forces: the paper's six loads first;
// then, only where that guide leaves the acceptable region, every load from its optimum with
// F_k = 0. The point forces only ever refine the terminal-load guide (its cost is where the
// second solve starts, and LM accepts only descent), and act only where the layer has to hold the
// hair. Solved together from the start, the larger problem ended in worse minima: on MakeHuman
// short04 with three forces, 4 guides with 2–4.5× the cost and 21–35 nodes up to 3 mm out of the
// layer.
GuideSolve optimise_in_stages(const GuideTargets& targets, const double* start, const GuideOptions& o,
                              const StallTest& stall, const ShootingResult* near, const Boundary& boundary) {
  const int loads = targets.load_count();
  if (targets.point_forces == 0 || std::any_of(start + 6, start + loads, [](double v) { return v != 0.0; }))
    return optimise_guide(targets, start, o.max_iterations, o.tolerance, stall, near);
  GuideTargets terminal = targets;
  terminal.point_forces = 0;
  const double first_tolerance = std::max(o.tolerance, kTerminalStageTolerance);
  const GuideSolve first = optimise_guide(terminal, start, o.max_iterations, first_tolerance, stall, near);
  Vec3 torque;
  if (worst_excursion(solved_shape(terminal, first, torque), boundary) <= 0.0) return first;
  double from[kMaxGuideLoads] = {};
  std::copy(first.eta, first.eta + 6, from);
  GuideSolve second = optimise_guide(targets, from, o.max_iterations, o.tolerance, stall, near);
  second.iterations += first.iterations;
  second.evaluations += first.evaluations;
  second.initial_cost = first.initial_cost;
  return second;
}

// Whether guide b keeps its rest shape, unloaded: a weightless rod, free of the scalp (so solved by
// single shooting, whose zero loads are its rest), shorter than stubble_length. Such a guide lies
// within a cell or two of the fields, whose trilinear values cannot tell a layer thinner than a
// cell from outside it, so the boundary term has nothing true to steer it by; its neighbours,
// centimetres long, are no guide to its curvature either. Optimised, the carved hulls' hairline
// stubble (0.15–0.25 cm, roots 0.05–0.3 cm below the hull) was bent into hooks and folds, turning
// 30–120° and crossing the layer: braids, 8 of its 89 guides under 0.3 cm with over a fifth of
// their nodes outside, 26–253 evaluations each (docs/results/carved-flow.md). At rest it runs
// straight along its root's direction, as long as the roots let its layer hold it (scalp/roots.h,
// fitted_stubble).
bool rests_unloaded(const GuideTargets& targets, const Boundary& boundary) {
  const RodModel& m = targets.model;
  return targets.length < stubble_length(*boundary.volume) && m.force_per_length.isZero(0.0) && !m.support;
}

// The solve of a guide at rest: every load 0, its cost that of the rest shape.
GuideSolve rest_solve(const GuideTargets& targets) {
  GuideSolve solve;
  solve.converged = true;
  solve.termination = "AT_REST";
  solve.initial_cost = solve.final_cost = 0.5 * evaluate_guide_terms(targets, solve.eta).total;
  return solve;
}

}  // namespace

Guide solve_guide(const GuideProblem& problem, int b, const GuideSolveSetup& setup) {
  const RootSet& bases = problem.bases;
  const PreGuides& preguides = problem.preguides;
  const Boundary& boundary = problem.boundary;
  const GuideOptions& o = problem.options;
  const StallTest& stall = setup.stall;
  const ShootingResult* near = setup.near;
  Guide g;
  g.root = bases.positions[b];
  g.normal = bases.normals[b];
  g.direction = bases.directions[b];
  g.length = bases.lengths[b];
  GuideTargets targets = make_targets(bases, b, preguides, boundary, o, g.neighbours, g.neighbour_weights);
  targets.density = setup.density;
  targets.density_term = setup.term;
  targets.density_ceiling = setup.density_ceiling;

  // Start: straight (the paper) or the neighbours' dimensionless loads, weighted (warm start);
  // no interior point force (a pre-guide has none).
  double start[kMaxGuideLoads] = {};
  const int loads = targets.load_count();
  if (setup.start)
    std::copy(setup.start, setup.start + loads, start);
  else if (o.warm_start)
    add_weighted_loads(preguides.items, g.neighbours, g.neighbour_weights, start);
  const bool at_rest = rests_unloaded(targets, boundary);
  GuideSolve solve = at_rest ? rest_solve(targets) : optimise_in_stages(targets, start, o, stall, near, boundary);
  g.shape = solved_shape(targets, solve, g.terminal_torque);
  // The solve can stop in a local minimum that runs through the head or out of the
  // volume well past the boundary ramp, or that folds the guide onto itself (where neighbouring
  // pre-guides pull apart): then the other start (straight ↔ the neighbours' loads) is tried too,
  // and the lower cost kept, unless it is the same start (a heavy rod's solve reads only the
  // start's force), which would repeat the same solve.
  // A weightless guide that ends outside by less than that is tried from the other start as well,
  // for at most kInsideRetryIterations, and that solve is kept if it lies wholly inside.
  double other[kMaxGuideLoads] = {};
  if (std::all_of(start, start + loads, [](double v) { return v == 0.0; }))
    add_weighted_loads(preguides.items, g.neighbours, g.neighbour_weights, other);
  const bool same_start = std::equal(start, start + start_loads_read(solve.scheme), other);
  const double worst = worst_excursion(g.shape, boundary);
  const bool astray = worst > o.boundary_width || folded(g.shape, g.length);
  const bool grazing = !astray && worst > 0.0 && solve.scheme == RodScheme::single_shooting;
  if (!at_rest && !same_start && (astray || grazing)) {
    GuideOptions retry_options = o;
    if (grazing) retry_options.max_iterations = std::min(o.max_iterations, kInsideRetryIterations);
    GuideSolve retry = optimise_in_stages(targets, other, retry_options, stall, near, boundary);
    const int iterations = solve.iterations + retry.iterations, evaluations = solve.evaluations + retry.evaluations;
    Vec3 retry_torque;
    FibreShape retry_shape = solved_shape(targets, retry, retry_torque);
    const bool better = astray ? retry.final_cost < solve.final_cost : worst_excursion(retry_shape, boundary) <= 0.0;
    if (better) {
      solve = std::move(retry);
      g.shape = std::move(retry_shape);
      g.terminal_torque = retry_torque;
    }
    solve.iterations = iterations;
    solve.evaluations = evaluations;
  }
  if (setup.pieces && solve.scheme == RodScheme::multiple_shooting) *setup.pieces = solve.solution;
  g.force = Vec3(solve.eta[0], solve.eta[1], solve.eta[2]);
  g.root_moment = Vec3(solve.eta[3], solve.eta[4], solve.eta[5]);
  for (int k = 0; k < targets.point_forces; ++k)
    g.point_forces.emplace_back(solve.eta[6 + 3 * k], solve.eta[7 + 3 * k], solve.eta[8 + 3 * k]);
  const RodScales scales = rod_scales(hair_rod(g.length, o.material));
  g.force_scale = scales.force;
  g.moment_scale = scales.moment;
  g.iterations = solve.iterations;
  g.evaluations = solve.evaluations;
  g.converged = solve.converged;
  g.termination = solve.termination;
  g.initial_cost = 2.0 * solve.initial_cost;  // Ceres reports ½Σr²
  if (o.material.contact.active()) {
    // The share counts the nodes beyond the first tenth of the hair: every root sits in the layer.
    const std::size_t n = g.shape.nodes.size(), first = (n + 9) / 10;
    int touching = 0;
    for (std::size_t i = 0; i < n; ++i) {
      const Vec3& p = g.shape.nodes[i];
      g.contact_force = std::max(g.contact_force, contact_force(*boundary.scalp, o.material.contact, p).norm());
      if (i >= first) touching += boundary.scalp->value(p) < o.material.contact.layer;
    }
    g.contact_share = n > first ? static_cast<double>(touching) / static_cast<double>(n - first) : 0.0;
  }
  if (setup.use == GuideUse::start) return g;
  const GuideTerms terms = solved_terms(targets, solve);
  g.cost = terms.total;
  g.f1 = terms.f1;
  g.f2 = terms.f2;
  g.f3 = terms.f3;
  g.f4 = terms.f4;
  g.f5 = terms.f5;
  return g;
}

// A guide with the density term, by continuation: first without F4, as make_guides solves it,
// then with F4 from that optimum (`plain`). F4 then perturbs a shape that already follows the
// pre-guides inside the acceptable region. Started from the pre-guides' loads directly,
// Levenberg–Marquardt with F4 on ended in local minima behind the scalp (smoke fixture, CDM: a
// guide 3.3 cm deep, its wisp leaving density 2.35 cm inside the head; the paper scale, CDM:
// 3.9 % of guide nodes outside the region against 0.1 % without F4).
// Iterations and evaluations count both solves; the rest describes the second.
Guide solve_guide_with_density(const GuideProblem& problem, int b, const Guide& plain, const DensityGrid& density,
                               const DensityTermOptions& term, double ceiling, const StallTest& stall) {
  double start[kMaxGuideLoads] = {};
  for (int a = 0; a < 3; ++a) {
    start[a] = plain.force[a];
    start[3 + a] = plain.root_moment[a];
  }
  for (std::size_t k = 0; k < plain.point_forces.size(); ++k)
    for (int a = 0; a < 3; ++a) start[6 + 3 * k + a] = plain.point_forces[k][a];
  GuideSolveSetup setup;
  setup.density = density;
  setup.term = term;
  setup.density_ceiling = ceiling;
  setup.start = start;
  setup.stall = stall;
  Guide g = solve_guide(problem, b, setup);
  g.iterations += plain.iterations;
  g.evaluations += plain.evaluations;
  return g;
}

}  // namespace hairfit
