#include "render/plot.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "render/axes.h"
#include "render/canvas.h"

namespace hairfit {

namespace {

// Plot area inside a canvas, leaving room for the title, tick labels and axis labels.
PlotRect plot_rect(int width, int height, double right_margin) {
  return {std::min(100.0, 0.2 * width), 48.0, width - right_margin, height - std::min(70.0, 0.18 * height)};
}

}  // namespace

Image render_bar_plot(const BarPlot& plot, int width, int height) {
  if (!(plot.x_step > 0)) throw std::invalid_argument("render_bar_plot: x_step must be positive");
  Canvas canvas(width, height, paper_color());
  double top = 0.0;
  for (double v : plot.values)
    if (std::isfinite(v)) top = std::max(top, v);
  const int n = static_cast<int>(plot.values.size());
  const double x_lo = plot.x_start - 0.5 * plot.x_step, x_hi = plot.x_start + (std::max(n, 1) - 0.5) * plot.x_step;
  AxisRange y = fit_range(0.0, top > 0 ? top : 1.0, false, 0.0);
  y.low = 0.0;
  y.high = top > 0 ? top * 1.06 : 1.0;
  const Axes axes(plot_rect(width, height, 24.0), {x_lo, x_hi, false}, y);
  // Grid first, bars over it, then the frame and ticks again on top.
  axes.draw(canvas, plot.x_label, plot.y_label);
  for (int i = 0; i < n; ++i) {
    if (!std::isfinite(plot.values[i]) || plot.values[i] <= 0) continue;
    const double c = plot.x_start + i * plot.x_step;
    const double x0 = axes.to_x(c - 0.4 * plot.x_step), x1 = axes.to_x(c + 0.4 * plot.x_step);
    canvas.fill_rect(x0, axes.to_y(plot.values[i]), x1, axes.to_y(0.0), plot.color);
  }
  axes.draw(canvas, "", "", true, false);
  draw_title(canvas, plot.title);
  return canvas.image();
}

Image render_line_plot(const LinePlot& plot, int width, int height) {
  double x_lo = INFINITY, x_hi = -INFINITY, y_lo = INFINITY, y_hi = -INFINITY;
  auto usable = [&](double x, double y) {
    return std::isfinite(x) && std::isfinite(y) && (!plot.log_x || x > 0) && (!plot.log_y || y > 0);
  };
  for (const Series& s : plot.series) {
    if (s.x.size() != s.y.size())
      throw std::invalid_argument("render_line_plot: series \"" + s.name + "\" has " + std::to_string(s.x.size()) +
                                  " x values and " + std::to_string(s.y.size()) + " y values");
    for (std::size_t i = 0; i < s.x.size(); ++i)
      if (usable(s.x[i], s.y[i])) {
        x_lo = std::min(x_lo, s.x[i]), x_hi = std::max(x_hi, s.x[i]);
        y_lo = std::min(y_lo, s.y[i]), y_hi = std::max(y_hi, s.y[i]);
      }
  }
  if (!(x_lo <= x_hi)) x_lo = plot.log_x ? 1 : 0, x_hi = plot.log_x ? 10 : 1, y_lo = x_lo, y_hi = x_hi;
  Canvas canvas(width, height, paper_color());
  const Axes axes(plot_rect(width, height, 24.0), fit_range(x_lo, x_hi, plot.log_x), fit_range(y_lo, y_hi, plot.log_y));
  axes.draw(canvas, plot.x_label, plot.y_label);
  const PlotRect& r = axes.rect();
  auto inside = [&](const Vec2& p) { return p.x() >= r.x0 - 1 && p.x() <= r.x1 + 1 && p.y() >= r.y0 - 1 && p.y() <= r.y1 + 1; };
  for (std::size_t k = 0; k < plot.series.size(); ++k) {
    const Series& s = plot.series[k];
    const Color color = palette_color(s.color_id >= 0 ? s.color_id : static_cast<int>(k));
    std::vector<Vec2> run;  // a polyline between skipped points
    auto flush = [&] {
      if (s.lines && run.size() > 1) canvas.polyline(run, color, 2.0);
      run.clear();
    };
    for (std::size_t i = 0; i < s.x.size(); ++i) {
      if (!usable(s.x[i], s.y[i])) {
        flush();
        continue;
      }
      run.push_back(axes.to_pixel(s.x[i], s.y[i]));
    }
    flush();
    if (s.markers)
      for (std::size_t i = 0; i < s.x.size(); ++i)
        if (usable(s.x[i], s.y[i]) && inside(axes.to_pixel(s.x[i], s.y[i]))) {
          canvas.disc(axes.to_pixel(s.x[i], s.y[i]), 4.0, paper_color());
          canvas.disc(axes.to_pixel(s.x[i], s.y[i]), 3.0, color);
        }
  }
  // Legend in the top-right corner of the plot area, on a white box.
  std::vector<std::size_t> named;
  double legend_width = 0.0;
  for (std::size_t k = 0; k < plot.series.size(); ++k)
    if (!plot.series[k].name.empty()) {
      named.push_back(k);
      legend_width = std::max(legend_width, Canvas::text_width(plot.series[k].name));
    }
  if (!named.empty()) {
    const double row = 22.0, box_w = legend_width + 48, box_h = row * named.size() + 10;
    const double bx = r.x1 - box_w - 10, by = r.y0 + 10;
    canvas.fill_rect(bx, by, bx + box_w, by + box_h, paper_color(), 0.92f);
    canvas.stroke_rect(bx, by, bx + box_w, by + box_h, grid_color(), 1.0);
    for (std::size_t n = 0; n < named.size(); ++n) {
      const Series& s = plot.series[named[n]];
      const Color color = palette_color(s.color_id >= 0 ? s.color_id : static_cast<int>(named[n]));
      const double y = by + 5 + row * (n + 0.5);
      canvas.line({bx + 8, y}, {bx + 32, y}, color, 2.0);
      if (s.markers) canvas.disc({bx + 20, y}, 3.0, color);
      canvas.text(bx + 40, y - 7, s.name, ink_color(), 2.0);
    }
  }
  draw_title(canvas, plot.title);
  return canvas.image();
}

}  // namespace hairfit
