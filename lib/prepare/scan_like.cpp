#include "prepare/scan_like.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "core/random.h"

namespace hairfit {

namespace {

constexpr double kDegree = M_PI / 180.0;
// The quantum the bust is rounded to before it is moved: 2⁻²⁴ cm, so a coordinate of up to 2²⁹ cm
// plus an offset that is a multiple of it stays exact.
constexpr double kQuantum = 1.0 / (1 << 24);

Mat3 turned_by_30_degrees() {
  // Forward (about x) by 25°, to the side (about z) by 17°: 30° in all.
  return (Eigen::AngleAxisd(25.0 * kDegree, Vec3::UnitX()) * Eigen::AngleAxisd(17.0 * kDegree, Vec3::UnitZ()))
      .toRotationMatrix();
}

}  // namespace

std::vector<ScanLikeCase> scan_like_cases(double spacing) {
  std::vector<ScanLikeCase> cases;
  ScanLikeCase far{"far", SculptFeatures{}, spacing};
  // 10⁴ times the bust's size (its box's diagonal, about 58 cm) from the origin, in multiples of 4096 cm
  // (so the frame prepare and run compute in, core/mesh.h frame_origin, moves by exactly the offset).
  const Vec3 direction = Vec3(0.6, -0.3, 0.74).normalized();
  for (int axis = 0; axis < 3; ++axis) far.offset[axis] = 4096.0 * std::round(5.8e5 * direction[axis] / 4096.0);
  cases.push_back(far);
  ScanLikeCase coarse{"coarse", sculpt_features(BustStyle::bun), 5.0};
  cases.push_back(coarse);
  ScanLikeCase tilted{"tilted", SculptFeatures{}, spacing};
  tilted.features.tilt = turned_by_30_degrees();
  cases.push_back(tilted);
  // Coarser than 0.3 cm the tilted bows' thin lobes (0.9 cm) get holes and the painted hair handles
  // (the hull is refused as not disk-like), and a braid's end overhanging the hairline makes the
  // scalp's strip cross the hull at every voxel tried.
  ScanLikeCase dressed{"dressed", SculptFeatures{}, std::min(spacing, 0.3)};
  dressed.features.bun = dressed.features.braids = dressed.features.bows = true;
  dressed.features.tilt = turned_by_30_degrees();
  cases.push_back(dressed);
  ScanLikeCase noisy{"noisy", sculpt_features(BustStyle::braids), spacing, 0.05};
  cases.push_back(noisy);
  return cases;
}

ScanLikeCase scan_like_case(const std::string& name, double spacing) {
  for (const ScanLikeCase& c : scan_like_cases(spacing))
    if (c.name == name) return c;
  throw std::invalid_argument("no scan-like case \"" + name + "\" (far, coarse, tilted, dressed, noisy)");
}

void add_scan_noise(Mesh& mesh, double amplitude, std::uint64_t seed) {
  const std::size_t n = mesh.positions.size();
  std::vector<Vec3> normal(n, Vec3::Zero());
  std::vector<std::vector<int>> next(n);
  for (const Vec3i& t : mesh.triangles) {
    const Vec3 face = (mesh.positions[t[1]] - mesh.positions[t[0]]).cross(mesh.positions[t[2]] - mesh.positions[t[0]]);
    for (int k = 0; k < 3; ++k) normal[t[k]] += face, next[t[k]].push_back(t[(k + 1) % 3]);
  }
  // White noise per vertex, averaged with the neighbours twice (a scanner's mesher reconstructs
  // over a few samples, so its noise is correlated over a few edges), then scaled to ±amplitude.
  std::vector<double> noise(n);
  for (std::size_t v = 0; v < n; ++v) noise[v] = Random(seed, RandomStage::test, v).uniform(-1.0, 1.0);
  for (int pass = 0; pass < 2; ++pass) {
    const std::vector<double> previous = noise;
    for (std::size_t v = 0; v < n; ++v) {
      if (next[v].empty()) continue;
      double sum = previous[v];
      for (int k : next[v]) sum += previous[k];
      noise[v] = sum / static_cast<double>(next[v].size() + 1);
    }
  }
  double largest = 0.0;
  for (double x : noise) largest = std::max(largest, std::abs(x));
  for (std::size_t v = 0; v < n; ++v)
    if (normal[v].squaredNorm() > 0.0 && largest > 0.0) mesh.positions[v] += amplitude * noise[v] / largest * normal[v].normalized();
}

BustScan make_scan_like(const ScanLikeCase& c) {
  BustScan scan = make_sculpted_bust(c.features, c.spacing);
  if (c.noise > 0.0) add_scan_noise(scan.mesh, c.noise, 1);
  for (Vec3& p : scan.mesh.positions) {
    for (int axis = 0; axis < 3; ++axis) p[axis] = std::round(p[axis] / kQuantum) * kQuantum;
    p += c.offset;
  }
  return scan;
}

}  // namespace hairfit
