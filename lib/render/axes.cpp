#include "render/axes.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

namespace hairfit {

namespace {

double transform(double value, bool log) {
  if (!log) return value;
  return value > 0 ? std::log10(value) : -std::numeric_limits<double>::infinity();
}

std::string decade_label(int exponent) {
  if (exponent >= -3 && exponent <= 4) return tick_label(std::pow(10.0, exponent));
  return "1e" + std::to_string(exponent);
}

}  // namespace

double Axes::to_x(double value) const {
  const double lo = transform(x_.low, x_.log), hi = transform(x_.high, x_.log);
  return rect_.x0 + (transform(value, x_.log) - lo) / (hi - lo) * (rect_.x1 - rect_.x0);
}

double Axes::to_y(double value) const {
  const double lo = transform(y_.low, y_.log), hi = transform(y_.high, y_.log);
  return rect_.y1 - (transform(value, y_.log) - lo) / (hi - lo) * (rect_.y1 - rect_.y0);
}

AxisRange fit_range(double low, double high, bool log, double pad) {
  AxisRange r;
  r.log = log;
  if (log) {
    if (!(low > 0) || !std::isfinite(low)) low = high;
    if (!(high > 0) || !std::isfinite(high)) return {1.0, 10.0, true};
    r.low = std::pow(10.0, std::floor(std::log10(low) + 1e-9));
    r.high = std::pow(10.0, std::ceil(std::log10(high) - 1e-9));
    if (!(r.high > r.low)) r.high = r.low * 10.0;
    return r;
  }
  if (!std::isfinite(low) || !std::isfinite(high)) low = 0.0, high = 1.0;
  if (high < low) std::swap(low, high);
  if (high == low) {
    const double w = low == 0 ? 1.0 : 0.1 * std::abs(low);
    low -= w, high += w;
  }
  r.low = low - pad * (high - low);
  r.high = high + pad * (high - low);
  return r;
}

void Axes::draw(Canvas& canvas, const std::string& x_label, const std::string& y_label, bool x_ticks, bool grid) const {
  const Color ink = ink_color(), light = grid_color();
  const double scale = 2.0;
  // Tick positions: whole decades on log axes (with 2..9 minor ticks), nice steps otherwise, as
  // many as fit: labels need their width plus a gap along x, 1.6 text heights along y (a small
  // panel of a contact sheet otherwise runs its labels into one another).
  const double gap = 10.0, line = 1.6 * Canvas::text_height(scale);
  auto fits = [&](const std::vector<std::string>& labels, bool along_x) {
    double need = 0.0;
    for (const std::string& l : labels) need += along_x ? Canvas::text_width(l, scale) + gap : line;
    return need <= (along_x ? rect_.x1 - rect_.x0 : rect_.y1 - rect_.y0);
  };
  auto ticks = [&](const AxisRange& a, bool along_x, std::vector<double>& major, std::vector<double>& minor,
                   std::vector<std::string>& labels) {
    if (a.log) {
      const int e0 = static_cast<int>(std::floor(std::log10(a.low) + 1e-9));
      const int e1 = static_cast<int>(std::ceil(std::log10(a.high) - 1e-9));
      const int stride = std::max(1, (e1 - e0 + 7) / 8);
      for (int e = e0; e <= e1; ++e) {
        if ((e - e0) % stride == 0) major.push_back(std::pow(10.0, e)), labels.push_back(decade_label(e));
        if (stride == 1 && e < e1)
          for (int m = 2; m <= 9; ++m) minor.push_back(m * std::pow(10.0, e));
      }
    } else {
      for (int target = 6; target >= 2; --target) {
        major = nice_ticks(a.low, a.high, target);
        const double step = major.size() > 1 ? major[1] - major[0] : 0.0;
        labels.clear();
        for (double v : major) labels.push_back(tick_label(v, step));
        if (fits(labels, along_x)) break;
      }
    }
  };
  std::vector<double> xs, xm, ys, ym;
  std::vector<std::string> xl, yl;
  ticks(x_, true, xs, xm, xl);
  ticks(y_, false, ys, ym, yl);
  const PlotRect& r = rect_;
  if (grid) {
    for (double v : ys) {
      const double y = to_y(v);
      if (y >= r.y0 - 0.5 && y <= r.y1 + 0.5) canvas.line({r.x0, y}, {r.x1, y}, light, 1.0);
    }
    if (x_ticks)
      for (double v : xs) {
        const double x = to_x(v);
        if (x >= r.x0 - 0.5 && x <= r.x1 + 0.5) canvas.line({x, r.y0}, {x, r.y1}, light, 1.0);
      }
  }
  canvas.stroke_rect(r.x0, r.y0, r.x1, r.y1, ink, 1.2);
  double widest = 0.0;
  for (std::size_t i = 0; i < ys.size(); ++i) {
    const double y = to_y(ys[i]);
    if (y < r.y0 - 0.5 || y > r.y1 + 0.5) continue;
    canvas.line({r.x0 - 5, y}, {r.x0, y}, ink, 1.2);
    canvas.text(r.x0 - 8, y - 0.5 * Canvas::text_height(scale), yl[i], ink, scale, TextAlign::right);
    widest = std::max(widest, Canvas::text_width(yl[i], scale));
  }
  for (double v : ym) {
    const double y = to_y(v);
    if (y >= r.y0 && y <= r.y1) canvas.line({r.x0 - 3, y}, {r.x0, y}, ink, 1.0);
  }
  if (x_ticks) {
    for (std::size_t i = 0; i < xs.size(); ++i) {
      const double x = to_x(xs[i]);
      if (x < r.x0 - 0.5 || x > r.x1 + 0.5) continue;
      canvas.line({x, r.y1}, {x, r.y1 + 5}, ink, 1.2);
      canvas.text(x, r.y1 + 9, xl[i], ink, scale, TextAlign::centre);
    }
    for (double v : xm) {
      const double x = to_x(v);
      if (x >= r.x0 && x <= r.x1) canvas.line({x, r.y1}, {x, r.y1 + 3}, ink, 1.0);
    }
  }
  if (!x_label.empty()) canvas.text(0.5 * (r.x0 + r.x1), r.y1 + 32, x_label, ink, scale, TextAlign::centre);
  if (!y_label.empty())
    canvas.text(std::max(4.0, r.x0 - widest - 30), 0.5 * (r.y0 + r.y1), y_label, ink, scale, TextAlign::centre, true);
}

void draw_title(Canvas& canvas, const std::string& title) {
  if (title.empty()) return;
  canvas.text(0.5 * canvas.width(), 14, title, ink_color(), Canvas::fitting_scale(title, canvas.width() - 8, 2.5),
              TextAlign::centre);
}

}  // namespace hairfit
