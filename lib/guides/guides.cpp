#include "guides/guides.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>

#include "core/parallel.h"
#include "core/progress.h"
#include "density/accumulator.h"
#include "guides/guide_solve.h"

namespace hairfit {

namespace {
// The density-free solves as make_guides defines them. With a warm start, in rounds: first the
// seeds, the guide nearest each pre-guide, from the pre-guides' loads; then a quarter of the
// others, then another quarter, each guide from the optimised loads of its nearest guides solved
// in earlier rounds, which lie closer to its own optimum than the pre-guides' loads; the rest
// likewise from all of them. Starting from nearer solved guides took 9 % fewer evaluations on the
// spheroid fixture and 8 % on the paper scale than starting every guide from the seeds, with
// shares inside and mismatches within scatter. Without a warm start, every guide on its own.
// Once the rounds are solved, any other guide can be solved at any time on any thread with the
// same result: the results do not depend on the thread count or on when each guide is taken.
class FirstSolves {
 public:
  // `use`: the guides are the result (make_guides) or the density solves' starts.
  FirstSolves(const GuideProblem& problem, GuideUse use, int threads, std::vector<Guide>& out)
      : problem_(problem), bases_(problem.bases), preguides_(problem.preguides), options_(problem.options), use_(use),
        threads_(threads), out_(out), in_round_(bases_.size(), 0), pieces_(bases_.size()) {
    const RootSet& bases = bases_;
    const PreGuides& preguides = preguides_;
    out_.resize(bases.size());
    if (!warm()) return;
    auto base_at = [&](int b) { return bases.positions[b]; };
    const std::vector<int> everyone = all_indices(bases.size());
    for (const PreGuide& p : preguides.items) in_round_[nearest(everyone, base_at, p.root, 1)[0]] = 1;
    rounds_.resize(3);
    int k = 0;  // counts the others in index order: k % 4 == 0 joins round 1, k % 4 == 2 round 2
    for (int b = 0; b < bases.size(); ++b) {
      if (in_round_[b]) {
        rounds_[0].push_back(b);
        continue;
      }
      const int r = k++ % 4;
      if (r == 0 || r == 2) {
        rounds_[r == 0 ? 1 : 2].push_back(b);
        in_round_[b] = 1;
      }
    }
  }

  // Solves the rounds, each on all threads.
  void solve_rounds(ProgressCounter& progress) {
    for (std::size_t r = 0; r < rounds_.size(); ++r) {
      const std::vector<int>& round = rounds_[r];
      parallel_for(round.size(), threads_, [&](int i) {
        if (r == 0)
          out_[round[i]] = solve_guide(problem_, round[i], setup(nullptr, nullptr, &pieces_[round[i]]));
        else
          solve(round[i]);
        progress.item_done();
      });
      solved_.insert(solved_.end(), round.begin(), round.end());
      std::sort(solved_.begin(), solved_.end());
    }
  }
  // The guides in [begin, end) in no round, in index order.
  std::vector<int> others(int begin, int end) const {
    std::vector<int> list;
    for (int b = begin; b < end; ++b)
      if (!in_round_[b]) list.push_back(b);
    return list;
  }
  // Solves guide b (not a seed) from the guides of the rounds solved so far.
  void solve(int b) {
    if (!warm()) {
      out_[b] = solve_guide(problem_, b, setup(nullptr, nullptr, nullptr));
      return;
    }
    auto base_at = [&](int j) { return bases_.positions[j]; };
    const std::vector<int> from = nearest(solved_, base_at, bases_.positions[b], options_.neighbours);
    std::vector<double> weights;
    for (int j : from) weights.push_back((bases_.positions[j] - bases_.positions[b]).norm());
    weights = follow_weights(weights);
    double start[kMaxGuideLoads] = {};
    add_weighted_loads(out_, from, weights, start);
    const ShootingResult* near = from.empty() ? nullptr : &pieces_[from[0]];
    out_[b] = solve_guide(problem_, b, setup(start, near, in_round_[b] ? &pieces_[b] : nullptr));
  }

 private:
  bool warm() const { return options_.warm_start && preguides_.size() > 0; }
  GuideSolveSetup setup(const double* start, const ShootingResult* near, ShootingResult* pieces) const {
    GuideSolveSetup s;
    s.start = start;
    s.use = use_;
    s.near = near;
    s.pieces = pieces;
    return s;
  }

