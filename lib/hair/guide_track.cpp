#include "hair/guide_track.h"

#include <algorithm>
#include <cmath>

namespace hairfit {

namespace {

// A unit vector perpendicular to t, chosen from the axis least aligned with it (deterministic).
Vec3 any_normal(const Vec3& t) {
  Eigen::Index axis;
  t.cwiseAbs().minCoeff(&axis);
  const Vec3 e = Vec3::Unit(axis);
  return (e - e.dot(t) * t).normalized();
}

}  // namespace

GuideTrack::GuideTrack(const std::vector<Vec3>& points) {
  // Drop repeated points: they have no tangent.
  for (const Vec3& q : points)
    if (p_.empty() || (q - p_.back()).norm() > 1e-12) p_.push_back(q);
  if (p_.size() == 1) p_.push_back(p_[0] + Vec3(0, 0, 1e-9));
  const std::size_t n = p_.size();
  s_.assign(n, 0.0);
  for (std::size_t i = 1; i < n; ++i) s_[i] = s_[i - 1] + (p_[i] - p_[i - 1]).norm();
  // Node tangents: the mean of the adjacent segment directions.
  t_.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3 before = i > 0 ? Vec3((p_[i] - p_[i - 1]).normalized()) : Vec3::Zero();
    const Vec3 after = i + 1 < n ? Vec3((p_[i + 1] - p_[i]).normalized()) : Vec3::Zero();
    const Vec3 sum = before + after;
    t_[i] = sum.norm() > 1e-12 ? Vec3(sum.normalized()) : (after.norm() > 0 ? after : before);
  }
  d1_.resize(n);
  d1_[0] = any_normal(t_[0]);
  for (std::size_t i = 0; i + 1 < n; ++i) {
    // Double reflection: reflect across the bisector plane of the chord, then across the plane
    // that maps the reflected tangent onto the next tangent.
    const Vec3 v1 = p_[i + 1] - p_[i];
    const double c1 = v1.squaredNorm();
    const Vec3 r = d1_[i] - (2.0 / c1) * v1.dot(d1_[i]) * v1;
    const Vec3 tl = t_[i] - (2.0 / c1) * v1.dot(t_[i]) * v1;
    const Vec3 v2 = t_[i + 1] - tl;
    const double c2 = v2.squaredNorm();
    Vec3 next = c2 > 1e-30 ? Vec3(r - (2.0 / c2) * v2.dot(r) * v2) : r;
    next -= next.dot(t_[i + 1]) * t_[i + 1];
    d1_[i + 1] = next.norm() > 1e-12 ? Vec3(next.normalized()) : any_normal(t_[i + 1]);
  }
}

void GuideTrack::at(double s, Vec3& position, Vec3& t, Vec3& d1, Vec3& d2) const {
  const std::size_t n = p_.size();
  const std::size_t k = s >= s_.back() ? n - 1 : std::upper_bound(s_.begin(), s_.end(), std::max(s, 0.0)) - s_.begin() - 1;
  interpolate(s, k, position, t, d1, d2);
}

void GuideTrack::at(double s, Vec3& position, Vec3& t, Vec3& d1, Vec3& d2, std::size_t& segment) const {
  const std::size_t n = p_.size();
  if (s >= s_.back()) {
    interpolate(s, n - 1, position, t, d1, d2);
    return;
  }
  const double clamped = std::max(s, 0.0);
  if (segment >= n - 1 || s_[segment] > clamped) segment = 0;  // not a forward step: start over
  // The last node at or before s (s_ increases strictly), as upper_bound − 1 would find it.
  while (s_[segment + 1] <= clamped) ++segment;
  interpolate(s, segment, position, t, d1, d2);
}

// Position and frame at s on segment k (k = n − 1: beyond the tip).
void GuideTrack::interpolate(double s, std::size_t k, Vec3& position, Vec3& t, Vec3& d1, Vec3& d2) const {
  const std::size_t n = p_.size();
  if (k == n - 1) {
    const Vec3 last = (p_[n - 1] - p_[n - 2]).normalized();
    position = p_[n - 1] + (s - s_.back()) * last;
    t = t_[n - 1];
    d1 = d1_[n - 1];
  } else {
    s = std::max(s, 0.0);
    const double f = (s - s_[k]) / (s_[k + 1] - s_[k]);
    position = (1.0 - f) * p_[k] + f * p_[k + 1];
    t = ((1.0 - f) * t_[k] + f * t_[k + 1]).normalized();
    d1 = (1.0 - f) * d1_[k] + f * d1_[k + 1];
  }
  d1 = (d1 - d1.dot(t) * t).normalized();
  d2 = t.cross(d1);
}

}  // namespace hairfit
