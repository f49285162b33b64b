#include "reference/carved_hull.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>

#include "core/random.h"
#include "core/shapes.h"
#include "core/smoothstep.h"

namespace hairfit {

namespace {

constexpr double kDegree = M_PI / 180.0;
const Vec3 kHead(7.6, 9.0, 9.6);  // the fixtures' head (fixtures/make_fixtures.cpp)
constexpr double kHairline = 78.0 * kDegree;
constexpr double kCrownThickness = 2.5, kRimThickness = 0.1, kGrooveDepth = 0.35;
constexpr double kNoise = 0.04;  // cm, the scan's noise normal to the skin
constexpr double kHeadRadius = 9.0;  // cm per radian of direction, for widths on the head

// The ramp from 0 at a to 1 at b (either order).
double ramp(double a, double b, double x) { return smoothstep((x - a) / (b - a)); }

double skin_radius(const Vec3& u) {
  return 1.0 / std::sqrt(std::pow(u.x() / kHead.x(), 2) + std::pow(u.y() / kHead.y(), 2) + std::pow(u.z() / kHead.z(), 2));
}

// The cap's frame: its axis tilted 25° back; φ_c = 0 toward the person's left (+x), π/2 toward
// the back and down.
struct CapFrame {
  Vec3 axis = Vec3(0.0, std::cos(25.0 * kDegree), -std::sin(25.0 * kDegree));
  Vec3 e1 = Vec3::UnitX();
  Vec3 e2 = axis.cross(e1);
  double theta(const Vec3& u) const { return std::acos(std::clamp(u.dot(axis), -1.0, 1.0)); }
  double phi(const Vec3& u) const { return std::atan2(u.dot(e2), u.dot(e1)); }
  Vec3 direction(double theta, double phi) const {
    return std::cos(theta) * axis + std::sin(theta) * (std::cos(phi) * e1 + std::sin(phi) * e2);
  }
};

const CapFrame& cap() {
  static const CapFrame frame;
  return frame;
}

double angle_between(const Vec3& a, const Vec3& b) { return std::atan2(a.cross(b).norm(), a.dot(b)); }

// The signed difference of two angles, in (−π, π].
double wrapped(double a) { return std::remainder(a, 2.0 * M_PI); }

// A braid's path over the head: directions along a spherical quadratic Bézier, from a temple
// round to the back.
struct BraidPath {
  std::vector<Vec3> points;  // unit directions
  std::vector<double> arc;   // cm along the head, from the start
};

BraidPath braid_path(double side) {
  const Vec3 a = Vec3(side * 0.80, 0.30, 0.30).normalized(), b = Vec3(side * 0.95, 0.25, -0.45).normalized(),
             c = Vec3(side * 0.30, 0.10, -0.95).normalized();
  BraidPath path;
  constexpr int kSegments = 64;
  for (int i = 0; i <= kSegments; ++i) {
    const double t = static_cast<double>(i) / kSegments;
    const Vec3 u = ((1 - t) * (1 - t) * a + 2 * t * (1 - t) * b + t * t * c).normalized();
    path.arc.push_back(path.points.empty() ? 0.0 : path.arc.back() + kHeadRadius * angle_between(path.points.back(), u));
    path.points.push_back(u);
  }
  return path;
}

// Where u lies against a braid: along its path and across it (cm), and its angular distance.
struct BraidPlace {
  double along = 0.0, across = 0.0, distance = INFINITY;
};

BraidPlace braid_place(const BraidPath& path, const Vec3& u) {
  BraidPlace best;
  for (std::size_t i = 0; i + 1 < path.points.size(); ++i) {
    const Vec3 a = path.points[i], d = path.points[i + 1] - a;
    const double t = std::clamp((u - a).dot(d) / d.squaredNorm(), 0.0, 1.0);
    const Vec3 q = (a + t * d).normalized();
    const double distance = angle_between(q, u);
    if (distance < best.distance) {
      const double side = d.cross(q).dot(u) >= 0.0 ? 1.0 : -1.0;
      best = {path.arc[i] + t * (path.arc[i + 1] - path.arc[i]), side * kHeadRadius * distance, distance};
    }
  }
  return best;
}

constexpr double kBraidHalfWidth = 0.14;  // radians of direction (≈ 1.3 cm)

// One family of grooves: its phase (grooves one unit apart) and how much of the hull it carves.
struct Family {
  double phase = 0.0, share = 0.0;
  bool root_to_tip = false;
};

struct Carving {
  CarvedStyle style;
  Eigen::Matrix3d turn = Eigen::Matrix3d::Identity();  // head frame → world
  std::array<Vec3, 3> curls;
  Vec3 bun, bows[2];
  BraidPath braids[2] = {braid_path(1.0), braid_path(-1.0)};

