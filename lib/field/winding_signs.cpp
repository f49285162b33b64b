#include "field/winding_signs.h"

#include <algorithm>
#include <cmath>

#include "core/parallel.h"
#include "field/distance_field.h"

namespace hairfit::field {

namespace {

constexpr double kRoundoff = 1e-9;  // adding an integer to the estimate, and the slack's own sum
// A box whose longest path could change w by this much or more gets no reference of its own.
constexpr double kReach = 1.0;

}  // namespace

GridWindingSigns::GridWindingSigns(const WindingSoup& soup, const GridGeometry& grid, int threads)
    : soup_(soup), grid_(grid), crossings_(soup.parts, grid, threads), rims_(soup.parts) {}

void GridWindingSigns::decide_box(const Box& box, std::vector<int>& which, const std::vector<int64_t>& nodes,
                                  const std::vector<double>& distance, std::vector<std::uint8_t>& inside,
                                  Counts& counts) const {
  if (which.empty()) return;
  // The nodes one by one, or, where the soup estimates many points at once, by one estimate of
  // the box and one by one where that does not decide.
  auto ask_each = [&] {
    if (!soup_.estimate_box || which.size() < 2) {
      for (int q : which) inside[q] = soup_.above_half(grid_.node(nodes[q]));
      counts.asked += int64_t(which.size());
      return;
    }
    std::vector<int> open = which, still;
    std::vector<Vec3> points;
    std::vector<WindingEstimate> e;
    for (int pass = 0; pass < kBoxPasses && !open.empty(); ++pass) {
      points.resize(open.size());
      for (std::size_t q = 0; q < open.size(); ++q) points[q] = grid_.node(nodes[open[q]]);
      soup_.estimate_box(points, kBoxBeta * double(1 << pass), e);
      ++counts.boxes;
      still.clear();
      for (std::size_t q = 0; q < open.size(); ++q) {
        if (e[q].value - 0.5 > e[q].error_bound) {
          inside[open[q]] = 1;
        } else if (0.5 - e[q].value > e[q].error_bound) {
          inside[open[q]] = 0;
        } else {
          still.push_back(open[q]);
        }
      }
      open.swap(still);
    }
    for (int q : open) inside[q] = soup_.above_half(grid_.node(nodes[q]));
    counts.asked += int64_t(open.size());
  };
  const Vec3i extent = box.hi - box.lo;
  if (int(which.size()) <= kAsk || extent.maxCoeff() <= 1) return ask_each();
  // A box small enough for one estimate of the box takes it (a reference would serve it only
  // where no rim is near, and its nodes undecided would need their own estimates).
  if (soup_.estimate_box && extent.maxCoeff() <= kEstimatedBox) return ask_each();
  const double h = grid_.voxel;
  // How fast w may change in the box, and whether a reference could decide anything.
  const double reach = h * double((extent - Vec3i::Ones()).sum());  // the longest path in the box
  const double g = rims_.gradient(grid_.node(box.lo.x(), box.lo.y(), box.lo.z()),
                                  grid_.node(box.hi.x() - 1, box.hi.y() - 1, box.hi.z() - 1), kReach / reach);
  std::vector<int> undecided;
  if (g * reach < kReach) {
    int ref = which[0];
    for (int q : which)
      if (distance[q] > distance[ref]) ref = q;
    if (distance[ref] < kClearance * h) return ask_each();
    const Vec3i c = grid_.indices(nodes[ref]);
    const WindingEstimate e = soup_.estimate(grid_.node(nodes[ref]));
    ++counts.references;
    for (int q : which) {
      const Vec3i v = grid_.indices(nodes[q]);
      const double value = e.value + crossings_.path(c, v);
      const double slack = e.error_bound + g * h * double((v - c).cwiseAbs().sum()) + kRoundoff;
      if (value > 0.5 + slack) {
        inside[q] = 1;
      } else if (value < 0.5 - slack) {
        inside[q] = 0;
      } else {
        undecided.push_back(q);
      }
    }
  } else {
    undecided = which;
  }
  if (undecided.empty()) return;
  // The eight halves (fewer along an axis one node wide), each with its own reference.
  const Vec3i mid = box.lo + (extent + Vec3i::Ones()) / 2;
  std::vector<int> part[8];
  for (int q : undecided) {
    const Vec3i v = grid_.indices(nodes[q]);
    part[(v.x() >= mid.x()) + 2 * (v.y() >= mid.y()) + 4 * (v.z() >= mid.z())].push_back(q);
  }
  for (int o = 0; o < 8; ++o) {
    if (part[o].empty()) continue;
    Box child;
    for (int a = 0; a < 3; ++a) {
      const bool upper = o >> a & 1;
      child.lo[a] = upper ? mid[a] : box.lo[a];
      child.hi[a] = upper ? box.hi[a] : mid[a];
    }
    decide_box(child, part[o], nodes, distance, inside, counts);
  }
}

std::vector<std::uint8_t> GridWindingSigns::decide(const std::vector<int64_t>& nodes, const std::vector<double>& distance,
                                                   int threads, Counts* counts) const {
  std::vector<std::uint8_t> inside(nodes.size(), 0);
  const Vec3i boxes = (grid_.dims + Vec3i::Constant(kTopBox - 1)) / kTopBox;
  // The requests of each top box, in the nodes' order.
  auto box_of = [&](int64_t n) {
    const Vec3i v = grid_.indices(n) / kTopBox;
    return v.x() + int64_t(boxes.x()) * (v.y() + int64_t(boxes.y()) * v.z());
  };
  const int64_t box_count = int64_t(boxes.x()) * boxes.y() * boxes.z();
  std::vector<int64_t> offsets(box_count + 1, 0);
  for (int64_t n : nodes) ++offsets[box_of(n) + 1];
  for (int64_t b = 0; b < box_count; ++b) offsets[b + 1] += offsets[b];
  std::vector<int> order(nodes.size());
  {
    std::vector<int64_t> next(offsets.begin(), offsets.end() - 1);
    for (std::size_t q = 0; q < nodes.size(); ++q) order[next[box_of(nodes[q])]++] = int(q);
  }
  std::vector<int64_t> busy;
  for (int64_t b = 0; b < box_count; ++b)
    if (offsets[b + 1] > offsets[b]) busy.push_back(b);
  std::vector<Counts> per_box(busy.size());
  parallel_for(static_cast<int>(busy.size()), threads, [&](int k) {
    const int64_t b = busy[k];
    Box box;
    box.lo = grid_indices(b, boxes) * kTopBox;
    box.hi = (box.lo + Vec3i::Constant(kTopBox)).cwiseMin(grid_.dims);
    std::vector<int> which;
    for (int64_t o = offsets[b]; o < offsets[b + 1]; ++o) {
      const int q = order[o];
      if (distance[q] < kSnapped * grid_.voxel) {
        inside[q] = soup_.above_half(grid_.node(nodes[q]));
        ++per_box[k].asked;
      } else {
        which.push_back(q);
      }
    }
    per_box[k].nodes = offsets[b + 1] - offsets[b];
    decide_box(box, which, nodes, distance, inside, per_box[k]);
  });
  if (counts) {
    *counts = Counts{};
    for (const Counts& c : per_box) *counts += c;
  }
  return inside;
}

RobustSigns::RobustSigns(const RobustInside& inside, const GridGeometry& grid, int threads)
    : negative_in_(inside.negative_in), grid_(grid) {
  for (const WindingSoup& soup : inside.soups) soups_.push_back(std::make_unique<GridWindingSigns>(soup, grid, threads));
}

std::vector<std::uint8_t> RobustSigns::decide(const std::vector<int64_t>& nodes, const std::vector<double>& distance,
                                              int threads, GridWindingSigns::Counts* counts) const {
  std::vector<std::uint8_t> inside(nodes.size(), 0);
  if (counts) *counts = {};
  if (negative_in_) {
    constexpr int kChunk = 4096;
    parallel_for(int((nodes.size() + kChunk - 1) / kChunk), threads, [&](int c) {
      const std::size_t last = std::min(nodes.size(), std::size_t(c + 1) * kChunk);
      for (std::size_t q = std::size_t(c) * kChunk; q < last; ++q) inside[q] = negative_in_->value(grid_.node(nodes[q])) < 0.0;
    });
  }
  std::vector<int> open;  // the nodes not yet inside
  for (std::size_t q = 0; q < nodes.size(); ++q)
    if (!inside[q]) open.push_back(int(q));
  for (const auto& soup : soups_) {
    std::vector<int64_t> ask(open.size());
    std::vector<double> clearance(open.size());
    for (std::size_t q = 0; q < open.size(); ++q) ask[q] = nodes[open[q]], clearance[q] = distance[open[q]];
    GridWindingSigns::Counts c;
    const std::vector<std::uint8_t> in = soup->decide(ask, clearance, threads, &c);
    if (counts) *counts += c;
    std::vector<int> still;
    for (std::size_t q = 0; q < open.size(); ++q) {
      if (in[q]) inside[open[q]] = 1;
      else still.push_back(open[q]);
    }
    open.swap(still);
  }
  return inside;
}

}  // namespace hairfit::field
