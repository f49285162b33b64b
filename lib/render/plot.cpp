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
  // The bottom margin holds the tick labels and the axis label, whose text does not shrink with
  // the picture: 70 px down to 230 px high.
  return {std::min(100.0, 0.2 * width), 48.0, width - right_margin, height - std::min(70.0, 0.3 * height)};
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

  // The legend's box: one row per named series.
  std::vector<std::size_t> named;
  double legend_width = 0.0;
  for (std::size_t k = 0; k < plot.series.size(); ++k)
    if (!plot.series[k].name.empty()) {
      named.push_back(k);
      legend_width = std::max(legend_width, Canvas::text_width(plot.series[k].name));
    }
  const double row = 22.0, box_w = legend_width + 48, box_h = row * named.size() + 10;

  // Axes whose y range leaves the top `headroom` share of the plot area free of data.
  const PlotRect area = plot_rect(width, height, 24.0);
  auto make_axes = [&](double headroom) {
    double high = y_hi;
    if (headroom > 0.0)
      high = plot.log_y ? y_hi * std::pow(y_hi / y_lo, headroom / (1.0 - headroom))
                        : y_hi + (y_hi - y_lo) * headroom / (1.0 - headroom);
    return Axes(area, fit_range(x_lo, x_hi, plot.log_x), fit_range(y_lo, high, plot.log_y));
  };
  // Pixels along every line and at every point, where the legend must not go.
  auto drawn_pixels = [&](const Axes& axes) {
    std::vector<Vec2> drawn;
    for (const Series& s : plot.series) {
      Vec2 previous = Vec2::Zero();
      bool joined = false;
      for (std::size_t i = 0; i < s.x.size(); ++i) {
        if (!usable(s.x[i], s.y[i])) {
          joined = false;
          continue;
        }
        const Vec2 p = axes.to_pixel(s.x[i], s.y[i]);
        if (s.lines && joined)
          for (int t = 1; t < 16; ++t) drawn.push_back(previous + (p - previous) * (t / 16.0));
        drawn.push_back(p);
        previous = p, joined = true;
      }
    }
    return drawn;
  };
  // The corners of the plot area in order of preference, and the first that hides nothing; with
  // none, the data makes room at the top and the legend takes the top right.
  auto corner = [&](const PlotRect& r, int c) {
    return Vec2(c % 2 == 0 ? r.x1 - box_w - 10 : r.x0 + 10, c < 2 ? r.y0 + 10 : r.y1 - box_h - 10);
  };
  auto hides = [&](const std::vector<Vec2>& drawn, const Vec2& at) {
    return std::any_of(drawn.begin(), drawn.end(), [&](const Vec2& p) {
      return p.x() >= at.x() - 4 && p.x() <= at.x() + box_w + 4 && p.y() >= at.y() - 4 && p.y() <= at.y() + box_h + 4;
    });
  };
  Axes axes = make_axes(0.0);
  Vec2 legend_at = corner(area, 0);
  if (!named.empty()) {
    const std::vector<Vec2> drawn = drawn_pixels(axes);
    int clear = -1;
    for (int c = 0; c < 4 && clear < 0; ++c)
      if (!hides(drawn, corner(axes.rect(), c))) clear = c;
    if (clear >= 0) {
      legend_at = corner(axes.rect(), clear);
    } else {
      axes = make_axes(std::min(0.6, (box_h + 24.0) / (area.y1 - area.y0)));
      legend_at = corner(axes.rect(), 0);
    }
  }

  Canvas canvas(width, height, paper_color());
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
  if (!named.empty()) {
    const double bx = legend_at.x(), by = legend_at.y();
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
