#include "render/camera.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>

#include "core/error.h"

namespace hairfit {

const std::vector<std::string>& view_names() {
  static const std::vector<std::string> names{"front", "side", "back", "top", "three-quarter"};
  return names;
}

std::string view_name(ViewName view) { return view_names()[static_cast<int>(view)]; }

ViewName parse_view(const std::string& name) {
  const auto& names = view_names();
  for (std::size_t i = 0; i < names.size(); ++i)
    if (names[i] == name) return static_cast<ViewName>(i);
  std::string list;
  for (const std::string& n : names) list += (list.empty() ? "" : ", ") + n;
  throw InputError("--view", "unknown view \"" + name + "\"; valid views: " + list);
}

std::pair<int, int> parse_size(const std::string& text) {
  const std::size_t x = text.find_first_of("xX");
  auto number = [](const std::string& s, int& out) {
    if (s.empty() || s.size() > 6 || s.find_first_not_of("0123456789") != std::string::npos) return false;
    out = std::atoi(s.c_str());
    return out >= 16 && out <= 16384;
  };
  int w = 0, h = 0;
  if (x == std::string::npos || !number(text.substr(0, x), w) || !number(text.substr(x + 1), h))
    throw InputError("--size", "invalid size \"" + text + "\"; write WIDTHxHEIGHT in pixels, each 16–16384, e.g. 1200x900");
  return {w, h};
}

Vec3 Camera::project(const Vec3& world) const {
  const Vec3 d = world - centre;
  return {0.5 * width + pixels_per_unit * d.dot(right), 0.5 * height - pixels_per_unit * d.dot(up), d.dot(forward)};
}

Camera orient_camera(ViewName view, const Vec3& down, const Vec3& front) {
  const double dn = down.norm();
  if (!(dn > 0) || !std::isfinite(dn)) throw InputError("scene", "[scene] down must be a non-zero direction");
  const Vec3 u = -down / dn;  // world up
  Vec3 f = front - front.dot(u) * u;
  if (!(f.norm() > 1e-6 * front.norm()) || !std::isfinite(f.norm()))
    throw InputError("scene", "[scene] front must be a direction not parallel to down");
  f.normalize();
  const Vec3 left = u.cross(f);  // the person's left (facing f with head toward u)
  Vec3 to_camera = f, image_up = u;
  switch (view) {
    case ViewName::front: to_camera = f; break;
    case ViewName::side: to_camera = -left; break;
    case ViewName::back: to_camera = -f; break;
    case ViewName::top: to_camera = u, image_up = f; break;
    case ViewName::three_quarter: {
      const double elevation = 20.0 * M_PI / 180.0;
      to_camera = std::cos(elevation) * (f - left).normalized() + std::sin(elevation) * u;
      image_up = (u - u.dot(to_camera) * to_camera).normalized();
      break;
    }
  }
  Camera camera;
  camera.forward = -to_camera;
  camera.up = image_up;
  camera.right = camera.forward.cross(camera.up);
  return camera;
}

Camera fit_camera(ViewName view, const Vec3& down, const Vec3& front, const Vec3& lo, const Vec3& hi, int width,
                  int height, double margin) {
  Camera camera = orient_camera(view, down, front);
  camera.width = width;
  camera.height = height;
  double x0 = INFINITY, x1 = -INFINITY, y0 = INFINITY, y1 = -INFINITY, z0 = INFINITY, z1 = -INFINITY;
  for (int corner = 0; corner < 8; ++corner) {
    const Vec3 p(corner & 1 ? hi.x() : lo.x(), corner & 2 ? hi.y() : lo.y(), corner & 4 ? hi.z() : lo.z());
    x0 = std::min(x0, p.dot(camera.right)), x1 = std::max(x1, p.dot(camera.right));
    y0 = std::min(y0, p.dot(camera.up)), y1 = std::max(y1, p.dot(camera.up));
    z0 = std::min(z0, p.dot(camera.forward)), z1 = std::max(z1, p.dot(camera.forward));
  }
  camera.centre = 0.5 * (x0 + x1) * camera.right + 0.5 * (y0 + y1) * camera.up + 0.5 * (z0 + z1) * camera.forward;
  const double pad = 2.0 * margin * std::min(width, height);
  const double extent_x = std::max(x1 - x0, 1e-12), extent_y = std::max(y1 - y0, 1e-12);
  camera.pixels_per_unit = std::max(1e-12, std::min((width - pad) / extent_x, (height - pad) / extent_y));
  if (!std::isfinite(x0) || !std::isfinite(x1)) camera.centre.setZero(), camera.pixels_per_unit = 1.0;
  return camera;
}

}  // namespace hairfit
