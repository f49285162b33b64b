#include "strands/cutting.h"

namespace hairfit {

CutResult cut_at_exit(const std::vector<Vec3>& points, const DistanceFunction& distance, double threshold) {
  CutResult result;
  const std::size_t n = points.size();
  std::vector<double> d(n);
  for (std::size_t i = 0; i < n; ++i) d[i] = distance(points[i]);

  // The root is fixed on the scalp: a stretch outside that starts at the root (a scalp that pokes
  // out of the volume) is never cut, only excursions after the fibre has been inside.
  bool outside = false;
  bool been_inside = n > 0 && d[0] <= 0.0;
  std::size_t exit_segment = 0;  // segment in which the current excursion started
  Vec3 exit_point = n > 0 ? points[0] : Vec3::Zero();
  double length_outside = 0.0;
  auto keep_all = [&]() {
    result.points = points;
    result.distances = std::move(d);
    return result;
  };
  auto cut_here = [&]() {
    result.points.assign(points.begin(), points.begin() + exit_segment + 1);
    result.distances.assign(d.begin(), d.begin() + exit_segment + 1);
    if ((exit_point - result.points.back()).norm() > 0.0) {
      result.points.push_back(exit_point);
      result.distances.push_back(distance(exit_point));
    }
    if (result.points.size() < 2) return keep_all();  // left right at a root on the boundary: nothing to keep
    result.cut = true;
    result.outside_length = length_outside;
    return result;
  };
  for (std::size_t i = 0; i + 1 < n; ++i) {
    const Vec3& a = points[i];
    const Vec3& b = points[i + 1];
    const double length = (b - a).norm();
    const bool a_out = d[i] > 0.0, b_out = d[i + 1] > 0.0;
    // Fraction of the segment at which the distance crosses zero (linear interpolation).
    const double t = a_out != b_out ? d[i] / (d[i] - d[i + 1]) : 0.0;
    if (!been_inside) {
      been_inside = !b_out;
      continue;
    }
    if (!outside && b_out) {  // leaves the volume in this segment
      outside = true;
      exit_segment = i;
      exit_point = a + t * (b - a);
      length_outside = (1.0 - t) * length;
    } else if (outside && !b_out) {  // re-enters
      length_outside += t * length;
      if (length_outside > threshold) return cut_here();
      outside = false;
      length_outside = 0.0;
    } else if (outside) {
      length_outside += length;
    }
    if (outside && length_outside > threshold) return cut_here();
  }
  return keep_all();
}

}  // namespace hairfit
