#include "strands/cutting.h"

#include <cmath>

namespace hairfit {

std::size_t cut_in_place(Vec3* points, std::size_t n, double* d, const DistanceFunction& distance, double threshold,
                         bool cut_tips, const DistanceFunction& quick, bool& cut, double& outside_length) {
  cut = false;
  outside_length = 0.0;
  const DistanceFunction& first = quick ? quick : distance;
  for (std::size_t i = 0; i < n; ++i) d[i] = first(points[i]);
  auto exact = [&](std::size_t i) {  // where the crossing is interpolated, the distance itself
    if (std::isinf(d[i])) d[i] = distance(points[i]);
  };

  // The root is fixed on the scalp: a stretch outside that starts at the root (a scalp that pokes
  // out of the volume) is never cut, only excursions after the fibre has been inside.
  bool outside = false;
  bool been_inside = n > 0 && d[0] <= 0.0;
  std::size_t exit_segment = 0;  // segment in which the current excursion started
  Vec3 exit_point = n > 0 ? points[0] : Vec3::Zero();
  double length_outside = 0.0;
  // Ends the fibre at the crossing where the excursion started; the crossing (if it is not the
  // segment's first point) takes the place of the segment's second point.
  auto cut_here = [&]() -> std::size_t {
    std::size_t kept = exit_segment + 1;
    if ((exit_point - points[exit_segment]).norm() > 0.0) ++kept;
    if (kept < 2) return n;  // left right at a root on the boundary: nothing to keep
    if (kept == exit_segment + 2) {
      points[exit_segment + 1] = exit_point;
      d[exit_segment + 1] = distance(exit_point);
    }
    cut = true;
    outside_length = length_outside;
    return kept;
  };
  for (std::size_t i = 0; i + 1 < n; ++i) {
    const Vec3& a = points[i];
    const Vec3& b = points[i + 1];
    const double length = (b - a).norm();
    const bool a_out = d[i] > 0.0, b_out = d[i + 1] > 0.0;
    if (a_out != b_out) exact(i), exact(i + 1);
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
  if (cut_tips && outside) return cut_here();
  return n;
}

CutResult cut_at_exit(const std::vector<Vec3>& points, const DistanceFunction& distance, double threshold,
                      const DistanceFunction& quick, bool cut_tips) {
  CutResult result;
  result.points = points;
  result.distances.resize(points.size());
  const std::size_t kept = cut_in_place(result.points.data(), points.size(), result.distances.data(), distance, threshold,
                                        cut_tips, quick, result.cut, result.outside_length);
  result.points.resize(kept);
  result.distances.resize(kept);
  return result;
}

}  // namespace hairfit