  explicit Carving(CarvedStyle s) : style(s) {
    curls = {cap().direction(0.95, 0.15), cap().direction(0.95, M_PI - 0.15), cap().direction(1.0, 0.5 * M_PI + 0.1)};
    bun = cap().direction(0.55, 0.5 * M_PI);
    bows[0] = Vec3(0.55, 0.45, -0.70).normalized();
    bows[1] = Vec3(-0.55, 0.45, -0.70).normalized();
    if (style == CarvedStyle::tilted)
      turn = Eigen::AngleAxisd(30.0 * kDegree, Vec3(1.0, 0.0, 0.4).normalized()).toRotationMatrix();
  }

  bool has_curls() const { return style == CarvedStyle::curls || style == CarvedStyle::scan; }
  bool has_fringe() const { return style == CarvedStyle::fringe || style == CarvedStyle::tilted; }
  bool has_bun() const { return style == CarvedStyle::bun; }
  bool has_braids() const { return style == CarvedStyle::braids; }
  bool coarse() const { return style != CarvedStyle::locks && style != CarvedStyle::curls; }

  // How much of the front the fringe covers (1 in the middle of the forehead).
  double fringe_share(const Vec3& u) const {
    if (!has_fringe()) return 0.0;
    const double off = std::fabs(wrapped(cap().phi(u) + 0.5 * M_PI));
    return ramp(0.75, 0.6, off) * ramp(kHairline - 0.3, kHairline - 0.15, cap().theta(u));
  }

  // Whether the hull covers u: the cap, a little past the hairline, and the forehead under a fringe.
  bool covered(const Vec3& u) const {
    const double theta = cap().theta(u);
    if (theta <= kHairline + 0.02) return true;
    return has_fringe() && std::fabs(wrapped(cap().phi(u) + 0.5 * M_PI)) < 0.75 && theta < kHairline + 0.35;
  }

  double thickness(const Vec3& u) const {
    const double theta = cap().theta(u), s = theta / kHairline;
    double t = kRimThickness + kCrownThickness * std::max(0.0, 1.0 - s * s);
    if (has_fringe()) {
      const double lying = 0.5 * ramp(0.75, 0.6, std::fabs(wrapped(cap().phi(u) + 0.5 * M_PI))) *
                           ramp(kHairline + 0.35, kHairline + 0.25, theta);
      t = std::max(t, lying);
    }
    return t;
  }

  // The raised parts: the bun, the braids' tubes, the bows (cm above the layer).
  double raised(const Vec3& u) const {
    double h = 0.0;
    if (has_bun()) {
      const double a = angle_between(u, bun) / 0.42;
      if (a < 1.0) h = std::max(h, 4.5 * std::sqrt(1.0 - a * a));
    }
    if (has_braids()) {
      for (const BraidPath& path : braids) {
        const double b = braid_place(path, u).distance / kBraidHalfWidth;
        if (b < 1.0) h = std::max(h, 1.0 * std::sqrt(1.0 - b * b));
      }
      for (const Vec3& bow : bows) {
        const double a = angle_between(u, bow) / 0.22;
        if (a < 1.0) h = std::max(h, 1.6 * (1.0 - a * a));
      }
    }
    return h;
  }

