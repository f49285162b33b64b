#include "guides/styled_rest.h"

#include <algorithm>
#include <cmath>

#include "guides/layer_preguide.h"

namespace hairfit {

namespace {

// The rotation vector (axis · angle) that turns unit a onto unit b about a × b.
Vec3 turn(const Vec3& a, const Vec3& b) {
  const Vec3 axis = a.cross(b);
  const double s = axis.norm();
  if (!(s > 1e-15)) return Vec3::Zero();
  return axis * (std::atan2(s, a.dot(b)) / s);
}

Mat3 rotation(const Vec3& v) {
  const double angle = v.norm();
  if (!(angle > 0.0)) return Mat3::Identity();
  return Eigen::AngleAxisd(angle, v / angle).toRotationMatrix();
}

}  // namespace

StyledPath styled_path(const FlowLookup& flow, const Boundary& boundary, const Vec3& root, const Vec3& direction,
                       double length, double target, double thickness, int segments) {
  const double h = length / segments;
  const double share = 1.0 - std::exp(-h / (kStyleRelaxation * length));  // of the turn taken per step
  const double least = 1e-3 * std::max(thickness, 1.0);  // cm: the least thickness λ is read in
  StyledPath path;
  Vec3 p = root, t = direction.normalized();
  path.nodes.push_back(p);
  path.tangents.push_back(t);
  for (int k = 0; k < segments; ++k) {
    Vec3 normal = Vec3::Zero();
    Vec3 desired = flow.at(p, &normal);
    if (desired.isZero(0.0)) {
      desired = normal.isZero(0.0) ? t : Vec3(t - t.dot(normal) * normal);  // on along the layer
    } else {
      // The layer's thickness here (distance to the scalp plus to the hull) is the unit of λ.
      const double local = std::max(boundary.scalp->value(p) - boundary.volume->value(p), least);
      const double miss = target - layer_coordinate(boundary, p, local);
      desired += std::clamp(miss * local / kStyleDepthReach, -1.0, 1.0) * normal;
    }
    const Vec3 next = desired.norm() > 1e-12 ? Vec3(((1.0 - share) * t + share * desired.normalized()).normalized()) : t;
    p += h * (t + next).normalized();
    t = next;
    path.nodes.push_back(p);
    path.tangents.push_back(t);
  }
  return path;
}

std::vector<Vec3> rest_curvature(const StyledPath& path, const Mat3& root_frame) {
  // Per step the rotation of the parallel-transported frame in its own axes, per unit normalised
  // arc length; sampled at the nodes and the steps' midpoints (2N + 1 samples, linear between
  // them), the midpoints holding the step's rotation and each node the mean of its two steps.
  const int n = static_cast<int>(path.tangents.size()) - 1;
  if (n < 1) return {};
  std::vector<Vec3> steps(n);
  Mat3 frame = root_frame;
  for (int k = 0; k < n; ++k) {
    const Vec3 w = turn(path.tangents[k], path.tangents[k + 1]);
    steps[k] = frame.transpose() * w * static_cast<double>(n);
    frame = rotation(w) * frame;
  }
  std::vector<Vec3> samples(2 * n + 1);
  for (int k = 0; k < n; ++k) samples[2 * k + 1] = steps[k];
  samples[0] = steps[0];
  samples[2 * n] = steps[n - 1];
  for (int k = 1; k < n; ++k) samples[2 * k] = 0.5 * (steps[k - 1] + steps[k]);
  return samples;
}

std::vector<Vec3> styled_rest(const FlowLookup& flow, const Boundary& boundary, const Vec3& root,
                              const Mat3& root_frame, double length, double immersion, int segments) {
  const double thickness = std::max(0.0, -boundary.volume->value(root));
  return rest_curvature(styled_path(flow, boundary, root, root_frame.col(2), length, 1.0 - immersion, thickness, segments),
                        root_frame);
}

}  // namespace hairfit
