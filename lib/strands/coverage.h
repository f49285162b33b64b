// How much of the hair volume's boundary the strands reach (issue 23's measure): the hull's area,
// sampled by area, within `radius` of a strand point. Samples where `counts` says no (the hull's
// parts behind the scalp, which no hair can reach) are left out of the share.
#pragma once
#include <functional>
#include <vector>

#include "core/mesh.h"

namespace hairfit {

struct CoverageOptions {
  double radius = 0.75;  // cm
  int samples = 20000;   // area samples over the whole hull
  int threads = 1;
};

struct Coverage {
  int samples = 0;     // samples that count
  int covered = 0;     // of those, within `radius` of a strand point
  double share = 0.0;  // covered / samples (0 without samples)
};

// Sample k lies in the triangle where the cumulative area reaches (k + ½)/samples of the total
// (stratified by area), at the R2 low-discrepancy point k folded into the triangle: deterministic,
// and the same for any thread count.
std::vector<Vec3> area_samples(const Mesh& mesh, int samples);
// The same samples, each with the triangle it lies in.
struct AreaSample {
  int triangle = 0;
  Vec3 point = Vec3::Zero();
};
std::vector<AreaSample> area_samples_on_triangles(const Mesh& mesh, int samples);

Coverage strand_coverage(const Mesh& hull, const std::vector<Vec3>& strand_points,
                         const std::function<bool(const Vec3&)>& counts, const CoverageOptions& options = {});

}  // namespace hairfit
