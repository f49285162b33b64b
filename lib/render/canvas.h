// A float RGB drawing surface for 2D pictures (plots, charts, captions): the transient builder
// behind every plot, turned into an immutable Image at the end. Coordinates are image pixels, x to
// the right and y downward; pixel (i, j) covers [i, i+1) × [j, j+1), its centre is (i+½, j+½).
// Every primitive is anti-aliased by its exact or estimated pixel coverage and blended in the order
// drawn, so the same calls always give the same pixels.
#pragma once
#include <string>
#include <vector>

#include "core/types.h"
#include "io/png_image.h"
#include "render/color.h"

namespace hairfit {

enum class TextAlign { left, centre, right };

class Canvas {
 public:
  // Throws std::invalid_argument for a non-positive size.
  Canvas(int width, int height, const Color& background);

  int width() const { return width_; }
  int height() const { return height_; }
  Color at(int x, int y) const;

  // Blends `color` over pixel (x, y) with weight alpha in [0, 1]; outside pixels are ignored.
  void blend(int x, int y, const Color& color, float alpha);
  void set(int x, int y, const Color& color) { blend(x, y, color, 1.0f); }

  // Axis-aligned rectangle [x0, x1] × [y0, y1] (pixels), weighted by each pixel's exact covered area.
  void fill_rect(double x0, double y0, double x1, double y1, const Color& color, float alpha = 1.0f);
  void stroke_rect(double x0, double y0, double x1, double y1, const Color& color, double width = 1.0);
  // Segment of the given width (pixels) with butt ends, anti-aliased by exact area coverage along
  // the major axis (see line_raster.h): the coverage deposited is width × length at every angle.
  void line(const Vec2& a, const Vec2& b, const Color& color, double width = 1.0, float alpha = 1.0f);
  void polyline(const std::vector<Vec2>& points, const Color& color, double width = 1.0, bool closed = false,
                float alpha = 1.0f);
  void disc(const Vec2& centre, double radius, const Color& color, float alpha = 1.0f);
  void circle(const Vec2& centre, double radius, const Color& color, double width = 1.0, float alpha = 1.0f);
  // Filled triangle, anti-aliased by 4×4 sub-samples per edge pixel.
  void triangle(const Vec2& a, const Vec2& b, const Vec2& c, const Color& color, float alpha = 1.0f);

  // Text in stb_easy_font's built-in bitmap font (ASCII), `scale` pixels per font unit (the
  // capital height is 7 units). (x, y) is the anchor: the top of the text, aligned left/centre/
  // right of x. With `vertical`, the text runs bottom to top (for y-axis labels) and the anchor is
  // its left edge, centred on y by `align`.
  void text(double x, double y, const std::string& text, const Color& color, double scale = 2.0,
            TextAlign align = TextAlign::left, bool vertical = false);
  static double text_width(const std::string& text, double scale = 2.0);
  // The scale, at most `largest` and never below the font's own pixel size (1), at which `text`
  // fits in `room` pixels: smaller type rather than a label cut off in a small panel.
  static double fitting_scale(const std::string& text, double room, double largest);
  static double text_height(double scale = 2.0) { return 7.0 * scale; }

  // Copies an image with its top-left corner at pixel (x, y), blending by its alpha.
  void draw_image(const Image& image, int x, int y);

  Image image() const;

 private:
  int width_;
  int height_;
  std::vector<float> rgb_;
};

// "Nice" axis tick values covering [low, high]: steps of 1, 2 or 5 × 10^k, about `target` of them.
std::vector<double> nice_ticks(double low, double high, int target = 6);
// Short label of a tick value: %g with up to 4 significant digits, "0" for values within
// 1e-9·step of zero (never "-0").
std::string tick_label(double value, double step = 0.0);

}  // namespace hairfit
