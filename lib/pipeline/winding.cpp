#include "pipeline/winding.h"

#include <algorithm>
#include <cmath>

namespace hairfit {

double closed_winding_number(const Mesh& closed, const Vec3& point) {
  // The ray from the point along +x crosses the triangles whose projection onto the (y, z) plane
  // contains the point's projection, in front of it. Each crossing counts the sign of the
  // triangle's normal along x: +1 leaving an outward surface, −1 entering it.
  // Tolerances far above the round-off of the coordinates (~1e-16 of their magnitude) in the
  // tests below: within them the count could be wrong, and the solid angles decide instead.
  constexpr double kTolerance = 1e-9;
  int crossings = 0;
  for (const Vec3i& t : closed.triangles) {
    const Vec3& a = closed.positions[t[0]];
    const Vec3& b = closed.positions[t[1]];
    const Vec3& c = closed.positions[t[2]];
    const double ay = a.y() - point.y(), by = b.y() - point.y(), cy = c.y() - point.y();
    const double az = a.z() - point.z(), bz = b.z() - point.z(), cz = c.z() - point.z();
    // Most triangles lie wholly to one side of the ray.
    if ((ay > 0 && by > 0 && cy > 0) || (ay < 0 && by < 0 && cy < 0) || (az > 0 && bz > 0 && cz > 0) ||
        (az < 0 && bz < 0 && cz < 0))
      continue;
    const double size = std::max({1.0, point.cwiseAbs().maxCoeff(), a.cwiseAbs().maxCoeff(), b.cwiseAbs().maxCoeff(),
                                  c.cwiseAbs().maxCoeff()});  // cm
    // Twice the signed areas of the projected triangle's edges with the ray's foot point.
    const double eab = ay * bz - az * by, ebc = by * cz - bz * cy, eca = cy * az - cz * ay;
    const double near_edge = kTolerance * size * size;
    if (std::fabs(eab) <= near_edge || std::fabs(ebc) <= near_edge || std::fabs(eca) <= near_edge)
      return winding_number(closed, point);  // on or near an edge's projection: no exact count
    if ((eab > 0) != (ebc > 0) || (ebc > 0) != (eca > 0)) continue;  // the ray misses it
    const double area = eab + ebc + eca;  // the normal's x component, ×2
    // How far along the ray it meets the triangle's plane.
    const double along = (ebc * (a.x() - point.x()) + eca * (b.x() - point.x()) + eab * (c.x() - point.x())) / area;
    if (std::fabs(along) <= kTolerance * size) return winding_number(closed, point);  // on the surface
    if (along > 0) crossings += area > 0 ? 1 : -1;
  }
  return crossings;
}

}  // namespace hairfit
