// The fibres' share of the density models (effects.density = "binary" | "continuous", scene key
// density.spread): the guides' density term (paper §3.5) steers where the wisps run, but the
// crowding the fibres show lies where neighbouring wisps overlap half-way down their length
// (docs/results/density.md). So the grown fibres are spread down their own density gradient
// before the strand stage keeps them out of the head and cuts them: in each pass every point but
// the root moves by −step·h²·∇ρ/ρ̄ (at most h/2), weighted by its wisp's settle ramp, and each
// fibre then takes back its segment lengths from the root on.
#pragma once
#include <cstddef>
#include <functional>
#include <vector>

#include "core/types.h"

namespace hairfit {

struct DensitySpread {
  int passes = 0;       // 0: the fibres stay as grown
  double voxel = 0.25;  // cm: node spacing h of the fibres' density
  double step = 2.0;    // the move's size in units of h²·∇ρ/ρ̄
  double settle = 0.2;  // share of a fibre's length over which its move weight rises from 0 to 1
};

// The fibres' point density on a lattice of nodes lower + h·(i, j, k), i < dims.x() …: each point
// adds its trilinear weights to the 8 nodes around it (so every point adds exactly 1 in all),
// then the lattice is smoothed by `smoothing` passes of the [1 2 1]/4 filter along each axis
// (values beyond the lattice count as 0). Points outside [lower, lower + h·(dims − 1)] are
// rejected with std::invalid_argument.
struct PointDensity {
  Vec3 lower = Vec3::Zero();
  double h = 1.0;
  Vec3i dims = Vec3i::Zero();
  std::vector<double> values;  // x fastest
  double at(int i, int j, int k) const { return values[(static_cast<std::size_t>(k) * dims.y() + j) * dims.x() + i]; }
  // ∇ρ at p: central differences at the 8 nodes around p (one-sided at the lattice's faces),
  // blended trilinearly.
  Vec3 gradient(const Vec3& p) const;
};

PointDensity point_density(const std::vector<Vec3>& points, const Vec3& lower, double h, const Vec3i& dims,
                           int smoothing, int threads = 1);

// The density a point sees on average: Σρ² / Σρ over the nodes (0 on an empty lattice).
double seen_density(const PointDensity& density);

// Whether a point lies in the hair's region (inside the volume, in front of the scalp).
using RegionTest = std::function<bool(const Vec3&)>;

// The density per unit of the region's own volume, a normalised convolution (Knutsson and Westin
// 1993): each node's smoothed point density divided by the region's share of that node's
// smoothing stencil, the indicator of the region at the nodes smoothed alike. Without it a thin
// layer's two faces read as a fall in density, and the spread pushes fibres out through them
// rather than along the layer. Nodes whose share is below kRegionShareFloor keep their density
// divided by that floor: a node so far outside holds almost no points, and a point there is not
// pushed by round-off in the share. The stencil equals point_density's smoothing.
constexpr double kRegionShareFloor = 1.0 / 16.0;
void normalise_by_region(PointDensity& density, const RegionTest& region, int smoothing, int threads = 1);

// Spreads `points` (fibres of `n` points each, root first, one after another) in place as
// DensitySpread says. Roots never move and every segment keeps its length (to round-off). With
// `region`, the density is normalise_by_region's. Deterministic for any thread count.
void spread_fibres(std::vector<Vec3>& points, std::size_t n, const DensitySpread& spread, int threads = 1,
                   const RegionTest& region = nullptr);

}  // namespace hairfit
