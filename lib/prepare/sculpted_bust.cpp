#include "prepare/sculpted_bust.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>

#include "core/parallel.h"
#include "prepare/marching_tetrahedra.h"

namespace hairfit {

namespace {

constexpr double kDegree = M_PI / 180.0;

// The procedural bust's head, neck and tapered layer without its radial bun and braids.
BustShape base_shape() {
  BustShape shape;
  shape.bun_height = 0.0;
  shape.braid_height = 0.0;
  return shape;
}

// Polynomial smooth minimum: a fillet of width k where two shapes join.
double smooth_min(double a, double b, double k) {
  const double h = std::max(k - std::abs(a - b), 0.0) / k;
  return std::min(a, b) - 0.25 * h * h * k;
}

Vec3 direction_of(const Vec3& p) {
  const double r = p.norm();
  return r > 1e-12 ? Vec3(p / r) : Vec3(Vec3::UnitY());
}

// Radial offsets above the bare skin and above the hair layer (≈ distances where the surface
// faces the centre, as the skull and the layer do).
double above_skin(const BustShape& s, const Vec3& p) { return p.norm() - s.skin_radius(direction_of(p)); }
double above_layer(const BustShape& s, const Vec3& p) { return p.norm() - s.radius(direction_of(p)); }

// The point of the hair surface along u, lifted by `lift`.
Vec3 on_hair(const BustShape& s, const Vec3& u, double lift) { return (s.radius(u) + lift) * u; }

// An ellipsoid with orthonormal axes a, b, c and half-lengths ha, hb, hc (scaled so the value is
// a lower bound of the distance, exact in its thin direction).
double ellipsoid(const Vec3& p, const Vec3& centre, const Vec3& a, const Vec3& b, const Vec3& c, double ha,
                 double hb, double hc) {
  const Vec3 d = p - centre;
  const Vec3 q(d.dot(a) / ha, d.dot(b) / hb, d.dot(c) / hc);
  return (q.norm() - 1.0) * std::min({ha, hb, hc});
}

// A braid: a tube along a path lying on the hair, its radius swelling every 1.8 cm (the plaits).
struct Braid {
  std::vector<Vec3> points;
  std::vector<double> radii;
  Vec3 low, high;  // bounding box of the tube
};

Braid make_braid(const BustShape& s, double side) {
  Braid braid;
  const Vec3 from = Vec3(side * 0.7, 0.6, 0.05).normalized(), to = Vec3(side * 0.3, -0.1, -0.95).normalized();
  constexpr int kSegments = 48;
  double arc = 0.0;
  for (int i = 0; i <= kSegments; ++i) {
    const double t = static_cast<double>(i) / kSegments;
    const Vec3 u = ((1.0 - t) * from + t * to + Vec3(0.0, 0.35 * std::sin(M_PI * t), 0.0)).normalized();
    const Vec3 point = on_hair(s, u, 0.35);
    if (i > 0) arc += (point - braid.points.back()).norm();
    braid.points.push_back(point);
    braid.radii.push_back(0.95 * (0.85 + 0.15 * std::cos(2.0 * M_PI * arc / 1.8)));
  }
  braid.low = braid.high = braid.points.front();
  for (const Vec3& p : braid.points) braid.low = braid.low.cwiseMin(p), braid.high = braid.high.cwiseMax(p);
  braid.low.array() -= 1.2;
  braid.high.array() += 1.2;
  return braid;
}

double braid_value(const Braid& braid, const Vec3& p) {
  const Vec3 outside = (braid.low - p).cwiseMax(p - braid.high).cwiseMax(0.0);
  if (outside.squaredNorm() > 0.0) return outside.norm() + 0.1;  // a lower bound, far from the tube
  double best = INFINITY;
  for (std::size_t i = 0; i + 1 < braid.points.size(); ++i) {
    const Vec3 a = braid.points[i], d = braid.points[i + 1] - a;
    const double t = std::clamp((p - a).dot(d) / d.squaredNorm(), 0.0, 1.0);
    const double r = (1.0 - t) * braid.radii[i] + t * braid.radii[i + 1];
    best = std::min(best, (p - (a + t * d)).norm() - r);
  }
  return best;
}

// A ribbon bow on each side of the back of the head: a knot and two thin lobes standing off the
// hair, their undersides facing the head.
double bow_value(const BustShape& s, const Vec3& p, double side) {
  const Vec3 u = Vec3(side * 0.75, 0.45, -0.45).normalized();
  const Vec3 t = u.cross(Vec3::UnitY()).normalized(), b = u.cross(t);
  const Vec3 base = on_hair(s, u, 0.0);
  double value = (p - (base + 0.5 * u)).norm() - 0.9;
  for (double lobe : {1.0, -1.0}) {
    const Vec3 along = (lobe * t + 0.45 * u).normalized();  // each lobe rises off the hair
    const Vec3 across = along.cross(b).normalized();
    value = std::min(value, ellipsoid(p, base + 1.1 * u + 2.7 * along, along, b, across, 2.4, 1.4, 0.45));
  }
  return value;
}

// Hair hanging over the ears: a shell 0.8 to 1.7 cm off the skin on the sides, from within the
// full layer (55° from the cap axis) down past the hairline to 105°, with air between it and the
// skin where the layer thins out.
double ear_flap_value(const BustShape& s, const Vec3& p) {
  const Vec3 u = direction_of(p);
  const double r = p.norm(), lift = above_skin(s, p), theta = s.cap_angle(u);
  const double shell = std::max(0.8 - lift, lift - 1.7);
  const double span = r * std::max(55.0 * kDegree - theta, theta - 105.0 * kDegree);
  const double sides = r * (0.6 - std::abs(u.x()));
  return std::max({shell, span, sides});
}

struct Sculpture {
  BustShape shape = base_shape();
  std::array<Braid, 2> braids{make_braid(shape, 1.0), make_braid(shape, -1.0)};