  const GuideProblem problem_;
  const RootSet& bases_;
  const PreGuides& preguides_;
  const GuideOptions& options_;
  GuideUse use_;
  int threads_;
  std::vector<Guide>& out_;
  std::vector<char> in_round_;
  std::vector<std::vector<int>> rounds_;  // seeds, then two quarters of the others
  std::vector<int> solved_;               // the guides of the rounds solved so far, in index order
  // A heavy rod's shooting pieces, kept for the guides of the rounds: the later guides' first
  // solves start from their nearest solved neighbour's (empty for light rods).
  std::vector<ShootingResult> pieces_;
};

}  // namespace

Curves Guides::curves() const {
  Curves c;
  for (std::size_t i = 0; i < items.size(); ++i) c.add(items[i].shape.nodes, static_cast<std::int32_t>(i));
  return c;
}

Guides make_guides(const RootSet& bases, const PreGuides& preguides, const Boundary& boundary, const GuideOptions& options,
                   const Exec& exec) {
  Guides guides;
  ProgressCounter progress(exec.progress);
  FirstSolves first(GuideProblem{bases, preguides, boundary, options}, GuideUse::result, exec.threads, guides.items);
  first.solve_rounds(progress);
  const std::vector<int> others = first.others(0, bases.size());
  parallel_for(others.size(), exec.threads, [&](int i) {
    first.solve(others[i]);
    progress.item_done();
  });
  return guides;
}

DensityGuides make_guides_with_density(const RootSet& bases, const PreGuides& preguides, const Boundary& boundary,
                                       const GuideOptions& options, const GuideDensityOptions& density,
                                       const Exec& exec) {
  if (density.batch < 1) throw std::invalid_argument("make_guides_with_density: batch must be >= 1");
  const int count = bases.size();
  DensityGuides out;
  out.guides.items.resize(count);
  // The pores of each cluster, in pore order (CDM deposits their wisp).
  std::vector<std::vector<int>> pores_of(count);
  const std::size_t fibre_points = fibre_point_count(density.wisp);
  // CDM deposits each guide's wisp, as lines over its cross-section or as the fibres its guide
  // will grow; BOM tubes along the guides.
  const bool cdm = density.term.model == GuideDensityModel::continuous;
  const bool grow = cdm && density.deposit == WispDeposit::fibres;
  std::vector<Vec3> grown;  // grown fibres: every pore's fibre, in its place
  std::vector<Vec3> lines;  // wisp tubes: the batch's guides' lines, guide by guide
  const std::size_t lines_per_guide = kWispTubeLines * fibre_points;
  if (cdm) {
    for (std::size_t i = 0; i < density.pores.guide.size(); ++i) {
      const int g = density.pores.guide[i];
      if (g >= 0 && g < count) pores_of[g].push_back(static_cast<int>(i));
    }
    if (grow) grown.resize(fibre_points * density.pores.positions.size());  // each written before it is read
    else lines.resize(lines_per_guide * static_cast<std::size_t>(density.batch));
  }
  // The first solves do not see the density: the guides the scene would have without a density
  // model (FirstSolves, as make_guides). They are only the second solves' start, and those
  // minimise the whole objective to options.tolerance, so they stop at a relative decrease of
  // kFirstSolveTolerance. On the paper-scale scene 1e-2 takes 17.7 evaluations a guide where 1e-3
  // took 20.1, with F4 10.43 against 10.71, every node inside and the followed mismatch 0.0208
  // against 0.0205; 1e-1 leaves nodes outside (0.99955) and 1 leaves the guides unfinished
  // (bench/results/density_stall.md).
  GuideOptions first_options = options;
  first_options.tolerance = std::max(options.tolerance, kFirstSolveTolerance);
  std::vector<Guide> plain;
  FirstSolves first(GuideProblem{bases, preguides, boundary, first_options}, GuideUse::start, exec.threads, plain);
  const GuideProblem problem{bases, preguides, boundary, options};
  const ProgressCallback nobody;
  ProgressCounter no_progress(nobody);  // the first solves report nothing
  first.solve_rounds(no_progress);
  auto batch_end = [&](int begin) { return std::min(count, begin + density.batch); };
  {
    const std::vector<int> todo = first.others(0, batch_end(0));
    parallel_for(todo.size(), exec.threads, [&](int i) { first.solve(todo[i]); });
  }
  ProgressCounter progress(exec.progress);  // guides finished, after their second solve
  DensityAccumulator accumulator(density.grid);
  DensityCeiling ceiling(density.term);
  DensityGrid frozen = accumulator.freeze();  // the earlier batches only
  double outside_f4 = ceiling(frozen, exec.threads);
  for (int begin = 0; begin < count; begin += density.batch) {
    const int end = batch_end(begin);
    // The guides of a batch are independent of each other, so the order they are taken in changes
    // nothing but the balance: the costliest first (by their first solve's evaluations), so that
    // the batch does not end with one thread on a slow guide while the others wait.
    std::vector<int> order(end - begin);
    std::iota(order.begin(), order.end(), begin);
    std::stable_sort(order.begin(), order.end(),
                     [&](int x, int y) { return plain[x].evaluations > plain[y].evaluations; });
    // CDM: each guide lays out its wisp's lines or grows its fibres as soon as it is solved (they
    // are deposited below, in guide order).
    parallel_for(end - begin, exec.threads, [&](int i) {
      const int g = order[i];
      out.guides.items[g] =
          solve_guide_with_density(problem, g, plain[g], frozen, density.term, outside_f4, density.stall);
      if (grow) grow_guide_fibres(out.guides.items[g].shape.nodes, pores_of[g], density, grown.data());
      else if (cdm && !pores_of[g].empty())
        wisp_tube_lines(out.guides.items[g].shape.nodes, density.wisp, lines.data() + lines_per_guide * (g - begin));
      progress.item_done();
    });
    // Released before the deposit, which then writes the grid in place (a frozen grid shares the
    // accumulator's buffer until then: DensityAccumulator::freeze).
    frozen = DensityGrid();
    std::vector<FibreSpan> fibres;
    if (cdm) {
      for (int g = begin; g < end; ++g) {
        if (pores_of[g].empty()) {
          fibres.push_back({out.guides.items[g].shape.nodes.data(), out.guides.items[g].shape.nodes.size()});
        } else if (grow) {
          for (int i : pores_of[g]) fibres.push_back({grown.data() + fibre_points * i, fibre_points});
        } else {  // each line an equal share of the wisp's fibres
          const double share = static_cast<double>(pores_of[g].size()) / kWispTubeLines;
          for (int j = 0; j < kWispTubeLines; ++j)
            fibres.push_back({lines.data() + lines_per_guide * (g - begin) + fibre_points * j, fibre_points, share});
        }
      }
    } else {  // BOM: the tubes' voxelisation scales over threads
      std::vector<Tube> tubes;
      for (int g = begin; g < end; ++g)
        tubes.push_back(guide_tube(out.guides.items[g].shape.nodes, density.wisp.root_radius, density.wisp.tip_radius));
      accumulator.occupy_all(tubes, exec.threads);
    }
    // The fibres' deposit (CDM), the next grid and its ceiling are one thread's task, so that the
    // other threads meanwhile solve the next batch's first solves (they need neither): the fibre
    // deposit's memory traffic scaled poorly over threads, and the other cores idled through it.
    const bool last = end == count;
    const std::vector<int> next = last ? std::vector<int>() : first.others(end, batch_end(end));
    parallel_for(1 + static_cast<int>(next.size()), exec.threads, [&](int i) {
      if (i > 0) return first.solve(next[i - 1]);
      if (cdm) accumulator.add_fibres(fibres, 1);
      if (last) return;
      frozen = accumulator.freeze();
      outside_f4 = ceiling(frozen, 1);
    });
    ++out.batches;
  }
  out.density = std::move(accumulator).freeze();
  // Handed on only when every pore's fibre was grown (each pore belongs to a guide in range).
  if (grow && std::all_of(density.pores.guide.begin(), density.pores.guide.end(), [&](int g) { return g >= 0 && g < count; }))
    out.fibres = std::move(grown);
  return out;
}

GuideFigures guide_figures(const Guides& guides, const PreGuides& preguides, const Boundary& boundary,
                           const GuideOptions& options, double voxel) {
  GuideFigures f;
  f.guides = guides.size();
  long long nodes = 0, inside = 0, in_head = 0, out_volume = 0, out_tip = 0;
  double mismatch = 0.0, mismatch_weight = 0.0;
  const double segments = options.rod.segments;
  // How far each pre-guide node is followed (follow_trust), for the mismatch where guides follow.
  std::vector<std::vector<double>> trust(preguides.items.size());
  for (std::size_t j = 0; j < preguides.items.size(); ++j)
    for (const Vec3& p : preguides.items[j].shape.nodes) trust[j].push_back(follow_trust(boundary, p, options.boundary_width));
  double followed = 0.0, followed_weight = 0.0;
  for (const Guide& g : guides.items) {
    const Rod rod = hair_rod(g.length, options.material);
    const double weight = rod.force_per_length.norm() * std::pow(rod.length, 3) / rod.stiffness[0];
    f.max_weight = std::max(f.max_weight, weight);
    f.unresolved_weight += weight > segments * segments;
    f.shorter_than_voxel += g.length < voxel;
    f.max_contact_force = std::max(f.max_contact_force, g.contact_force);
    f.contact_share += g.contact_share;
    f.guides_in_contact += g.contact_share > 0.0;
    f.guides_held += held_by_layer(g);
    for (const Vec3& F : g.point_forces) f.max_point_force = std::max(f.max_point_force, F.norm() * g.force_scale);
    f.failures += !g.converged;
    f.mean_iterations += g.iterations;
    f.max_iterations = std::max(f.max_iterations, g.iterations);
    f.mean_evaluations += g.evaluations;
    bool tail = true;  // on the stretch outside the volume that ends at the tip, walking back
    int tail_nodes = 0;
    // The root (node 0) lies on the scalp by construction, where the inside is undecided (the
    // region's winding number is ½ there): the shares count the nodes after it.
    for (std::size_t i = g.shape.nodes.size(); i-- > 1;) {
      const Vec3& p = g.shape.nodes[i];
      const bool head = boundary.beyond_scalp(p) > 0.0, out = boundary.beyond_volume(p) > 0.0;
      ++nodes;
      in_head += head;
      out_volume += out;
      inside += !head && !out;
      tail = tail && out;
      tail_nodes += tail;
    }
    out_tip += tail_nodes;
    f.guides_ending_outside += tail_nodes > 0;
    for (std::size_t j = 0; j < g.neighbours.size(); ++j) {
      const FibreShape& p = preguides.items[g.neighbours[j]].shape;
      for (std::size_t i = 0; i < g.shape.tangents.size(); ++i) {
        const double miss = 1.0 - g.shape.tangents[i].dot(p.tangents[i]);
        mismatch += g.neighbour_weights[j] * miss;
        mismatch_weight += g.neighbour_weights[j];
        const double w = g.neighbour_weights[j] * trust[g.neighbours[j]][i];
        followed += w * miss;
        followed_weight += w;
      }
    }
  }
  if (f.guides > 0) {
    f.mean_iterations /= f.guides;
    f.mean_evaluations /= f.guides;
    f.contact_share /= f.guides;
  }
  if (nodes > 0) {
    f.inside_fraction = static_cast<double>(inside) / nodes;
    f.inside_head_fraction = static_cast<double>(in_head) / nodes;
    f.outside_volume_fraction = static_cast<double>(out_volume) / nodes;
    f.outside_tip_fraction = static_cast<double>(out_tip) / nodes;
  }
  if (mismatch_weight > 0) f.mean_direction_mismatch = mismatch / mismatch_weight;
  if (followed_weight > 0) f.followed_direction_mismatch = followed / followed_weight;
  return f;
}

Digest digest(const Guides& guides) {
  Digest d;
  for (const Guide& g : guides.items) {
    d.add(g.force).add(g.root_moment).add(g.shape.nodes);
    for (const Vec3& f : g.point_forces) d.add(f);
    d.add(static_cast<std::int64_t>(g.converged)).add(static_cast<std::int64_t>(g.iterations));
  }
  return d;
}

}  // namespace hairfit
