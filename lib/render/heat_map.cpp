#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "render/axes.h"
#include "render/canvas.h"
#include "render/plot.h"

namespace hairfit {

std::vector<std::array<Vec2, 2>> contour_segments(const ScalarGrid& grid, double level) {
  std::vector<std::array<Vec2, 2>> segments;
  if (grid.width < 2 || grid.height < 2) return segments;
  const double dx = (grid.x_max - grid.x_min) / (grid.width - 1), dy = (grid.y_max - grid.y_min) / (grid.height - 1);
  for (int j = 0; j + 1 < grid.height; ++j)
    for (int i = 0; i + 1 < grid.width; ++i) {
      // Corners counter-clockwise from (i, j); edge k joins corner k and corner k+1.
      const int ci[4] = {i, i + 1, i + 1, i}, cj[4] = {j, j, j + 1, j + 1};
      double v[4];
      bool finite = true;
      for (int k = 0; k < 4; ++k) finite = finite && std::isfinite(v[k] = grid.at(ci[k], cj[k]));
      if (!finite) continue;
      bool above[4];
      for (int k = 0; k < 4; ++k) above[k] = v[k] > level;
      Vec2 cross[4];
      int crossings = 0;
      for (int k = 0; k < 4; ++k) {
        const int m = (k + 1) % 4;
        if (above[k] == above[m]) continue;
        const double t = (level - v[k]) / (v[m] - v[k]);
        cross[k] = Vec2(grid.x_min + (ci[k] + t * (ci[m] - ci[k])) * dx, grid.y_min + (cj[k] + t * (cj[m] - cj[k])) * dy);
        ++crossings;
      }
      if (crossings == 2) {
        int a = -1, b = -1;
        for (int k = 0; k < 4; ++k)
          if (above[k] != above[(k + 1) % 4]) (a < 0 ? a : b) = k;
        segments.push_back({cross[a], cross[b]});
      } else if (crossings == 4) {
        // Saddle: the cell-centre average decides which diagonal pair is connected.
        const bool centre_above = 0.25 * (v[0] + v[1] + v[2] + v[3]) > level;
        if (centre_above == above[0]) {
          segments.push_back({cross[0], cross[1]});  // cut off corner 1
          segments.push_back({cross[2], cross[3]});  // cut off corner 3
        } else {
          segments.push_back({cross[3], cross[0]});  // cut off corner 0
          segments.push_back({cross[1], cross[2]});  // cut off corner 2
        }
      }
    }
  return segments;
}

namespace {

// Bilinear sample at fractional node coordinates; falls back to the nearest finite corner when
// some corners have no data, NaN when none has.
double sample(const ScalarGrid& grid, double gx, double gy, bool smooth) {
  gx = std::clamp(gx, 0.0, grid.width - 1.0);
  gy = std::clamp(gy, 0.0, grid.height - 1.0);
  if (!smooth) return grid.at(static_cast<int>(std::lround(gx)), static_cast<int>(std::lround(gy)));
  const int i = std::min(grid.width - 2, static_cast<int>(gx)), j = std::min(grid.height - 2, static_cast<int>(gy));
  const double fx = gx - i, fy = gy - j;
  const double v00 = grid.at(i, j), v10 = grid.at(i + 1, j), v01 = grid.at(i, j + 1), v11 = grid.at(i + 1, j + 1);
  if (std::isfinite(v00) && std::isfinite(v10) && std::isfinite(v01) && std::isfinite(v11))
    return (1 - fy) * ((1 - fx) * v00 + fx * v10) + fy * ((1 - fx) * v01 + fx * v11);
  return grid.at(i + (fx > 0.5), j + (fy > 0.5));
}

}  // namespace

Image render_heat_map(const HeatMap& map, int width, int height) {
  const ScalarGrid& g = map.grid;
  if (g.width < 2 || g.height < 2 || g.values.size() != static_cast<std::size_t>(g.width) * g.height)
    throw std::invalid_argument("render_heat_map: grid must have at least 2×2 nodes and width·height values");
  const double x_span = g.x_max - g.x_min, y_span = g.y_max - g.y_min;
  if (!(x_span > 0) || !(y_span > 0)) throw std::invalid_argument("render_heat_map: grid extent is empty");
  const bool diverging = map.scale == ColorScale::diverging;
  double range = map.range;
  if (!(range > 0)) {
    range = 0.0;
    for (double v : g.values)
      if (std::isfinite(v)) range = std::max(range, diverging ? std::abs(v) : v);
    if (!(range > 0)) range = 1.0;
  }
  auto color_of = [&](double v) { return diverging ? diverging_color(v / range) : sequential_color(v / range); };

  Canvas canvas(width, height, paper_color());
  // The map keeps the world aspect ratio inside the space left by labels and the colour bar.
  const double ax0 = std::min(100.0, 0.18 * width), ax1 = width - std::min(130.0, 0.33 * width);
  const double ay0 = 48.0, ay1 = height - std::min(70.0, std::max(52.0, 0.16 * height));
  const double s = std::min((ax1 - ax0) / x_span, (ay1 - ay0) / y_span);
  const double w = s * x_span, h = s * y_span;
  const PlotRect rect{0.5 * (ax0 + ax1 - w), 0.5 * (ay0 + ay1 - h), 0.5 * (ax0 + ax1 + w), 0.5 * (ay0 + ay1 + h)};
  const Axes axes(rect, {g.x_min, g.x_max, false}, {g.y_min, g.y_max, false});

  const Color no_data{0.80f, 0.80f, 0.80f};
  const int px0 = static_cast<int>(std::floor(rect.x0)), px1 = static_cast<int>(std::ceil(rect.x1));
  const int py0 = static_cast<int>(std::floor(rect.y0)), py1 = static_cast<int>(std::ceil(rect.y1));
  for (int py = py0; py < py1; ++py)
    for (int px = px0; px < px1; ++px) {
      // The pixel's covered share of the map rectangle keeps the map's edge anti-aliased.
      const double cover = (std::min(rect.x1, px + 1.0) - std::max(rect.x0, static_cast<double>(px))) *
                           (std::min(rect.y1, py + 1.0) - std::max(rect.y0, static_cast<double>(py)));
      const double x = g.x_min + (px + 0.5 - rect.x0) / s, y = g.y_max - (py + 0.5 - rect.y0) / s;
      const double v = sample(g, (x - g.x_min) / x_span * (g.width - 1), (y - g.y_min) / y_span * (g.height - 1), map.smooth);
      canvas.blend(px, py, std::isfinite(v) ? color_of(v) : no_data, static_cast<float>(std::clamp(cover, 0.0, 1.0)));
    }

  const std::vector<double> levels = diverging ? nice_ticks(-range, range, 8) : nice_ticks(0.0, range, 6);
  auto draw_contour = [&](double level, const Color& color, double line_width, float alpha) {
    for (const auto& seg : contour_segments(g, level))
      canvas.line(axes.to_pixel(seg[0].x(), seg[0].y()), axes.to_pixel(seg[1].x(), seg[1].y()), color, line_width, alpha);
  };
  if (map.iso_lines) {
    const double step = levels.size() > 1 ? levels[1] - levels[0] : range;
    for (double level : levels)
      if (std::abs(level) > 1e-9 * step && std::abs(level) < range) draw_contour(level, ink_color(), 1.0, 0.3f);
  }
  if (diverging && map.zero_contour) draw_contour(0.0, ink_color(), 2.5, 1.0f);
  axes.draw(canvas, map.x_label, map.y_label, true, false);

  // Colour bar beside the map, with the contour levels as ticks.
  const double bx0 = rect.x1 + 24, bx1 = bx0 + 18;
  const double low = diverging ? -range : 0.0;
  for (int py = py0; py < py1; ++py) {
    const double t = std::clamp((rect.y1 - (py + 0.5)) / (rect.y1 - rect.y0), 0.0, 1.0);
    canvas.fill_rect(bx0, std::max(rect.y0, static_cast<double>(py)), bx1, std::min(rect.y1, py + 1.0),
                     color_of(low + t * (range - low)));
  }
  canvas.stroke_rect(bx0, rect.y0, bx1, rect.y1, ink_color(), 1.0);
  const double step = levels.size() > 1 ? levels[1] - levels[0] : range;
  // Every level gets a tick; labels on every stride-th level counted from 0, so they never touch.
  const double per_label = 1.6 * Canvas::text_height(2.0);
  const int stride = std::max(1, static_cast<int>(std::ceil(levels.size() * per_label / (rect.y1 - rect.y0))));
  double widest = 0.0;
  for (double level : levels) {
    const double y = rect.y1 - (level - low) / (range - low) * (rect.y1 - rect.y0);
    canvas.line({bx1, y}, {bx1 + 4, y}, ink_color(), 1.0);
    if (static_cast<long>(std::llround(level / step)) % stride != 0) continue;
    const std::string label = tick_label(level, step);
    canvas.text(bx1 + 7, y - 7, label, ink_color(), 2.0);
    widest = std::max(widest, Canvas::text_width(label));
  }
  if (!map.value_label.empty()) {
    canvas.text(std::min(width - 18.0, bx1 + 14 + widest), 0.5 * (rect.y0 + rect.y1), map.value_label, ink_color(),
                Canvas::fitting_scale(map.value_label, rect.y1 - rect.y0, 2.0), TextAlign::centre, true);
  }
  draw_title(canvas, map.title);
  return canvas.image();
}

}  // namespace hairfit
