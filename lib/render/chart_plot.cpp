#include "render/chart_plot.h"

#include <algorithm>
#include <stdexcept>

#include "render/axes.h"
#include "render/canvas.h"

namespace hairfit {

Image render_chart(const ChartDrawing& chart, int width, int height) {
  const int n = static_cast<int>(chart.vertices.size());
  for (const Vec3i& t : chart.triangles)
    if (t.minCoeff() < 0 || t.maxCoeff() >= n) throw std::invalid_argument("render_chart: triangle index out of range");
  if (!chart.point_ids.empty() && chart.point_ids.size() != chart.points.size())
    throw std::invalid_argument("render_chart: point_ids must match points");
  Canvas canvas(width, height, paper_color());
  const double top = chart.title.empty() ? 36.0 : 60.0;
  const double radius = 0.5 * std::min(width - 40.0, height - top - 24.0);
  const Vec2 centre(0.5 * width, top + 0.5 * (height - top - 24.0) + 12.0);
  auto to_pixel = [&](const Vec2& uv) { return Vec2(centre.x() + radius * uv.x(), centre.y() - radius * uv.y()); };
  const double point_scale = radius / 380.0;  // sizes follow the picture

  canvas.disc(centre, radius, {0.96f, 0.96f, 0.97f});
  // Each edge once: the triangle lines would otherwise be drawn twice and look heavier inside.
  std::vector<std::pair<int, int>> edges;
  edges.reserve(chart.triangles.size() * 3);
  for (const Vec3i& t : chart.triangles)
    for (int k = 0; k < 3; ++k) edges.emplace_back(std::min(t[k], t[(k + 1) % 3]), std::max(t[k], t[(k + 1) % 3]));
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  const double edge_width = std::clamp(0.8 * point_scale, 0.4, 1.0);
  for (const auto& [a, b] : edges)
    canvas.line(to_pixel(chart.vertices[a]), to_pixel(chart.vertices[b]), {0.55f, 0.58f, 0.64f}, edge_width, 0.8f);
  canvas.circle(centre, radius, ink_color(), 1.5);

  for (const ChartCircle& c : chart.circles) {
    const Color color = palette_color(c.id);
    canvas.disc(to_pixel(c.centre), radius * c.radius, color, 0.10f);
    canvas.circle(to_pixel(c.centre), radius * c.radius, scale(color, 0.8f), 1.5);
  }
  const double dot = std::clamp(2.0 * point_scale, 1.0, 3.0);
  for (std::size_t i = 0; i < chart.points.size(); ++i) {
    const Color color = chart.point_ids.empty() ? Color{0.25f, 0.25f, 0.28f} : scale(palette_color(chart.point_ids[i]), 0.85f);
    canvas.disc(to_pixel(chart.points[i]), dot, color);
  }
  const double base = std::clamp(5.0 * point_scale, 3.0, 7.0);
  for (const Vec2& h : chart.highlights) {
    canvas.disc(to_pixel(h), base + 1.5, ink_color());
    canvas.disc(to_pixel(h), base, {1.0f, 0.85f, 0.2f});
  }
  if (!chart.up_label.empty())
    canvas.text(centre.x(), centre.y() - radius - 20, chart.up_label, ink_color(), 2.0, TextAlign::centre);
  draw_title(canvas, chart.title);
  return canvas.image();
}

}  // namespace hairfit
