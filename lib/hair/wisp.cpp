#include "hair/wisp.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/smoothstep.h"

namespace hairfit {

int fibre_point_count(const WispShape& shape) { return std::max(2, shape.points); }

namespace {

// Share of the fibre over which it moves from its pore's own offset to its place in the wisp.
constexpr double kSettle = 0.2;

}  // namespace

std::vector<WispStation> wisp_stations(const WispShape& shape) {
  const int n = fibre_point_count(shape);
  std::vector<WispStation> out(n);
  for (int i = 0; i < n; ++i) {
    const double t = static_cast<double>(i) / (n - 1);
    const double angle = 2.0 * M_PI * shape.turns * t;
    const double ca = std::cos(angle), sa = std::sin(angle);
    out[i] = {t, smoothstep(t / kSettle), shape.root_radius + (shape.tip_radius - shape.root_radius) * t, ca, sa};
  }
  return out;
}

const std::vector<WispStation>& kept_wisp_stations(const WispShape& shape) {
  thread_local WispShape key;
  thread_local std::vector<WispStation> kept;
  if (kept.size() != static_cast<std::size_t>(fibre_point_count(shape)) || key.root_radius != shape.root_radius ||
      key.tip_radius != shape.tip_radius || key.turns != shape.turns) {
    kept = wisp_stations(shape);
    key = shape;
  }
  return kept;
}

namespace {

struct FibreLayout {
  double a, b, c;  // pore offset from the guide root in the root frame (d1, d2, t)
  double u1, u2;   // its place in the wisp's unit disk
};

// The offsets of point i do not depend on the reach, so they are computed once per fibre rather
// than in every step of the length solve.
void sweep_points(const FibreLayout& f, const std::vector<WispStation>& stations, WispPoint* out) {
  for (std::size_t i = 0; i < stations.size(); ++i) {
    const WispStation& q = stations[i];
    const double x = (1.0 - q.w) * f.a + q.w * f.u1 * q.radius;
    const double y = (1.0 - q.w) * f.b + q.w * f.u2 * q.radius;
    out[i] = {q.t, q.ca * x - q.sa * y, q.sa * x + q.ca * y, (1.0 - q.w) * f.c};
  }
}

// The guide's position and frame at its root (arc length 0).
struct RootFrame {
  Vec3 position, tangent, d1, d2;
};

// The n points of a fibre that runs along the guide up to arc length `reach`. Arc length 0 (the
// first point, and every point of the solve's first, zero-reach sweep) takes the root frame found
// once per fibre instead of asking the track again.
void sweep(const GuideTrack& track, const WispPoint* layout, int n, const RootFrame& root, double reach, Vec3* out) {
  std::size_t segment = 0;  // arc lengths reach·t_i only grow along the fibre
  for (int i = 0; i < n; ++i) {
    const WispPoint& q = layout[i];
    const double s = reach * q.t;
    if (s == 0.0) {
      out[i] = root.position + q.along_d1 * root.d1 + q.along_d2 * root.d2 + q.along_root_tangent * root.tangent;
    } else {
      Vec3 g, tangent, d1, d2;
      track.at(s, g, tangent, d1, d2, segment);
      out[i] = g + q.along_d1 * d1 + q.along_d2 * d2 + q.along_root_tangent * root.tangent;
    }
  }
}

double polyline_length(const Vec3* p, int n) {
  double length = 0.0;
  for (int i = 1; i < n; ++i) length += (p[i] - p[i - 1]).norm();
  return length;
}

}  // namespace

double wisp_extent(const GuideTrack& guide, const std::vector<Vec3>& positions, const std::vector<int>& pores) {
  RootFrame root;
  guide.at(0.0, root.position, root.tangent, root.d1, root.d2);
  double extent = 0.0;
  for (int i : pores) {
    const Vec3 delta = positions[i] - root.position;
    extent = std::max(extent, std::hypot(delta.dot(root.d1), delta.dot(root.d2)));
  }
  return extent;
}

void grow_fibre(const GuideTrack& guide, const Vec3& pore, double length, double wisp_extent, const WispShape& shape,
                Vec3* points) {
  const std::vector<WispStation>& stations = kept_wisp_stations(shape);
  thread_local std::vector<WispPoint> layout;
  layout.resize(stations.size());
  fibre_along(guide, pore, length, wisp_extent, stations, nullptr, points, layout.data());
}

void fibre_along(const GuideTrack& track, const Vec3& pore, double length, double wisp_extent,
                 const std::vector<WispStation>& stations, const FibreAdjust* adjust, Vec3* points, WispPoint* layout) {
  const int n = static_cast<int>(stations.size());
  RootFrame root;
  track.at(0.0, root.position, root.tangent, root.d1, root.d2);
  const Vec3& t0 = root.tangent;
  const Vec3 delta = pore - root.position;
  FibreLayout f{delta.dot(root.d1), delta.dot(root.d2), delta.dot(t0), 0.0, 0.0};
  if (wisp_extent > 0.0) {
    f.u1 = f.a / wisp_extent;
    f.u2 = f.b / wisp_extent;
  }
  sweep_points(f, stations, layout);
  // The polyline's length L grows with how far along the guide it reaches; find the reach r
  // with L(r) = `length`. L is nearly proportional to r, so the first guess scales the full
  // reach by length / L(length); secant steps follow, kept inside the bracket of reaches known
  // too short and too long (a step that would leave it bisects instead). On the paper-scale
  // scene this takes 4.7 sweeps a fibre where regula falsi on [0, length] (Illinois) took 6.7.
  auto excess = [&](double reach) {
    sweep(track, layout, n, root, reach, points);
    if (adjust) (*adjust)(points, n);
    return polyline_length(points, n) - length;
  };
  const double tolerance = 1e-12 * length;
  double r1 = length, f1 = excess(r1);  // the latest reach, and the one before (r0) for the secant
  if (std::fabs(f1) > tolerance) {
    // Reaches known too short and too long. Reach 0 (the wisp offsets alone) is taken to be too
    // short until a step would leave the bracket there; then it is measured, and if it is not,
    // the fibre is too short for its own offsets: a straight fibre along the root tangent.
    double lo = 0.0, hi = std::numeric_limits<double>::infinity();
    bool zero_measured = false;
    (f1 < 0.0 ? lo : hi) = r1;
    double r0 = r1, f0 = f1;
    double next = r1 * length / (f1 + length);  // L(r) ≈ L(length)·r/length
    for (int iteration = 0; iteration < 100; ++iteration) {
      if (!(next > lo && next < hi)) {
        if (lo == 0.0 && !zero_measured) {
          zero_measured = true;
          if (excess(0.0) >= 0.0) {
            for (int i = 0; i < n; ++i) points[i] = pore + length * static_cast<double>(i) / static_cast<double>(n - 1) * t0;
            if (adjust) (*adjust)(points, n);  // kept out of the head as every other fibre is
            points[0] = pore;
            return;
          }
        }
        next = std::isfinite(hi) ? 0.5 * (lo + hi) : 2.0 * lo;
      }
      r0 = r1, f0 = f1;
      r1 = next, f1 = excess(r1);
      if (std::fabs(f1) <= tolerance) break;
      (f1 < 0.0 ? lo : hi) = r1;
      // A bracket this narrow that still misses the length by more than the tolerance holds a
      // jump of the length (below), not a root: bisecting it further to round-off only costs sweeps.
      if (hi - lo <= 1e-9 * length) break;
      next = f1 != f0 ? r1 - f1 * (r1 - r0) / (f1 - f0) : std::numeric_limits<double>::quiet_NaN();
    }
    // A lift off the scalp, or a seam of the fields a fibre is moved by, can make the length jump
    // with the reach, so that no reach gives it exactly: the fibre at the shortest reach known too
    // long then ends short of its last point by the excess, along its last chord (a part of a
    // chord that crosses nothing crosses nothing). Where the excess is longer than that chord, the
    // fibre at the longest reach known too short goes on along its last chord by the shortfall.
    if (std::fabs(f1) > tolerance && std::isfinite(hi)) {
      const double too_long = r1 == hi ? f1 : excess(hi);
      const double last = (points[n - 1] - points[n - 2]).norm();
      if (too_long > 0.0 && too_long < last) {
        points[n - 1] = points[n - 2] + (1.0 - too_long / last) * (points[n - 1] - points[n - 2]);
      } else if (lo > 0.0) {
        const double too_short = -excess(lo);
        const double chord = (points[n - 1] - points[n - 2]).norm();
        if (too_short > 0.0 && chord > 0.0)
          points[n - 1] = points[n - 2] + (1.0 + too_short / chord) * (points[n - 1] - points[n - 2]);
      }
    }
  }
  points[0] = pore;  // exactly, not up to round-off
}

}  // namespace hairfit
