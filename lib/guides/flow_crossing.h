// How coherent a set of curves flows (issue 23's measure): over all pairs of points from different
// curves lying between `near` and `far` apart, the share whose unit tangents differ by more than
// `angle` degrees, and the median angle. Tangents are directed (root to tip), by central
// differences of the polyline (one-sided at the ends). Above `max_points` points the figures are
// estimated from the pairs of a sample of about that many (each point in with chance 1/k by a
// hash of its index, with all its neighbours): the paper-scale guides hold 195 000 points and
// 1.1e8 pairs. Deterministic for any thread count.
#pragma once
#include <cstdint>

#include "core/curves.h"

namespace hairfit {

struct FlowCrossing {
  std::int64_t pairs = 0;         // point pairs from different curves within [near, far] (estimated when sampled)
  double crossing_share = 0.0;    // of those, the share whose tangents differ by more than `angle`
  double median_degrees = 0.0;    // median tangent angle over the pairs (0.05° bins)
  int sampled_points = 0;         // the query points of a sample; 0 when every pair was counted
};

struct FlowCrossingOptions {
  double near = 0.3;    // cm
  double far = 1.5;     // cm
  double angle = 45.0;  // degrees
  int max_points = 10000;  // points counted exactly, all pairs; beyond, a sample of about this many (0: always all)
  int threads = 1;
};

FlowCrossing flow_crossing(const Curves& curves, const FlowCrossingOptions& options = {});

}  // namespace hairfit
