#include "render/canvas.h"

#include "render/line_raster.h"

// stb_easy_font is header-only with static functions; we use only print and width.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
#include <stb_easy_font.h>
#pragma GCC diagnostic pop

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace hairfit {

namespace {

// Coverage of a pixel (centre at distance d from a stroke's centre line) by a stroke of half width
// h: a box filter of the pixel against the stroke's profile, exact for axis-aligned strokes.
float stroke_coverage(double d, double h) { return static_cast<float>(std::clamp(h + 0.5 - d, 0.0, 1.0)); }

// A coverage mask over a pixel rectangle: primitives of one logical shape take the maximum (so
// joints of a polyline are not blended twice), then the shape is blended once.
struct Mask {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;  // pixel range [x0, x1) × [y0, y1)
  std::vector<float> coverage;
  Mask(int width, int height, double bx0, double by0, double bx1, double by1) {
    x0 = std::max(0, static_cast<int>(std::floor(bx0)));
    y0 = std::max(0, static_cast<int>(std::floor(by0)));
    x1 = std::min(width, static_cast<int>(std::ceil(bx1)) + 1);
    y1 = std::min(height, static_cast<int>(std::ceil(by1)) + 1);
    if (x1 < x0) x1 = x0;
    if (y1 < y0) y1 = y0;
    coverage.assign(static_cast<std::size_t>(x1 - x0) * (y1 - y0), 0.0f);
  }
  float& at(int x, int y) { return coverage[static_cast<std::size_t>(y - y0) * (x1 - x0) + (x - x0)]; }
};

}  // namespace

Canvas::Canvas(int width, int height, const Color& background) : width_(width), height_(height) {
  if (width <= 0 || height <= 0)
    throw std::invalid_argument("Canvas size must be positive, got " + std::to_string(width) + "x" +
                                std::to_string(height));
  rgb_.resize(static_cast<std::size_t>(width) * height * 3);
  for (std::size_t i = 0; i < rgb_.size(); i += 3) {
    rgb_[i] = background.r;
    rgb_[i + 1] = background.g;
    rgb_[i + 2] = background.b;
  }
}

Color Canvas::at(int x, int y) const {
  const float* p = &rgb_[(static_cast<std::size_t>(y) * width_ + x) * 3];
  return {p[0], p[1], p[2]};
}

void Canvas::blend(int x, int y, const Color& color, float alpha) {
  if (x < 0 || y < 0 || x >= width_ || y >= height_ || !(alpha > 0.0f)) return;
  alpha = std::min(alpha, 1.0f);
  float* p = &rgb_[(static_cast<std::size_t>(y) * width_ + x) * 3];
  p[0] += (color.r - p[0]) * alpha;
  p[1] += (color.g - p[1]) * alpha;
  p[2] += (color.b - p[2]) * alpha;
}

void Canvas::fill_rect(double x0, double y0, double x1, double y1, const Color& color, float alpha) {
  if (x1 < x0) std::swap(x0, x1);
  if (y1 < y0) std::swap(y0, y1);
  const int i0 = std::max(0, static_cast<int>(std::floor(x0))), i1 = std::min(width_, static_cast<int>(std::ceil(x1)));
  const int j0 = std::max(0, static_cast<int>(std::floor(y0))), j1 = std::min(height_, static_cast<int>(std::ceil(y1)));
  for (int j = j0; j < j1; ++j) {
    const double cy = std::min(y1, j + 1.0) - std::max(y0, static_cast<double>(j));
    for (int i = i0; i < i1; ++i) {
      const double cx = std::min(x1, i + 1.0) - std::max(x0, static_cast<double>(i));
      blend(i, j, color, static_cast<float>(alpha * cx * cy));
    }
  }
}

void Canvas::stroke_rect(double x0, double y0, double x1, double y1, const Color& color, double width) {
  polyline({Vec2(x0, y0), Vec2(x1, y0), Vec2(x1, y1), Vec2(x0, y1)}, color, width, true);
}

void Canvas::line(const Vec2& a, const Vec2& b, const Color& color, double width, float alpha) {
  polyline({a, b}, color, width, false, alpha);
}

void Canvas::polyline(const std::vector<Vec2>& points, const Color& color, double width, bool closed, float alpha) {
  if (points.size() < 2) return;
  const double h = 0.5 * width * 1.5 + 1;
  Vec2 lo = points[0], hi = points[0];
  for (const Vec2& p : points) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  // Coverage accumulates (clamped) so segments that share a column add up to exactly one stroke.
  Mask mask(width_, height_, lo.x() - h, lo.y() - h, hi.x() + h, hi.y() + h);
  const std::size_t segments = closed ? points.size() : points.size() - 1;
  for (std::size_t s = 0; s < segments; ++s) {
    const Vec2& a = points[s];
    const Vec2& b = points[(s + 1) % points.size()];
    raster::line_coverage(static_cast<float>(a.x()), static_cast<float>(a.y()), static_cast<float>(b.x()),
                          static_cast<float>(b.y()), static_cast<float>(width), width_, 0, height_,
                          [&](int x, int y, float c, float) {
                            if (x < mask.x0 || x >= mask.x1 || y < mask.y0 || y >= mask.y1) return;
                            float& m = mask.at(x, y);
                            m = std::min(1.0f, m + c);
                          });
  }
  for (int y = mask.y0; y < mask.y1; ++y)
    for (int x = mask.x0; x < mask.x1; ++x) blend(x, y, color, alpha * mask.at(x, y));
}

void Canvas::disc(const Vec2& centre, double radius, const Color& color, float alpha) {
  Mask mask(width_, height_, centre.x() - radius - 1, centre.y() - radius - 1, centre.x() + radius + 1,
            centre.y() + radius + 1);
  for (int y = mask.y0; y < mask.y1; ++y)
    for (int x = mask.x0; x < mask.x1; ++x)
      blend(x, y, color, alpha * stroke_coverage((Vec2(x + 0.5, y + 0.5) - centre).norm(), radius));
}

void Canvas::circle(const Vec2& centre, double radius, const Color& color, double width, float alpha) {
  const double h = 0.5 * std::max(width, 1.0);
  if (width < 1.0) alpha *= static_cast<float>(std::max(width, 0.0));
  const double reach = radius + h + 1;
  Mask mask(width_, height_, centre.x() - reach, centre.y() - reach, centre.x() + reach, centre.y() + reach);
  for (int y = mask.y0; y < mask.y1; ++y)
    for (int x = mask.x0; x < mask.x1; ++x)
      blend(x, y, color, alpha * stroke_coverage(std::abs((Vec2(x + 0.5, y + 0.5) - centre).norm() - radius), h));
}

void Canvas::triangle(const Vec2& a, const Vec2& b, const Vec2& c, const Color& color, float alpha) {
  const Vec2 lo = a.cwiseMin(b).cwiseMin(c), hi = a.cwiseMax(b).cwiseMax(c);
  const double area = (b - a).x() * (c - a).y() - (b - a).y() * (c - a).x();
  if (area == 0.0) return;
  const double sign = area > 0 ? 1.0 : -1.0;
  auto edge = [sign](const Vec2& p, const Vec2& q, double x, double y) {
    return sign * ((q.x() - p.x()) * (y - p.y()) - (q.y() - p.y()) * (x - p.x()));
  };
  Mask mask(width_, height_, lo.x(), lo.y(), hi.x(), hi.y());
  for (int y = mask.y0; y < mask.y1; ++y)
    for (int x = mask.x0; x < mask.x1; ++x) {
      int inside = 0;
      for (int sy = 0; sy < 4; ++sy)
        for (int sx = 0; sx < 4; ++sx) {
          const double px = x + (sx + 0.5) / 4, py = y + (sy + 0.5) / 4;
          inside += edge(a, b, px, py) >= 0 && edge(b, c, px, py) >= 0 && edge(c, a, px, py) >= 0;
        }
      blend(x, y, color, alpha * inside / 16.0f);
    }
}

double Canvas::text_width(const std::string& text, double scale) {
  std::string copy = text;
  return scale * stb_easy_font_width(copy.data());
}

double Canvas::fitting_scale(const std::string& text, double room, double largest) {
  return std::clamp(largest * room / text_width(text, largest), 1.0, largest);
}

void Canvas::text(double x, double y, const std::string& text, const Color& color, double scale, TextAlign align,
                  bool vertical) {
  if (text.empty()) return;
  std::string copy = text;
  std::vector<char> buffer(copy.size() * 400 + 1024);
  const int quads = stb_easy_font_print(0.0f, 0.0f, copy.data(), nullptr, buffer.data(), static_cast<int>(buffer.size()));
  const double length = text_width(text, scale);
  const double shift = align == TextAlign::left ? 0.0 : align == TextAlign::centre ? -0.5 * length : -length;
  // Each quad is an axis-aligned rectangle in font units (u right, v down); stb_easy_font's glyphs
  // sit one unit below their anchor, so v is moved up by one.
  struct Rect {
    double x0, y0, x1, y1;
  };
  std::vector<Rect> rects;
  rects.reserve(quads);
  for (int q = 0; q < quads; ++q) {
    const float* v = reinterpret_cast<const float*>(buffer.data() + q * 64);
    double u0 = v[0], u1 = v[0], w0 = v[1], w1 = v[1];
    for (int k = 1; k < 4; ++k) {
      u0 = std::min<double>(u0, v[k * 4]);
      u1 = std::max<double>(u1, v[k * 4]);
      w0 = std::min<double>(w0, v[k * 4 + 1]);
      w1 = std::max<double>(w1, v[k * 4 + 1]);
    }
    u0 = u0 * scale + shift, u1 = u1 * scale + shift, w0 = (w0 - 1) * scale, w1 = (w1 - 1) * scale;
    rects.push_back(vertical ? Rect{x + w0, y - u1, x + w1, y - u0} : Rect{x + u0, y + w0, x + u1, y + w1});
  }
  if (rects.empty()) return;
  Rect box = rects[0];
  for (const Rect& r : rects) box = {std::min(box.x0, r.x0), std::min(box.y0, r.y0), std::max(box.x1, r.x1), std::max(box.y1, r.y1)};
  // Glyph strokes overlap at their corners: accumulate exact area coverage, clamp, blend once.
  Mask mask(width_, height_, box.x0, box.y0, box.x1, box.y1);
  for (const Rect& r : rects) {
    const int i0 = std::max(mask.x0, static_cast<int>(std::floor(r.x0))), i1 = std::min(mask.x1, static_cast<int>(std::ceil(r.x1)));
    const int j0 = std::max(mask.y0, static_cast<int>(std::floor(r.y0))), j1 = std::min(mask.y1, static_cast<int>(std::ceil(r.y1)));
    for (int j = j0; j < j1; ++j)
      for (int i = i0; i < i1; ++i) {
        const double cx = std::min(r.x1, i + 1.0) - std::max(r.x0, static_cast<double>(i));
        const double cy = std::min(r.y1, j + 1.0) - std::max(r.y0, static_cast<double>(j));
        mask.at(i, j) = std::min(1.0f, mask.at(i, j) + static_cast<float>(cx * cy));
      }
  }
  for (int j = mask.y0; j < mask.y1; ++j)
    for (int i = mask.x0; i < mask.x1; ++i) blend(i, j, color, mask.at(i, j));
}

void Canvas::draw_image(const Image& image, int x, int y) {
  for (int j = 0; j < image.height; ++j)
    for (int i = 0; i < image.width; ++i) {
      const std::uint8_t* p = image.pixel(i, j);
      blend(x + i, y + j, {p[0] / 255.0f, p[1] / 255.0f, p[2] / 255.0f}, p[3] / 255.0f);
    }
}

Image Canvas::image() const {
  Image out;
  out.width = width_;
  out.height = height_;
  out.rgba.resize(static_cast<std::size_t>(width_) * height_ * 4);
  const std::size_t pixels = static_cast<std::size_t>(width_) * height_;
  for (std::size_t i = 0; i < pixels; ++i) {
    for (int c = 0; c < 3; ++c) out.rgba[i * 4 + c] = to_byte(rgb_[i * 3 + c]);
    out.rgba[i * 4 + 3] = 255;
  }
  return out;
}

std::vector<double> nice_ticks(double low, double high, int target) {
  if (!(high > low) || !std::isfinite(low) || !std::isfinite(high)) return {low};
  const double raw = (high - low) / std::max(1, target);
  const double power = std::pow(10.0, std::floor(std::log10(raw)));
  const double fraction = raw / power;
  const double step = (fraction < 1.5 ? 1.0 : fraction < 3.5 ? 2.0 : fraction < 7.5 ? 5.0 : 10.0) * power;
  std::vector<double> ticks;
  for (double k = std::ceil(low / step - 1e-9); k * step <= high + 1e-9 * step; k += 1.0) ticks.push_back(k * step);
  return ticks;
}

std::string tick_label(double value, double step) {
  if (std::abs(value) < 1e-9 * (step > 0 ? step : 1.0)) return "0";  // never "-0"
  char text[32];
  std::snprintf(text, sizeof text, "%.4g", value);
  return text;
}

}  // namespace hairfit
