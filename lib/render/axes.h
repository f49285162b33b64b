// Plot axes on a Canvas: the frame, grid, ticks and labels of a 2D plot, linear or logarithmic on
// each axis, and the data → pixel mapping. Shared by the bar, line and heat-map plots.
#pragma once
#include <string>

#include "render/canvas.h"

namespace hairfit {

struct AxisRange {
  double low = 0.0;
  double high = 1.0;
  bool log = false;  // low and high must then be > 0
};

// Pixel rectangle [x0, x1] × [y0, y1] of the plotting area (y downward).
struct PlotRect {
  double x0 = 0, y0 = 0, x1 = 1, y1 = 1;
};

class Axes {
 public:
  Axes(const PlotRect& rect, const AxisRange& x, const AxisRange& y) : rect_(rect), x_(x), y_(y) {}
  const PlotRect& rect() const { return rect_; }
  double to_x(double value) const;  // data → pixel x (values ≤ 0 on a log axis map to −∞ → clipped)
  double to_y(double value) const;  // data → pixel y
  Vec2 to_pixel(double x, double y) const { return {to_x(x), to_y(y)}; }
  // Grid lines, ticks with labels, the frame and axis labels (text colour `ink`).
  void draw(Canvas& canvas, const std::string& x_label, const std::string& y_label, bool x_ticks = true,
            bool grid = true) const;

 private:
  PlotRect rect_;
  AxisRange x_, y_;
};

// A linear range covering [low, high] padded by `pad` of its span (a zero span widens to ±1 or
// ±10%), or a log range widened to whole decades (non-positive values ignored; none → [1, 10]).
AxisRange fit_range(double low, double high, bool log, double pad = 0.05);

// Plot colours: white paper, near-black ink, light grid.
inline Color paper_color() { return {1.0f, 1.0f, 1.0f}; }
inline Color ink_color() { return {0.12f, 0.12f, 0.14f}; }
inline Color grid_color() { return {0.88f, 0.88f, 0.90f}; }

// Draws `title` centred at the top of a plot of the given width.
void draw_title(Canvas& canvas, const std::string& title);

}  // namespace hairfit
