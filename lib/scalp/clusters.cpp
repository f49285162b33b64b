#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>

#include "core/parallel.h"
#include "core/random.h"
#include "scalp/disk_grid.h"
#include "core/point_grid.h"
#include "scalp/roots.h"
#include "scalp/sample_elimination.h"

namespace hairfit {

namespace {

RootSet subset(const RootSet& s, const std::vector<int>& index) {
  RootSet out;
  for (int i : index) {
    out.where.push_back(s.where[i]);
    out.positions.push_back(s.positions[i]);
    out.normals.push_back(s.normals[i]);
    out.directions.push_back(s.directions[i]);
    out.lengths.push_back(s.lengths[i]);
    out.chart.push_back(s.chart[i]);
    out.heights.push_back(s.heights[i]);
    if (!s.hang_weights.empty()) out.hang_weights.push_back(s.hang_weights[i]);
  }
  return out;
}

}  // namespace

Clusters make_clusters(const ScalpChart& ch, const Roots& roots, const RootOptions& o, const Exec& exec) {
  if (o.guides < 1) throw std::invalid_argument("clusters: guides must be ≥ 1");
  if (!(o.cluster_overlap >= 1.0)) throw std::invalid_argument("clusters: cluster_overlap must be ≥ 1");
  Clusters cl;
  const RootSet& pores = roots.pores;
  const int np = pores.size();
  const int ng = std::min(o.guides, np);
  if (ng == 0) return cl;

  // Centres: a blue-noise subset of the pores, uniform over the hair-covered 3D area. Candidates
  // are the oversampling × guides pores with the smallest keys of their own random streams.
  std::vector<int> candidates(np);
  std::iota(candidates.begin(), candidates.end(), 0);
  const int wanted = static_cast<int>(std::min<double>(np, std::ceil(o.oversampling * ng)));
  if (wanted < np) {
    std::vector<std::uint64_t> key(np);
    parallel_for(np, exec.threads, [&](int i) { key[i] = Random(o.seed, RandomStage::clusters, static_cast<std::uint64_t>(i)).next_u64(); });
    std::nth_element(candidates.begin(), candidates.begin() + wanted, candidates.end(),
                     [&](int a, int b) { return key[a] != key[b] ? key[a] < key[b] : a < b; });
    candidates.resize(wanted);
    std::sort(candidates.begin(), candidates.end());
  }
  std::vector<Vec3> candidate_positions;
  for (int i : candidates) candidate_positions.push_back(pores.positions[i]);
  const double area = roots.hair_area > 0 ? roots.hair_area : ch.area;
  const std::vector<double> radius(candidates.size(), 1.0 / std::sqrt(2.0 * std::sqrt(3.0) * ng / area));
  for (int k : eliminate_samples(candidate_positions, radius, ng, exec.threads)) cl.centre_pore.push_back(candidates[k]);
  const int nc = cl.size();
  cl.bases = subset(pores, cl.centre_pore);

  // Nearest centre in the chart for every pore; each circle's covering radius is the farthest of
  // its nearest pores, so the circles (× overlap ≥ 1) cover all pores.
  const double cell = std::sqrt(M_PI / nc);  // about one centre per cell
  const DiskGrid centre_grid(cl.bases.chart, cell);
  std::vector<int> nearest(np);
  parallel_for(np, exec.threads, [&](int i) { nearest[i] = centre_grid.nearest(pores.chart[i]); });
  std::vector<double> cover(nc, 0.0);
  for (int i = 0; i < np; ++i)
    cover[nearest[i]] = std::max(cover[nearest[i]], (pores.chart[i] - cl.bases.chart[nearest[i]]).norm());
  cl.radius.resize(nc);
  for (int c = 0; c < nc; ++c) cl.radius[c] = o.cluster_overlap * cover[c];

  // Pores inside each circle, gathered per circle in parallel, then per pore in circle order.
  const DiskGrid pore_grid(pores.chart, cell);
  std::vector<std::vector<int>> inside(nc);
  parallel_for(nc, exec.threads, [&](int c) {
    pore_grid.for_each_within(cl.bases.chart[c], cl.radius[c], [&](int i) { inside[c].push_back(i); });
    std::sort(inside[c].begin(), inside[c].end());
  });
  std::vector<int> count(np + 1, 0);
  for (int c = 0; c < nc; ++c)
    for (int i : inside[c]) ++count[i + 1];
  for (int i = 0; i < np; ++i) count[i + 1] += count[i];
  std::vector<int> containing(count[np]), fill(count.begin(), count.end() - 1);
  for (int c = 0; c < nc; ++c)
    for (int i : inside[c]) containing[fill[i]++] = c;

  cl.pore_cluster.resize(np);
  cl.candidate_clusters.resize(np);
  parallel_for(np, exec.threads, [&](int i) {
    const int k = count[i + 1] - count[i];
    cl.candidate_clusters[i] = std::max(k, 1);
    if (k == 0) {  // only by round-off at a circle's rim: the nearest centre covers it
      cl.pore_cluster[i] = nearest[i];
      return;
    }
    Random rng(o.seed, RandomStage::clusters, static_cast<std::uint64_t>(i));
    rng.next_u64();  // the first value chose the centre candidates
    cl.pore_cluster[i] = containing[count[i] + static_cast<int>(rng.below(static_cast<std::uint64_t>(k)))];
  });
  cl.members.resize(nc);
  for (int i = 0; i < np; ++i) cl.members[cl.pore_cluster[i]].push_back(i);
  return cl;
}

std::vector<double> nearest_neighbour_distances(const std::vector<Vec3>& points, int threads) {
  const int n = static_cast<int>(points.size());
  std::vector<double> d(n, 0.0);
  if (n < 2) return d;
  Vec3 lo = points.front(), hi = points.front();
  for (const Vec3& p : points) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  const Vec3 extent = hi - lo;
  // About four points per cell for points spread over a surface within the box: the first search
  // (radius one cell, the 27 cells around) then almost always finds the nearest, where cells of
  // one point each often needed a second, 125-cell search. The distances do not depend on it.
  const double spread = std::max({extent.x() * extent.y(), extent.y() * extent.z(), extent.z() * extent.x(), 1e-300});
  const double cell = std::max(2.0 * std::sqrt(spread / n), 1e-12 * (1.0 + extent.norm()));
  const PointGrid grid(points, cell);
  // Cell by cell, so the neighbouring cells are looked up once for the few points of a cell: the
  // search of PointGrid::nearest's first round (within one cell size, the 27 cells around), which
  // almost always finds the nearest; it answers the rest. The distance of a nearest point does
  // not depend on which of equally near points it is.
  const HugeVector<Vec3>& sorted = grid.sorted();
  const HugeVector<int>& order = grid.order();
  const double r2 = cell * cell;
  constexpr int kCellsPerBlock = 64;
  const int cells = grid.cell_count();
  parallel_for((cells + kCellsPerBlock - 1) / kCellsPerBlock, threads, [&](int b) {
    std::vector<PointGrid::CellRange> ranges;
    for (int c = b * kCellsPerBlock; c < std::min(cells, (b + 1) * kCellsPerBlock); ++c) {
      grid.neighbourhood(c, 1, ranges);
      for (int k = grid.cell_begin(c); k < grid.cell_begin(c + 1); ++k) {
        const Vec3 p = sorted[k];
        double best = INFINITY;
        for (const PointGrid::CellRange& range : ranges) {
          for (int q = range.begin; q < range.end; ++q) {
            const double dx = sorted[q].x() - p.x(), dy = sorted[q].y() - p.y(), dz = sorted[q].z() - p.z();
            const double d2 = (dx * dx + dy * dy) + dz * dz;  // as Vec3::squaredNorm sums it
            if (q != k && d2 <= r2 && d2 < best) best = d2;
          }
        }
        const int i = order[k];
        if (best < INFINITY) {
          d[i] = std::sqrt(best);
        } else {
          const int j = grid.nearest(points[i], i, 2.0 * extent.norm() + cell);
          d[i] = j >= 0 ? (points[j] - points[i]).norm() : 0.0;
        }
      }
    }
  });
  return d;
}

ScalpFigures scalp_figures(const ScalpChart& ch, const Roots& roots, const Clusters& clusters,
                           const PreguideRoots& preguides, int threads) {
  ScalpFigures f;
  f.scalp_area = ch.area;
  f.expected_roots = roots.expected_count;
  f.roots = roots.pores.size();
  f.guides = clusters.size();
  f.preguide_roots = preguides.roots.size();
  const std::vector<double> d = nearest_neighbour_distances(roots.pores.positions, threads);
  if (d.size() >= 2) {
    f.min_spacing = *std::min_element(d.begin(), d.end());
    f.mean_spacing = std::accumulate(d.begin(), d.end(), 0.0) / d.size();
  }
  return f;
}

Digest digest(const Clusters& cl) {
  Digest d = digest(cl.bases);
  d.add(std::string_view("Clusters/1")).add(static_cast<std::int64_t>(cl.size()));
  d.add_bytes(cl.centre_pore.data(), cl.centre_pore.size() * sizeof(int));
  d.add(cl.radius);
  d.add(static_cast<std::int64_t>(cl.pore_cluster.size()));
  d.add_bytes(cl.pore_cluster.data(), cl.pore_cluster.size() * sizeof(int));
  return d;
}

}  // namespace hairfit
