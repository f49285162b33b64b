#include "field/rim_bound.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include "core/weld.h"

namespace hairfit::field {

namespace {

constexpr int kLeafSize = 4;

// Distance from p to the box [lo, hi] (0 inside it).
double box_distance(const Vec3& p, const Vec3& lo, const Vec3& hi) {
  return (p.cwiseMax(lo).cwiseMin(hi) - p).norm();
}

}  // namespace

RimBound::RimBound(const std::vector<SoupPart>& soup) {
  // Every part's vertices, one id per distinct position (the lowest index holding it).
  std::vector<Vec3> positions;
  for (const SoupPart& part : soup) positions.insert(positions.end(), part.mesh->positions.begin(), part.mesh->positions.end());
  const std::vector<int> id = weld_points(positions, 0.0);
  std::map<std::pair<int, int>, int> multiplicity;  // (lower id, higher id) → faces low→high minus high→low
  int base = 0;  // the part's first vertex in `positions`
  for (const SoupPart& part : soup) {
    for (const Vec3i& t : part.mesh->triangles) {
      const Vec3& a = positions[t[0] + base];
      if ((positions[t[1] + base] - a).cross(positions[t[2] + base] - a).squaredNorm() == 0.0) continue;
      for (int k = 0; k < 3; ++k) {
        const int from = id[t[k] + base], to = id[t[(k + 1) % 3] + base];
        multiplicity[{std::min(from, to), std::max(from, to)}] += from < to ? part.weight : -part.weight;
      }
    }
    base += int(part.mesh->positions.size());
  }
  for (const auto& [edge, m] : multiplicity) {
    if (m > 0) rims_.push_back({positions[edge.first], positions[edge.second], double(m)});
    if (m < 0) rims_.push_back({positions[edge.second], positions[edge.first], double(-m)});
  }
  if (!rims_.empty()) build(0, static_cast<int>(rims_.size()));
}

int RimBound::build(int first, int count) {
  const int index = static_cast<int>(nodes_.size());
  nodes_.emplace_back();
  Vec3 lo = rims_[first].a.cwiseMin(rims_[first].b), hi = rims_[first].a.cwiseMax(rims_[first].b);
  double length = 0;
  Vec3 current = Vec3::Zero();
  for (int r = first; r < first + count; ++r) {
    lo = lo.cwiseMin(rims_[r].a).cwiseMin(rims_[r].b);
    hi = hi.cwiseMax(rims_[r].a).cwiseMax(rims_[r].b);
    length += rims_[r].multiplicity * (rims_[r].b - rims_[r].a).norm();
    current += rims_[r].multiplicity * (rims_[r].b - rims_[r].a);
  }
  Node node;
  node.centre = 0.5 * (lo + hi);
  node.radius = 0.5 * (hi - lo).norm();
  node.weighted_length = length;
  node.current = current;
  node.first = first;
  node.count = count;
  if (count > kLeafSize) {
    int axis;
    (hi - lo).maxCoeff(&axis);
    const int mid = first + count / 2;
    std::nth_element(rims_.begin() + first, rims_.begin() + mid, rims_.begin() + first + count,
                     [axis](const Rim& x, const Rim& y) { return x.a[axis] + x.b[axis] < y.a[axis] + y.b[axis]; });
    node.left = build(first, mid - first);
    node.right = build(mid, first + count - mid);
  }
  nodes_[index] = node;
  return index;
}

double RimBound::bound(int index, const Vec3& lo, const Vec3& hi, double limit) const {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  const Node& node = nodes_[index];
  const double d = box_distance(node.centre, lo, hi), rho = d - node.radius;
  double best = kInf;
  if (rho > 0) {
    const double r = node.radius, l = node.weighted_length;
    best = std::min(l / (rho * rho), node.current.norm() / (d * d) + 2 * r * l / (rho * rho * rho));
    if (rho > 2 * r) return best;  // the children would not bound much tighter
  }
  if (node.left >= 0) {
    const double left = bound(node.left, lo, hi, std::min(best, limit));
    if (left > limit) return std::min(best, kInf);
    return std::min(best, left + bound(node.right, lo, hi, std::min(best, limit) - left));
  }
  // A leaf's rims one by one: each at least its distance from the box's centre less the box's
  // half-diagonal away.
  const Vec3 centre = 0.5 * (lo + hi);
  const double half_diagonal = 0.5 * (hi - lo).norm();
  double sum = 0;
  for (int k = node.first; k < node.first + node.count; ++k) {
    const Rim& rim = rims_[k];
    const Vec3 e = rim.b - rim.a;
    const double t = std::clamp((centre - rim.a).dot(e) / e.squaredNorm(), 0.0, 1.0);
    const double dr = (rim.a + t * e - centre).norm() - half_diagonal;
    if (!(dr > 0)) return best;
    sum += rim.multiplicity * std::min(e.norm() / (dr * dr), M_PI / dr);
  }
  return std::min(best, sum);
}

double RimBound::gradient(const Vec3& lo, const Vec3& hi, double limit) const {
  if (nodes_.empty()) return 0.0;
  return bound(0, lo, hi, 4 * M_PI * limit) / (4 * M_PI);
}

}  // namespace hairfit::field
