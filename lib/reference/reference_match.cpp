#include "reference/reference_match.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "core/parallel.h"
#include "core/point_grid.h"

namespace hairfit {

OrientedPoints curve_points(const Curves& curves, double spacing) {
  if (!(spacing > 0.0)) throw std::invalid_argument("curve_points: spacing must be > 0");
  OrientedPoints out;
  for (std::size_t c = 0; c < curves.count(); ++c) {
    double next = 0.0;  // arc length of the next point, from the curve's root
    double s = 0.0;     // arc length at the start of the current segment
    for (std::size_t i = 0; i + 1 < curves.size(c); ++i) {
      const Vec3 a = curves.point(c, i), b = curves.point(c, i + 1);
      const double length = (b - a).norm();
      if (!(length > 0.0)) continue;
      const Vec3 direction = (b - a) / length;
      // Points on [s, s + length): the end itself belongs to the next segment (or is the tip).
      for (; next < s + length; next += spacing) {
        out.points.push_back(a + (next - s) * direction);
        out.directions.push_back(direction);
      }
      s += length;
    }
    if (s > 0.0 && next <= s) {  // the tip, when it falls on the spacing
      out.points.push_back(curves.point(c, curves.size(c) - 1));
      out.directions.push_back(out.directions.back());
    }
  }
  return out;
}

double direction_angle(const Vec3& a, const Vec3& b, bool signed_directions) {
  const double along = a.dot(b);
  return std::atan2(a.cross(b).norm(), signed_directions ? along : std::abs(along)) * (180.0 / M_PI);
}

namespace {

void check(const OrientedPoints& p, const char* which) {
  if (p.points.size() != p.directions.size())
    throw std::invalid_argument(std::string("match_reference: the ") + which + " points and directions differ in number");
}

// Per point of `from`: whether a point of `to` (in `grid`) within the radius turns by at most the
// angle (bit 1), and whether any lies within the radius (bit 2).
std::vector<unsigned char> matched(const OrientedPoints& from, const OrientedPoints& to, const PointGrid& grid,
                                   const MatchOptions& o) {
  std::vector<unsigned char> state(from.points.size(), 0);
  if (to.points.empty()) return state;
  parallel_for(static_cast<int>(from.points.size()), o.threads, [&](int k) {
    unsigned char s = 0;
    grid.for_each_within(from.points[k], o.radius, [&](int j, double) {
      s |= 2;
      if (direction_angle(from.directions[k], to.directions[j], o.signed_directions) <= o.max_angle) s |= 1;
    });
    state[k] = s;
  });
  return state;
}

double share(const std::vector<unsigned char>& state, unsigned char bit) {
  if (state.empty()) return 0.0;
  const auto n = std::count_if(state.begin(), state.end(), [&](unsigned char s) { return (s & bit) != 0; });
  return static_cast<double>(n) / static_cast<double>(state.size());
}

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  const std::size_t n = v.size(), half = n / 2;
  std::nth_element(v.begin(), v.begin() + half, v.end());
  if (n % 2) return v[half];
  const double upper = v[half];
  return 0.5 * (*std::max_element(v.begin(), v.begin() + half) + upper);
}

void check_options(const MatchOptions& o) {
  if (!(o.radius > 0.0) || !(o.max_angle >= 0.0 && o.max_angle <= 180.0))
    throw std::invalid_argument("match_reference: needs radius > 0 and max_angle in [0, 180] degrees");
}

}  // namespace

std::vector<unsigned char> matched_points(const OrientedPoints& from, const OrientedPoints& to, const MatchOptions& o) {
  check_options(o);
  check(from, "first");
  check(to, "second");
  std::vector<unsigned char> state = matched(from, to, PointGrid(to.points, o.radius), o);
  for (unsigned char& s : state) s &= 1;
  return state;
}

MatchFigures match_reference(const OrientedPoints& generated, const OrientedPoints& reference, const MatchOptions& o) {
  check_options(o);
  check(generated, "generated");
  check(reference, "reference");
  MatchFigures f;
  f.generated = static_cast<int>(generated.points.size());
  f.reference = static_cast<int>(reference.points.size());
  if (generated.points.empty() || reference.points.empty()) return f;

  const PointGrid reference_grid(reference.points, o.radius), generated_grid(generated.points, o.radius);
  const std::vector<unsigned char> forward = matched(generated, reference, reference_grid, o);
  const std::vector<unsigned char> backward = matched(reference, generated, generated_grid, o);
  f.precision = share(forward, 1);
  f.recall = share(backward, 1);
  f.f = f.precision + f.recall > 0.0 ? 2.0 * f.precision * f.recall / (f.precision + f.recall) : 0.0;
  f.reached = share(backward, 2);
  f.near = share(forward, 2);

  std::vector<double> angles(generated.points.size());
  parallel_for(f.generated, o.threads, [&](int k) {
    const int j = reference_grid.nearest(generated.points[k], -1, std::numeric_limits<double>::infinity());
    angles[k] = direction_angle(generated.directions[k], reference.directions[j], o.signed_directions);
  });
  f.median_angle = median(std::move(angles));
  return f;
}

}  // namespace hairfit
