// The density term F4 of the principal-guide objective (paper §3.5, docs/design.md §5–6) and what a final
// guide deposits into the density grid. Guides then depend on each other: they are optimised in
// fixed-size batches (make_guides_with_density, guides.h), each batch against the frozen density
// of all earlier batches, and deposited in guide order, so results do not depend on threads.
#pragma once
#include <vector>

#include "density/grid.h"
#include "density/voxelise.h"
#include "hair/wisp.h"

namespace hairfit {

enum class GuideDensityModel {
  binary,      // BOM: occupancy grid, 1 where an earlier wisp's tube lies
  continuous,  // CDM: Σ fibre length in the cell / cell diagonal
};

// Everything the F4 residuals read besides the grid (weights.density = w4 multiplies them all).
struct DensityTermOptions {
  GuideDensityModel model = GuideDensityModel::continuous;
  double strength = 1.0;         // c_ρ (CDM): F4 = c_ρ ∫⟨∇Φρ, t⟩² ds
  double threshold = 0.5;        // BOM: occupancy above which the surcharge applies
  double surcharge = 10.0;       // c_BOM
  double surcharge_width = 0.2;  // BOM: occupancy over which the surcharge rises (smoothstep)
};

// When a guide's trust-region solve has stopped paying: `iterations` iterations in a row, accepted
// or rejected, that together lowered the cost by less than `tolerance` of it. 0 iterations: never
// (then only the relative tolerance and the iteration cap stop the solve).
struct StallTest {
  int iterations = 0;
  double tolerance = 0.0;
};

// What a final guide's wisp deposits for the continuous model (CDM).
enum class WispDeposit {
  // The wisp's expected density: kWispTubeLines lines spread evenly over its cross-section (the
  // paper's cylindrical region around the guide, radius wisp.root_radius → wisp.tip_radius), each
  // carrying an equal share of its pores' fibres (wisp_tube_lines).
  tubes,
  // The fibres the strand stage grows from its cluster's pores (grow_guide_fibres).
  fibres,
};

struct GuideDensityOptions {
  DensityTermOptions term;
  GridGeometry grid;  // make_density_geometry
  int batch = 64;     // guides per batch
  // Stops each guide's second solve, the one with F4 (make_guides_with_density). It starts at the
  // optimum without F4 and F4 rests on a grid of fibre lengths per voxel, rough at the voxel
  // scale: past its first steps the solve crept by steps the trust region kept rejecting (on the
  // paper-scale scene 51 evaluations per guide for a cost 2.5 % lower). Stopped at the stall, the
  // evaluations halve and the density comes out no less even (bench/results/density_stall.md).
  StallTest stall{3, 1e-4};
  // What a final guide deposits. CDM: as `deposit` says (a guide with no pores deposits the guide
  // polyline once instead). BOM: a tube along the guide, radius wisp.root_radius →
  // wisp.tip_radius (cm).
  Pores pores;
  WispShape wisp;
  WispDeposit deposit = WispDeposit::tubes;
};

// The density grid's cells: the box [lower, upper] (cm, e.g. the hair-volume mesh's bounding
// box) grown by `margin` cm on every side, at cells of edge `voxel` cm (make_grid_geometry; throws
// InputError beyond max_memory_gib).
GridGeometry make_density_geometry(const Vec3& lower, const Vec3& upper, double voxel, double margin,
                                   double max_memory_gib);

// The paper's surcharge indicator on occupancy o ∈ [0, 1], smoothed: 0 below threshold − width/2,
// 1 above threshold + width/2, the C¹ smoothstep 3x² − 2x³ between (x the position in the ramp).
double surcharge_step(double occupancy, double threshold, double width);

// The largest F4 integrand (per unit normalised arc length, before w4) any sample can pay on
// `grid`: BOM o² + c_BOM·S(o)² at the largest occupancy o (both grow with o); CDM c_ρ·|∇Φρ|² at
// its largest over the cell centres, which bounds c_ρ⟨∇Φρ, t⟩² everywhere since the central
// gradient is a trilinear blend of its cell-centre values and |·|² is convex. 0 on an empty grid.
double density_ceiling(const DensityGrid& grid, const DensityTermOptions& term, int threads = 1);

// density_ceiling over a sequence of grids of one geometry that change in places, as the batches'
// deposits change it: each call equals density_ceiling of its grid exactly, but (CDM) recomputes
// only the rows of cell centres whose central differences read a changed cell. On the paper-scale
// scene a batch's fibres change a fraction of the rows, and a full scan per batch would take 5 % of
// the guide stage's instructions.
class DensityCeiling {
 public:
  explicit DensityCeiling(const DensityTermOptions& term) : term_(term) {}
  double operator()(const DensityGrid& grid, int threads = 1);

 private:
  DensityTermOptions term_;
  int nx_ = 0, ny_ = 0, nz_ = 0;  // the padded grid's dimensions (two rings of zero cells)
  double voxel_ = 0.0;
  std::vector<double> padded_;    // the last grid's values, padded
  std::vector<double> row_top_;   // per padded row (j, k): the largest |∇Φρ|² along it
};

// The fibres a guide deposits (CDM): one per pore of its cluster, grown as make_strands grows them
// before the head exit and the cut (grow_fibre, with the wisp extent make_strands measures); pore
// i's (an index into options.pores, one of `pores_of_guide`) goes to
// fibres[i·n, (i+1)·n), n = fibre_point_count(options.wisp). A guide with no pores deposits its
// own polyline instead (make_guides_with_density).
void grow_guide_fibres(const std::vector<Vec3>& guide, const std::vector<int>& pores_of_guide,
                       const GuideDensityOptions& options, Vec3* fibres);

// WispDeposit::tubes: the lines, kWispTubeLines of fibre_point_count(wisp) points each, line j at
// the points of a sunflower on the unit disk, ρ_j = √((j + ½)/K) at the golden angle j·137.5°, in
// the guide's rotation-minimising frame, scaled by the wisp's radius at each station (stations
// evenly spaced in arc length, root to tip). Line j goes to lines[j·n, (j+1)·n). Each carries 1/K
// of the wisp's fibres. Measured at paper scale (bench/results/density_guide_cost_2026-12-07.md):
// 16 lines give F4 8.1 against the grown fibres' 10.4, and 17.4 evaluations a guide against 17.7;
// 7 lines 12.3 and 19.1; a sample of every 5th grown fibre 16.4 and 20.0.
constexpr int kWispTubeLines = 16;
void wisp_tube_lines(const std::vector<Vec3>& guide, const WispShape& wisp, Vec3* lines);

// The generalised cylinder a guide occupies (BOM): radius root_radius at the root to tip_radius at
// the tip, linear in arc length.
Tube guide_tube(const std::vector<Vec3>& guide, double root_radius, double tip_radius);

}  // namespace hairfit
