#include "guides/preguides.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include "core/parallel.h"
#include "guides/fall_rest.h"
#include "guides/layer_preguide.h"
#include "rod/rod_point_forces.h"
#include "rod/rod_shooting.h"

namespace hairfit {

namespace {

FibreShape shape_of(const Vec3& root, double length, int nodes_count, const std::vector<double>& nodes,
                    const std::vector<double>& frames, const std::vector<double>& curvature) {
  FibreShape shape;
  shape.nodes.resize(nodes_count);
  shape.tangents.resize(nodes_count);
  shape.darboux.resize(nodes_count);
  for (int i = 0; i < nodes_count; ++i) {
    const Eigen::Map<const Mat3> frame(&frames[9 * i]);
    shape.nodes[i] = root + length * Eigen::Map<const Vec3>(&nodes[3 * i]);
    shape.tangents[i] = frame.col(2);
    shape.darboux[i] = frame * Eigen::Map<const Vec3>(&curvature[3 * i]);
  }
  return shape;
}

}  // namespace

FibreShape fibre_shape(const RodModel& model, const Vec3& root, double length, const RodDiscretisation& rod,
                       const Vec3& force, const Vec3& root_moment, Vec3* terminal_moment) {
  const double loads[6] = {force.x(), force.y(), force.z(), root_moment.x(), root_moment.y(), root_moment.z()};
  return fibre_shape(model, root, length, rod, loads, 0, terminal_moment);
}

FibreShape fibre_shape(const RodModel& model, const Vec3& root, double length, const RodDiscretisation& rod,
                       const double* loads, int point_forces, Vec3* terminal_moment) {
  const int n = rod.segments + 1;
  std::vector<double> nodes(3 * n), frames(9 * n), curvature(3 * n);
  Vec3 m1;
  integrate_rod_with_point_forces<double>(model, rod.integrator, rod.segments, loads, loads + 3, loads + 6,
                                          point_forces, m1.data(),
                                          RodTrace<double>{nodes.data(), frames.data(), curvature.data(), nullptr});
  if (terminal_moment) *terminal_moment = m1;
  return shape_of(root, length, n, nodes, frames, curvature);
}

FibreShape fibre_shape(const RodModel& model, const Vec3& root, double length, const RodDiscretisation& rod,
                       const ShootingResult& solution) {
  if (solution.breaks.size() < 2) return fibre_shape(model, root, length, rod, solution.terminal_force, solution.root_moment);
  const int n = rod.segments + 1;
  std::vector<double> nodes(3 * n), frames(9 * n), curvature(3 * n);
  trace_pieces(model, rod.integrator, rod.segments, solution,
               RodTrace<double>{nodes.data(), frames.data(), curvature.data(), nullptr});
  return shape_of(root, length, n, nodes, frames, curvature);
}

namespace {

// The free end of a solved rod in rod units (the root at the origin, lengths in L): position r(1)
// and tangent d3(1), which is all a load step needs of the shape.
struct RodEnd {
  Vec3 position;
  Vec3 tangent;
};

// Newton steps a heavy rod's solve from rest may take: its load continuation follows hair that
// grows up as it falls over onto the head in small steps (about 260 for 22–26 cm crown hair on
// the straight fixture).
constexpr int kRestBudget = 1000;

// The cantilever m(1; P·b̂, m(0)) = 0 (t_L = 0) at one load P, from a predictor. Several
// equilibria exist at the same load (curled rods), so the loads are reached by continuation from
// the unloaded rod (march_load below), which keeps the path on the branch connected to it.
class Cantilever {
 public:
  Cantilever(const Vec3& bend, const RodDiscretisation& rod) : bend_(bend), rod_(rod) {}

