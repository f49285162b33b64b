// A guide polyline prepared for sweeping a wisp along it: arc length, and a rotation-minimising
// frame (double reflection, Wang et al. 2008) so that fibres do not twist about their guide
// except by the winding the scene asks for.
#pragma once
#include <cstddef>
#include <vector>

#include "core/types.h"

namespace hairfit {

class GuideTrack {
 public:
  explicit GuideTrack(const std::vector<Vec3>& points);

  double length() const { return s_.back(); }
  // Position and frame (tangent t, normals d1, d2; orthonormal, right-handed) at arc length s
  // (cm). Beyond the tip the guide continues straight along its last tangent.
  void at(double s, Vec3& position, Vec3& t, Vec3& d1, Vec3& d2) const;
  // The same, for calls with non-decreasing s (a sweep root to tip): `segment` carries the guide
  // segment found by the previous call (start at 0), so finding the next one is a short forward
  // walk instead of a binary search. Results are identical to at() without the hint.
  void at(double s, Vec3& position, Vec3& t, Vec3& d1, Vec3& d2, std::size_t& segment) const;

 private:
  void interpolate(double s, std::size_t k, Vec3& position, Vec3& t, Vec3& d1, Vec3& d2) const;

  std::vector<Vec3> p_, t_, d1_;
  std::vector<double> s_;
};

}  // namespace hairfit