  double value(const SculptFeatures& f, const Vec3& world) const {
    const Vec3 p = f.tilt.transpose() * world;
    double v = above_layer(shape, p);
    if (f.bun) {
      const Vec3 u = Vec3(0.0, 0.3, -1.0).normalized();
      v = smooth_min(v, (p - on_hair(shape, u, 0.8)).norm() - 3.3, 1.0);
    }
    if (f.braids)
      for (const Braid& braid : braids) v = smooth_min(v, braid_value(braid, p), 0.4);
    if (f.bows)
      for (double side : {1.0, -1.0}) v = smooth_min(v, bow_value(shape, p, side), 0.3);
    if (f.ears) v = std::min(v, ear_flap_value(shape, p));
    return v;
  }
  bool hair(const SculptFeatures& f, const Vec3& world) const {
    return above_skin(shape, Vec3(f.tilt.transpose() * world)) > 0.04;
  }
};

const Sculpture& sculpture() {
  static const Sculpture s;
  return s;
}

}  // namespace

const std::vector<BustStyle>& all_bust_styles() {
  static const std::vector<BustStyle> styles{BustStyle::plain, BustStyle::bun,  BustStyle::braids,
                                             BustStyle::bows,  BustStyle::ears, BustStyle::tilted};
  return styles;
}

std::string bust_style_name(BustStyle style) {
  switch (style) {
    case BustStyle::plain: return "plain";
    case BustStyle::bun: return "bun";
    case BustStyle::braids: return "braids";
    case BustStyle::bows: return "bows";
    case BustStyle::ears: return "ears";
    case BustStyle::tilted: return "tilted";
  }
  return "?";
}

SculptFeatures sculpt_features(BustStyle style) {
  SculptFeatures f;
  f.bun = style == BustStyle::bun;
  f.braids = style == BustStyle::braids;
  f.bows = style == BustStyle::bows;
  f.ears = style == BustStyle::ears;
  if (style == BustStyle::tilted)
    f.tilt = (Eigen::AngleAxisd(20.0 * kDegree, Vec3::UnitX()) * Eigen::AngleAxisd(12.0 * kDegree, Vec3::UnitZ()))
                 .toRotationMatrix();
  return f;
}

double sculpted_bust_value(BustStyle style, const Vec3& p) { return sculpture().value(sculpt_features(style), p); }
bool sculpted_bust_hair(BustStyle style, const Vec3& p) { return sculpture().hair(sculpt_features(style), p); }

BustScan make_sculpted_bust(BustStyle style, double spacing) { return make_sculpted_bust(sculpt_features(style), spacing); }

BustScan make_sculpted_bust(const SculptFeatures& features, double spacing) {
  // Every style fits in this box (the bun reaches z ≈ −16.5, the neck's cut y = −22; the tilted
  // head turns by 23° at most); a head tilted further gets the box of the bust's bounding sphere
  // about the head, 26 cm (the neck's cut).
  const double turned = std::acos(std::clamp(0.5 * (features.tilt.trace() - 1.0), -1.0, 1.0)) / kDegree;
  const Vec3 low = turned <= 23.5 ? Vec3(-15.0, -24.0, -18.5) : Vec3(-26.5, -26.5, -26.5);
  const Vec3 high = turned <= 23.5 ? Vec3(15.0, 17.0, 16.0) : Vec3(26.5, 26.5, 26.5);
  SampleGrid grid;
  grid.origin = low;
  grid.spacing = spacing;
  for (int axis = 0; axis < 3; ++axis) grid.dims[axis] = static_cast<int>(std::ceil((high[axis] - low[axis]) / spacing)) + 1;
  std::vector<double> values(grid.nodes());
  const Sculpture& sculpted = sculpture();
  parallel_for(grid.dims.z(), 0, [&](int k) {
    for (int j = 0; j < grid.dims.y(); ++j)
      for (int i = 0; i < grid.dims.x(); ++i) values[grid.node(i, j, k)] = sculpted.value(features, grid.position(i, j, k));
  });
  ZeroSet surface = marching_tetrahedra(grid, values);
  BustScan scan;
  scan.mesh = std::move(surface.mesh);
  for (const Vec3& p : scan.mesh.positions) {
    const double* c = sculpted.hair(features, p) ? kHairColor : kSkinColor;
    scan.colors.emplace_back(c[0], c[1], c[2]);
    scan.directions.push_back(direction_of(p));
  }
  return scan;
}

}  // namespace hairfit