  // Solves at load P from `at` (its m(0), and its pieces when it has them); on success `at` becomes
  // the solution. Single shooting (Newton until |m(1)| ≤ 1e-10·max(1, P)) up to kHeavyRod; beyond,
  // m(1) depends on m(0) like exp(√P) and the rod library's multiple shooting takes over, warm
  // started from the pieces of the nearby solution, which stay a good start where a sweep from
  // m(0) alone would diverge. A single-shooting solution also hands back its rod's end (the
  // integration that confirmed it traced it), bit for bit what fibre_shape would trace again.
  bool solve(const RodModel& model, double load, ShootingResult& at, int& solves, std::optional<RodEnd>& end) const {
    end.reset();
    const Vec3 force = load * bend_;
    if (rod_scheme(model, load) == RodScheme::multiple_shooting) {
      ShootingOptions options;
      static_cast<RodDiscretisation&>(options) = rod_;
      // A solve from nothing (the rod under its weight alone) continues from the unloaded rod; a
      // failed warm start returns at once, and the caller shortens its load step.
      options.restart_from_rest = at.breaks.empty() && at.root_moment.isZero();
      options.max_iterations = options.restart_from_rest ? kRestBudget : 10;
      const ShootingResult r = shoot_root_moment(model, force, Vec3::Zero(), at, options);
      solves += std::max(1, r.iterations);
      if (r.converged) at = r;
      return r.converged;
    }
    const SingleShot shot = shoot_single(model, rod_, force, Vec3::Zero(), at.root_moment, 1e-10 * std::max(1.0, load), 10);
    solves += shot.integrations;
    if (!shot.converged) return false;
    at = ShootingResult{};  // one piece: the shape is one integration from m(0)
    at.root_moment = shot.root_moment;
    at.terminal_force = force;
    at.force_per_length = model.force_per_length;
    at.converged = true;
    end = RodEnd{shot.end_position, shot.end_tangent};
    return true;
  }

