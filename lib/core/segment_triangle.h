// Where a segment crosses a triangle (Möller and Trumbore, "Fast, minimum storage ray–triangle
// intersection", 1997): the segment's parameter of the crossing point, if it lies in the segment's
// open interior and on the closed triangle.
#pragma once
#include <cmath>
#include <limits>

#include "core/types.h"

namespace hairfit {

// The share t of the way from p to q at which segment pq meets triangle abc, if t lies in
// (t_min, t_max) (by default the segment's open interior), or NaN where it does not (also when pq
// is parallel to the triangle's plane, or the triangle is degenerate). With `slack` > 0 the
// triangle grows by that much in barycentric terms (u, v ≥ −slack, u + v ≤ 1 + slack): a test that
// must not miss a segment grazing an edge that is no other triangle's (a mesh's rim), or touching
// the surface at an end (t_min < 0 < 1 < t_max), whichever way round-off falls.
inline double segment_triangle_parameter(const Vec3& p, const Vec3& q, const Vec3& a, const Vec3& b, const Vec3& c,
                                         double slack = 0.0, double t_min = 1e-9, double t_max = 1 - 1e-9) {
  const Vec3 d = q - p, e1 = b - a, e2 = c - a, h = d.cross(e2);
  const double det = e1.dot(h);
  const double none = std::numeric_limits<double>::quiet_NaN();
  if (std::abs(det) < 1e-300) return none;
  const Vec3 s = p - a;
  const double u = s.dot(h) / det;
  if (u < -slack || u > 1 + slack) return none;
  const Vec3 w = s.cross(e1);
  const double v = d.dot(w) / det;
  if (v < -slack || u + v > 1 + slack) return none;
  const double t = e2.dot(w) / det;
  return t > t_min && t < t_max ? t : none;
}

}  // namespace hairfit