  // The style's families at u, always in the same order, each with its share of carving it; the
  // shares add up to at most 1 (the first families take theirs first).
  std::vector<Family> families(const Vec3& u) const {
    std::vector<Family> out;
    double taken = 0.0;
    auto add = [&](double phase, double share, bool root_to_tip) {
      share = std::clamp(share, 0.0, 1.0 - taken);
      out.push_back({phase, share, root_to_tip});
      taken += share;
    };
    if (has_bun()) {
      const double a = angle_between(u, bun);
      const Vec3 x = bun.unitOrthogonal(), y = bun.cross(x);
      const double around = std::atan2(u.dot(y), u.dot(x));
      add(kHeadRadius * a / 0.9 + around / (2.0 * M_PI), ramp(0.48, 0.40, a), false);  // wound round it
    }
    if (has_braids()) {
      for (const Vec3& bow : bows) taken += std::min(1.0 - taken, ramp(0.26, 0.20, angle_between(u, bow)));
      for (const BraidPath& path : braids) {
        const BraidPlace place = braid_place(path, u);
        add((place.across + 0.7 * place.along) / 0.9, ramp(kBraidHalfWidth + 0.03, kBraidHalfWidth, place.distance), false);
      }
    }
    if (has_curls())
      for (const Vec3& c : curls) {
        const double d = kHeadRadius * angle_between(u, c);
        add(d / 1.1, ramp(2.9, 2.3, d), false);
      }
    const double theta = cap().theta(u), phi = cap().phi(u);
    add(60.0 * phi / (2.0 * M_PI), fringe_share(u), true);  // combed straight down the forehead
    const double kappa = 0.3 + 0.5 * std::sin(phi);
    add(20.0 * (phi + kappa * theta) / (2.0 * M_PI), ramp(0.12, 0.4, theta), true);
    return out;
  }

  // The relief carved at u (cm below the smooth layer): U-shaped grooves.
  double relief(const Vec3& u) const {
    const double depth = kGrooveDepth * std::min(1.0, (thickness(u) - kRimThickness) / 0.8 + (raised(u) > 0.0 ? 1.0 : 0.0));
    double r = 0.0;
    for (const Family& f : families(u)) r += f.share * std::pow(0.5 + 0.5 * std::cos(2.0 * M_PI * f.phase), 1.5);
    return depth * r;
  }