 private:
  Vec3 bend_;
  RodDiscretisation rod_;
};

constexpr double kMaxTipTurn = 0.26;  // radians (15°) of tip rotation per accepted load step
constexpr int kNewtonBudget = 250;    // Newton steps per pre-guide for following its branch

// A guess for `next` from the solution `at`: its pieces, with m(0) replaced by a predictor.
ShootingResult predicted(const ShootingResult& at, const Vec3& root_moment) {
  ShootingResult guess = at;
  guess.root_moment = root_moment;
  return guess;
}

// The rod under its own weight alone (no terminal load), by continuation in the weight from the
// straight rod: a heavy hair (ρAgL³/EI is ~10³ for 30 cm of hair) has many equilibria, and only
// this path finds the drooping one. Beyond kHeavyRod each level starts from the pieces of the one
// before. A heavy rod or one on the scalp is first solved from rest under the full weight, whose
// load continuation (rod_shooting.h) follows the branch of the unloaded rod, falling over where
// hair that grows up buckles. Where that continuation stalls (crown hair that stands nearly
// upright), the weight is followed in shares as for a light rod, each level warm-started from
// the last and its step held to a tip turn of kMaxTipTurn.
struct WeightedRod {
  ShootingResult solution;   // at `share` of the weight
  std::optional<RodEnd> end;  // its rod's end when the solve traced it
  double share = 0.0;         // 1, or the share reached before a fold or the budget
};

WeightedRod carry_weight(const Cantilever& cantilever, const RodModel& model, const RodDiscretisation& rod,
                         const Vec3& direction, int& solves) {
  WeightedRod w;
  RodModel scaled = model;
  double share_step = model.force_per_length.norm() > 0.0 ? 0.05 : 1.0;
  const bool from_rest = rod_scheme(model) == RodScheme::multiple_shooting;
  if (from_rest) {
    std::optional<RodEnd> end;
    ShootingResult trial;
    if (cantilever.solve(model, 0.0, trial, solves, end)) {
      w.solution = trial;
      w.end = end;
      w.share = 1.0;
    }
  }
  Vec3 m_prev = Vec3::Zero(), tip_prev = direction;
  double share_prev = 0.0;
  const int budget = solves + (from_rest ? kRestBudget : kNewtonBudget);
  while (w.share < 1.0 && share_step > 1e-5 && solves < budget) {
    const double next = std::min(1.0, w.share + share_step);
    scaled.force_per_length = next * model.force_per_length;
    const Vec3& m0 = w.solution.root_moment;
    const Vec3 predictor =
        w.share > share_prev ? Vec3(m0 + (m0 - m_prev) * ((next - w.share) / (w.share - share_prev))) : m0;
    ShootingResult trial = predicted(w.solution, predictor);
    std::optional<RodEnd> end;
    bool accepted = cantilever.solve(scaled, 0.0, trial, solves, end) &&
                    (trial.root_moment - predictor).norm() <= 0.1 * (1.0 + m0.norm());
    Vec3 tip = tip_prev;
    if (accepted) {
      tip = end ? end->tangent : fibre_shape(scaled, Vec3::Zero(), 1.0, rod, trial).tangents.back();
      accepted = std::acos(std::clamp(tip.dot(tip_prev), -1.0, 1.0)) <= kMaxTipTurn;
    }
    if (!accepted) {
      share_step *= 0.5;
      continue;
    }
    m_prev = m0;
    share_prev = w.share;
    w.solution = trial;
    w.end = end;  // traced under the full weight once the share reaches 1
    tip_prev = tip;
    w.share = next;
    share_step = std::min(share_step * 1.5, 0.25);
  }
  return w;
}

// A solved state of the cantilever at one load, with its rod's free end (rod units: the root at
// the origin, lengths in L, the model's axes).
struct MarchState {
  double load = 0.0;
  ShootingResult solution;  // m(0), and the pieces of a heavy rod
  RodEnd end{Vec3::Zero(), Vec3::Zero()};
  const Vec3& m0() const { return solution.root_moment; }
};

// The rod's end of a solution: as its solve traced it (single shooting), else traced again.
RodEnd rod_end(const RodModel& model, const RodDiscretisation& rod, const ShootingResult& solution,
               const std::optional<RodEnd>& traced) {
  if (traced) return *traced;
  const FibreShape shape = fibre_shape(model, Vec3::Zero(), 1.0, rod, solution);
  return RodEnd{shape.nodes.back(), shape.tangents.back()};
}

// m(0) at `load` extrapolated along the branch from the solutions a, b, c (loads increasing):
// the parabola through all three where their loads differ, else the line through the last two,
// else, from c alone, c's m(0) plus the moment of the added tip force about the root with c's
// shape held (m(0) = m(1) + ∫ d3 × n ds, n the tip force: the chord × the force), which is m(0)'s
// derivative in the load up to the shape's own response. Quadratic prediction starts Newton
// nearer its root than the line does; the first step from the unloaded rod, predicted as m(0)
// unchanged, is rejected twice (Newton lands beyond 0.1 of it) before 1/16 is taken.
Vec3 extrapolated(const MarchState& a, const MarchState& b, const MarchState& c, double load, const Vec3& bend) {
  if (c.load > b.load && b.load > a.load) {
    const double wa = ((load - b.load) * (load - c.load)) / ((a.load - b.load) * (a.load - c.load));
    const double wb = ((load - a.load) * (load - c.load)) / ((b.load - a.load) * (b.load - c.load));
    const double wc = ((load - a.load) * (load - b.load)) / ((c.load - a.load) * (c.load - b.load));
    return wa * a.m0() + wb * b.m0() + wc * c.m0();
  }
  if (c.load > b.load) return c.m0() + (c.m0() - b.m0()) * ((load - c.load) / (c.load - b.load));
  return c.m0() + (load - c.load) * c.end.position.cross(bend);
}

// Natural-parameter continuation in the load from `start`: visit(state) is called for `start`
// and for every state accepted after it, in order, until it returns false, the load reaches
// max_load, or the branch cannot be followed further (load steps below 1e-4 of the load, or the
// Newton budget spent). A step is accepted where Newton lands near its predictor and the tip
// turns by at most kMaxTipTurn, toward the pull, never back; else the step is halved.
template <class Visit>
void march_load(const Cantilever& cantilever, const RodModel& model, const RodDiscretisation& rod, const Vec3& bend,
                const MarchState& start, double max_load, int budget, int& solves, Visit&& visit) {
  if (!visit(start)) return;
  MarchState earliest = start, previous = start, current = start;  // the last three accepted
  double step = 0.25;
  while (current.load < max_load && step > 1e-4 * (1.0 + current.load) && solves < budget) {
    MarchState next;
    next.load = std::min(max_load, current.load + step);
    const Vec3 predictor = extrapolated(earliest, previous, current, next.load, bend);
    next.solution = predicted(current.solution, predictor);
    std::optional<RodEnd> traced;
    bool accepted = cantilever.solve(model, next.load, next.solution, solves, traced) &&
                    (next.m0() - predictor).norm() <= 0.1 * (1.0 + current.m0().norm());
    if (accepted) {
      next.end = rod_end(model, rod, next.solution, traced);
      const Vec3& tip = next.end.tangent;
      accepted = std::acos(std::clamp(tip.dot(current.end.tangent), -1.0, 1.0)) <= kMaxTipTurn &&
                 tip.dot(bend) >= current.end.tangent.dot(bend) - 1e-9;
    }
    if (!accepted) {
      step *= 0.5;
      continue;
    }
    if (!visit(next)) return;
    earliest = previous;
    previous = current;
    current = next;
    step = std::min(step * 1.5, 0.3 * (1.0 + current.load));
  }
}

// The load march of a rod whose loads are all at its tip and whose natural shape is straight (no
// weight, no curl) depends only on its bending and twisting compliance: in the frame of its root
// (direction d3, bending direction d1) it is the same dimensionless problem whatever the root,
// direction and length. It is followed once per compliance, root frame the identity, pulled along
// e1, and every such pre-guide replays it, rotated into its own root frame, until its tip reaches
// its depth. On the paper-scale scene all 435 pre-guides share one march.
struct PreguideMarch {
  Vec3 compliance = Vec3::Zero();
  std::vector<MarchState> states;  // every accepted state, the unloaded rod first
  int solves = 0;                  // Newton steps the march took
};

bool replays_march(const RodModel& model, const PreguideOptions& o) {
  const bool straight = std::all_of(model.kappa_hat.begin(), model.kappa_hat.end(), [](const Vec3& k) { return k.isZero(0.0); });
  return straight && model.force_per_length.isZero(0.0) && !o.material.contact.active() && o.max_load <= kHeavyRod;
}

PreguideMarch shared_march(const Vec3& compliance, const PreguideOptions& o) {
  PreguideMarch m;
  m.compliance = compliance;
  RodModel model;
  model.compliance = compliance;  // straight, weightless, root frame the identity
  const Vec3 bend = Vec3::UnitX();
  const Cantilever cantilever(bend, o.rod);
  // The unloaded rod, solved as a pre-guide's weight continuation solves it.
  MarchState start;
  std::optional<RodEnd> traced;
  cantilever.solve(model, 0.0, start.solution, m.solves, traced);
  start.end = rod_end(model, o.rod, start.solution, traced);
  march_load(cantilever, model, o.rod, bend, start, o.max_load, kNewtonBudget, m.solves, [&](const MarchState& s) {
    m.states.push_back(s);
    return true;
  });
  return m;
}

PreGuide solve_preguide(const RootSet& roots, int i, const Boundary& boundary, const PreguideOptions& o,
                        const std::vector<PreguideMarch>& shared) {
  PreGuide g = preguide_start(roots, i, boundary, o);
  const Vec3 bend = bending_direction(g.normal, g.direction, o.down, o.front);
  const RodModel model = hair_rod_model(g.length, o.material, RodRoot{g.root, root_frame(g.direction, bend)}, boundary.scalp.get());
  const Cantilever cantilever(bend, o.rod);

  // The states the march visits, with their misses (miss > 0: the tip is not yet deep enough):
  // the best tip so far, and the bracket [above, below] once the tip passes its depth.
  struct Visited {
    MarchState state;
    double miss = 0.0;
  };
  auto visited = [&](const MarchState& s) {
    return Visited{s, boundary.volume->value(g.root + g.length * s.end.position) + g.target_depth};
  };
  std::optional<Visited> best, previous;
  Visited above, below;
  bool bracketed = false;
  int rest_solves = 0;  // Newton steps a heavy rod's weight took, on top of the budgets below
  auto visit = [&](const MarchState& s) {
    const Visited v = visited(s);
    if (!best || std::fabs(v.miss) < std::fabs(best->miss)) best = v;
    if (v.miss <= 0.0) {
      above = previous ? *previous : v;
      below = v;
      bracketed = true;
      return false;
    }
    previous = v;
    return true;
  };

  const bool replay = replays_march(model, o);
  const auto march = std::find_if(shared.begin(), shared.end(),
                                  [&](const PreguideMarch& m) { return replay && m.compliance == model.compliance; });
  if (march != shared.end()) {
    // The shared march in this root frame: m(0), the end and the force rotate with it.
    const Mat3& frame = model.root_frame;
    for (const MarchState& s : march->states) {
      MarchState w;
      w.load = s.load;
      w.solution.root_moment = frame * s.m0();
      w.solution.terminal_force = s.load * bend;
      w.solution.force_per_length = Vec3::Zero();
      w.solution.converged = true;
      w.end = RodEnd{frame * s.end.position, frame * s.end.tangent};
      if (!visit(w)) break;
    }
  } else {
    // The rod under its own weight first, then the bending load's march from there.
    const WeightedRod weighted = carry_weight(cantilever, model, o.rod, g.direction, g.solves);
    if (rod_scheme(model) == RodScheme::multiple_shooting) rest_solves = g.solves;
    if (weighted.share < 1.0) {
      // The weight could be followed to this share of itself only: a fold, beyond which the rod
      // snaps through to an equilibrium no continuation from here reaches. The pre-guide keeps the
      // last equilibrium it reached, unbent by any terminal force, and is flagged.
      g.weight_share = weighted.share;
      g.root_moment = weighted.solution.root_moment;
      g.shape = fibre_shape(carrying_share(model, weighted.share), g.root, g.length, o.rod, weighted.solution);
      g.depth = -boundary.volume->value(g.shape.nodes.back());
      return g;
    }
    MarchState start;
    start.solution = weighted.solution;
    start.solution.force_per_length = model.force_per_length;
    start.end = rod_end(model, o.rod, start.solution, weighted.end);
    march_load(cantilever, model, o.rod, bend, start, o.max_load, kNewtonBudget + rest_solves, g.solves, visit);
  }

  const double tolerance = 1e-3 * std::max(g.thickness, 1e-2);
  // Regula falsi on the load inside the bracket, Illinois' variant (an end kept twice in a row has
  // its miss halved, so both ends move), each solve started from m(0) interpolated between the
  // ends, or, should that fail, from the shallower end. On the paper-scale scene this took
  // 11 Newton steps a pre-guide where bisection from the shallower end took 28.
  double above_miss = above.miss, below_miss = below.miss;  // the ends' misses as the secant weighs them
  int kept = 0;  // the end kept by the last step: +1 above, −1 below
  for (int k = 0; bracketed && k < 60 && std::fabs(best->miss) > tolerance && below.state.load > above.state.load &&
                  g.solves < 2 * kNewtonBudget + rest_solves;
       ++k) {
    const double t = std::clamp(above_miss / (above_miss - below_miss), 0.0, 1.0);
    MarchState mid;
    mid.load = above.state.load + t * (below.state.load - above.state.load);
    mid.solution = predicted(above.state.solution, above.state.m0() + t * (below.state.m0() - above.state.m0()));
    std::optional<RodEnd> traced;
    if (!cantilever.solve(model, mid.load, mid.solution, g.solves, traced)) {
      mid.solution = above.state.solution;
      if (!cantilever.solve(model, mid.load, mid.solution, g.solves, traced)) break;
    }
    mid.end = rod_end(model, o.rod, mid.solution, traced);
    const Visited v = visited(mid);
    if (std::fabs(v.miss) < std::fabs(best->miss)) best = v;
    if (v.miss > 0.0) {
      above = v;
      above_miss = v.miss;
      if (kept == -1) below_miss *= 0.5;
      kept = -1;
    } else {
      below = v;
      below_miss = v.miss;
      if (kept == 1) above_miss *= 0.5;
      kept = 1;
    }
  }
  g.force = best->state.load * bend;
  g.root_moment = best->state.m0();
  g.shape = fibre_shape(model, g.root, g.length, o.rod, best->state.solution);
  g.depth = -boundary.volume->value(g.shape.nodes.back());
  g.reached = best->miss <= tolerance;
  return g;
}

}  // namespace

HangingRod hang_under_weight(const RodModel& model, const RodDiscretisation& rod) {
  const Cantilever cantilever(Vec3::UnitX(), rod);  // no terminal load: the bend is never used
  int solves = 0;
  const WeightedRod w = carry_weight(cantilever, model, rod, model.root_frame.col(2), solves);
  return HangingRod{w.solution, w.share};
}

RodModel carrying_share(const RodModel& model, double weight_share) {
  RodModel partial = model;
  partial.force_per_length = weight_share * model.force_per_length;
  if (weight_share == 0.0) partial.support.reset();
  return partial;
}

double immersion_share(const std::array<double, 2>& depth_range, double height) {
  return depth_range[1] + (depth_range[0] - depth_range[1]) * std::clamp(height, 0.0, 1.0);
}

PreGuide preguide_start(const RootSet& roots, int i, const Boundary& boundary, const PreguideOptions& o) {
  PreGuide g;
  g.root = roots.positions[i];
  g.normal = roots.normals[i];
  g.direction = roots.directions[i];
  g.length = roots.lengths[i];
  g.height = roots.heights[i];
  g.thickness = std::max(0.0, -boundary.volume->value(g.root));
  g.target_depth = immersion_share(o, g.height) * g.thickness;
  return g;
}

namespace {

// Whether the pre-guides are fitted to the layer (layer_preguide.h) rather than marched.
bool fitted_to_layer(const PreguideOptions& o) {
  return o.immersion == PreguideImmersion::layer && o.material.gravity.isZero(0.0) && !o.material.contact.active();
}

// Whether root i's pre-guide rests along its fall (guides/fall_rest.h): a hanging root of hair
// styled along its path, weightless.
bool rests_along_fall(const RootSet& roots, int i, const PreguideOptions& o) {
  return o.styled && hangs(roots, i) && o.material.gravity.isZero(0.0) && !o.material.contact.active();
}

// The unloaded rod at rest along its fall: its tip rests where the fall ends, on the layer's floor.
PreGuide fall_preguide(const RootSet& roots, int i, const Boundary& boundary, const PreguideOptions& o) {
  PreGuide g = preguide_start(roots, i, boundary, o);
  const Mat3 frame = root_frame(g.direction, bending_direction(g.normal, g.direction, o.down, o.front));
  RodModel model = make_rod_model(hair_rod(g.length, o.material), RodRoot{g.root, frame});
  model.kappa_hat = fall_rest(fall_region(boundary, o.down, o.front), g.root, g.normal, frame, g.length,
                               immersion_share(o, g.height), o.rod.segments);
  g.shape = fibre_shape(model, g.root, g.length, o.rod, Vec3::Zero(), Vec3::Zero());
  g.depth = -boundary.volume->value(g.shape.nodes.back());
  g.reached = boundary.acceptable(g.shape.nodes.back());
  g.solves = 1;
  return g;
}

}  // namespace

PreGuide solve_preguide_alone(const RootSet& roots, int i, const Boundary& boundary, const PreguideOptions& options) {
  if (rests_along_fall(roots, i, options)) return fall_preguide(roots, i, boundary, options);
  return fitted_to_layer(options) && !hangs(roots, i) ? solve_layer_preguide(roots, i, boundary, options)
                                                      : solve_preguide(roots, i, boundary, options, {});
}

PreGuides make_preguides(const RootSet& roots, const Boundary& boundary, const PreguideOptions& options,
                         const Exec& exec) {
  PreGuides result;
  result.items.resize(roots.size());
  if (fitted_to_layer(options)) {
    // A root that hangs (scalp/hanging.h) falls free of the skull: the paper's construction bends
    // its tip into the layer.
    ProgressCounter progress(exec.progress);
    parallel_for(roots.size(), exec.threads, [&](int i) {
      result.items[i] = solve_preguide_alone(roots, i, boundary, options);
      progress.item_done();
    });
    return result;
  }
  // One shared march per distinct compliance among the pre-guides that can replay one.
  std::vector<PreguideMarch> shared;
  for (int i = 0; i < roots.size(); ++i) {
    const RodModel model = make_rod_model(hair_rod(roots.lengths[i], options.material), RodRoot{});
    if (!replays_march(model, options)) continue;
    if (std::none_of(shared.begin(), shared.end(), [&](const PreguideMarch& m) { return m.compliance == model.compliance; }))
      shared.push_back(shared_march(model.compliance, options));
  }
  for (const PreguideMarch& m : shared) result.shared_solves += m.solves;
  ProgressCounter progress(exec.progress);
  parallel_for(roots.size(), exec.threads, [&](int i) {
    result.items[i] = rests_along_fall(roots, i, options) ? fall_preguide(roots, i, boundary, options)
                                                          : solve_preguide(roots, i, boundary, options, shared);
    progress.item_done();
  });
  return result;
}

Digest digest(const PreGuides& preguides) {
  Digest d;
  for (const PreGuide& g : preguides.items) {
    d.add(g.force).add(g.root_moment).add(g.shape.nodes);
    d.add(static_cast<std::int64_t>(g.reached));
  }
  return d;
}

}  // namespace hairfit
