// One principal guide's solve: its targets from the pre-guides it follows, its start, the
// solve, and the retry from the other start where the first stays outside. Internal to
// lib/guides: guides.cpp schedules the solves (the warm-start rounds and the density batches).
#pragma once
#include <algorithm>
#include <optional>
#include <vector>

#include "guides/guides.h"
#include "guides/objective.h"

namespace hairfit {

// The `count` candidates nearest to p (ties: lower index first), nearest first.
template <typename PositionOf>
std::vector<int> nearest(std::vector<int> candidates, const PositionOf& position_of, const Vec3& p, int count) {
  count = std::min<int>(count, candidates.size());
  std::partial_sort(candidates.begin(), candidates.begin() + count, candidates.end(), [&](int a, int c) {
    const double da = (position_of(a) - p).squaredNorm(), dc = (position_of(c) - p).squaredNorm();
    return da < dc || (da == dc && a < c);
  });
  candidates.resize(count);
  return candidates;
}

// Weights of followed neighbours at these distances, nearest first: inverse distance, softened
// so that a neighbour at the very root does not take all the weight; they sum to 1.
std::vector<double> follow_weights(std::vector<double> distances);

// Σ wᵢ·(f_L, m(0)) over the given guides or pre-guides: a warm start for a neighbouring guide.
template <typename Item>
void add_weighted_loads(const std::vector<Item>& items, const std::vector<int>& which, const std::vector<double>& weights,
                        double loads[6]) {
  for (std::size_t i = 0; i < which.size(); ++i)
    for (int a = 0; a < 3; ++a) {
      loads[a] += weights[i] * items[which[i]].force[a];
      loads[3 + a] += weights[i] * items[which[i]].root_moment[a];
    }
}

// How far to follow a pre-guide at a point: fully inside the acceptable region, not at all once
// it is a boundary width beyond the scalp or the volume (smoothstep in between). A pre-guide that
// could not reach its depth pokes out of the volume; there its direction and curvature would pull
// the guide out after it, so there the boundary term and the rod alone decide.
double follow_trust(const Boundary& boundary, const Vec3& p, double width);

// 0, 1, …, count − 1.
std::vector<int> all_indices(int count);

// The relative cost decrease at which a guide's first, density-free solve stops when a density
// solve follows (make_guides_with_density).
constexpr double kFirstSolveTolerance = 1e-2;

// What a solve is for: a guide of the result (every figure of Guide), or only the start of a
// density solve (the loads, the shape, the counts; the cost and its terms stay 0).
enum class GuideUse { result, start };

// What every guide of a stage is solved against.
struct GuideProblem {
  const RootSet& bases;
  const PreGuides& preguides;
  const Boundary& boundary;
  const GuideOptions& options;
};

// How one guide's solve starts and what it adds to the problem.
struct GuideSolveSetup {
  std::optional<DensityGrid> density;  // the F4 term's grid (sharing its cells), or none
  DensityTermOptions term;               // read with a density grid
  double density_ceiling = 0.0;          // GuideTargets::density_ceiling
  // The loads to start from (world axes, dimensionless); null = as options.warm_start says (the
  // followed pre-guides' loads, weighted, or straight).
  const double* start = nullptr;
  StallTest stall;
  GuideUse use = GuideUse::result;
  // For a heavy rod: a solved neighbour's shooting pieces to start its first solve from, and where
  // its own go.
  const ShootingResult* near = nullptr;
  ShootingResult* pieces = nullptr;
};

// Hair shorter than this many voxels of the volume's field is stubble: a weightless guide that
// short keeps its straight rest shape, unloaded (guide_solve.cpp, rests_unloaded), and hair from
// the hull that short is as long as its layer holds it straight (scalp/roots.h, fitted_stubble).
// Such a guide spans at most two cells of the fields, which cannot tell a layer thinner than a
// cell from outside it. Measured on the seven carved hulls (bench_carved_hulls, docs/results/
// carved-flow.md): guides inside by exact winding 0.9965–1.0000 at 1 voxel, 0.9993–1.0000 at 2,
// 0.9996–1.0000 at 4; flow crossing 0.015–0.040, 0.005–0.030, 0.003–0.018. At 4 voxels, 1 cm hair
// at 0.25 cm voxels and 2 cm at 0.5 cm, the method would leave much of the hair unsolved.
constexpr double kStubbleVoxels = 2.0;
// cm: hair shorter than this is stubble, for a volume field of this voxel.
inline double stubble_length(const DistanceField& volume) { return kStubbleVoxels * volume.voxel(); }

// Guide b of the problem.
Guide solve_guide(const GuideProblem& problem, int b, const GuideSolveSetup& setup = {});

// A guide with the density term, by continuation from `plain`, its solve without F4
// (guide_solve.cpp says why); iterations and evaluations count both solves.
Guide solve_guide_with_density(const GuideProblem& problem, int b, const Guide& plain, const DensityGrid& density,
                               const DensityTermOptions& term, double ceiling, const StallTest& stall);

}  // namespace hairfit