  double radius(const Vec3& u) const { return skin_radius(u) + thickness(u) + raised(u) - relief(u); }
};

// The phase's gradient over the directions at u (tangent), by central differences; phases jump
// by whole periods across their branch cuts, so each difference is taken modulo 1.
Vec3 phase_gradient(const Carving& carving, std::size_t family, const Vec3& u) {
  constexpr double h = 1e-6;
  const Vec3 x = u.unitOrthogonal(), y = u.cross(x);
  Vec3 gradient = Vec3::Zero();
  for (const Vec3& axis : {x, y}) {
    const std::vector<Family> plus = carving.families((u + h * axis).normalized());
    const std::vector<Family> minus = carving.families((u - h * axis).normalized());
    const double d = plus[family].phase - minus[family].phase;
    gradient += (d - std::round(d)) / (2.0 * h) * axis;
  }
  return gradient;
}

}  // namespace

const std::vector<CarvedStyle>& all_carved_styles() {
  static const std::vector<CarvedStyle> styles{CarvedStyle::locks,  CarvedStyle::curls, CarvedStyle::bun,
                                               CarvedStyle::braids, CarvedStyle::fringe, CarvedStyle::scan,
                                               CarvedStyle::tilted};
  return styles;
}

std::string carved_style_name(CarvedStyle style) {
  switch (style) {
    case CarvedStyle::locks: return "locks";
    case CarvedStyle::curls: return "curls";
    case CarvedStyle::bun: return "bun";
    case CarvedStyle::braids: return "braids";
    case CarvedStyle::fringe: return "fringe";
    case CarvedStyle::scan: return "scan";
    case CarvedStyle::tilted: return "tilted";
  }
  return "?";
}

CarvedHull make_carved_hull(CarvedStyle style) {
  const Carving carving(style);
  CarvedHull out;
  // The scalp: the skin over the cap (a pole and rings about the cap axis).
  out.scalp = spherical_cap(kHairline, 28, 96);
  const Eigen::Matrix3d to_cap = Eigen::Quaterniond::FromTwoVectors(Vec3::UnitZ(), cap().axis).toRotationMatrix();
  for (Vec3& p : out.scalp.positions) {
    const Vec3 u = (to_cap * p).normalized();
    p = skin_radius(u) * u;
  }
  // The hull: the covered triangles of a sphere, each vertex at the carved radius plus the noise.
  const Mesh sphere = icosphere(carving.coarse() ? 5 : 6);
  std::vector<int> index(sphere.positions.size(), -1);
  for (const Vec3i& t : sphere.triangles) {
    if (!carving.covered((sphere.positions[t[0]] + sphere.positions[t[1]] + sphere.positions[t[2]]).normalized()))
      continue;
    Vec3i kept;
    for (int k = 0; k < 3; ++k) {
      if (index[t[k]] < 0) {
        index[t[k]] = static_cast<int>(out.hull.positions.size());
        const Vec3 u = sphere.positions[t[k]].normalized();
        double r = carving.radius(u);
        if (carving.coarse()) r += kNoise * Random(48, RandomStage::test, static_cast<std::uint64_t>(t[k])).normal();
        out.hull.positions.push_back(r * u);
      }
      kept[k] = index[t[k]];
    }
    out.hull.triangles.push_back(kept);
  }
  for (Mesh* mesh : {&out.scalp, &out.hull})
    for (Vec3& p : mesh->positions) p = carving.turn * p;
  return out;
}

CarvedDirection carved_direction(CarvedStyle style, const Vec3& p) {
  static const std::array<Carving, 7> carvings{Carving(CarvedStyle::locks),  Carving(CarvedStyle::curls),
                                               Carving(CarvedStyle::bun),    Carving(CarvedStyle::braids),
                                               Carving(CarvedStyle::fringe), Carving(CarvedStyle::scan),
                                               Carving(CarvedStyle::tilted)};
  const Carving& carving = carvings[static_cast<std::size_t>(style)];
  CarvedDirection out;
  if (!(p.norm() > 0.0)) return out;
  const Vec3 u = (carving.turn.transpose() * p).normalized();
  if (!carving.covered(u)) return out;
  const std::vector<Family> families = carving.families(u);
  std::size_t main = 0;
  for (std::size_t f = 1; f < families.size(); ++f)
    if (families[f].share > families[main].share) main = f;
  if (families.empty() || families[main].share < 0.9) return out;
  const Vec3 gradient = phase_gradient(carving, main, u);
  if (!(gradient.norm() > 1e-9)) return out;
  Vec3 d = u.cross(gradient).normalized();
  out.root_to_tip = families[main].root_to_tip;
  if (out.root_to_tip) {  // away from the crown
    const Vec3 toward_crown = cap().axis - cap().axis.dot(u) * u;
    if (d.dot(toward_crown) > 0.0) d = -d;
  }
  out.direction = carving.turn * d;
  out.weight = 1.0;
  return out;
}

CarvedFlowScore score_carved_flow(CarvedStyle style, const Curves& curves) {
  std::vector<double> angles;
  CarvedFlowScore s;
  std::size_t reversed = 0;
  for (std::size_t c = 0; c < curves.count(); ++c) {
    const std::size_t n = curves.size(c);
    for (std::size_t k = n / 5; k + 1 < n; ++k) {
      const Vec3& node = curves.point(c, k);
      const CarvedDirection truth = carved_direction(style, node);
      if (!(truth.weight > 0.5)) continue;
      const Vec3 radial = truth.direction.cross(node).cross(truth.direction).normalized();  // off the head
      Vec3 t = curves.point(c, k + 1) - node;
      t -= t.dot(radial) * radial;
      if (!(t.norm() > 1e-9)) continue;
      const double cosine = t.normalized().dot(truth.direction);
      angles.push_back(std::acos(std::min(1.0, std::fabs(cosine))) * 180.0 / M_PI);
      if (truth.root_to_tip) {
        ++s.signed_nodes;
        if (cosine < 0.0) ++reversed;
      }
    }
  }
  s.nodes = angles.size();
  if (!angles.empty()) {
    std::nth_element(angles.begin(), angles.begin() + angles.size() / 2, angles.end());
    s.median_degrees = angles[angles.size() / 2];
  }
  if (s.signed_nodes > 0) s.against = static_cast<double>(reversed) / s.signed_nodes;
  return s;
}

}  // namespace hairfit
