// Plots for stages and benchmarks: bar charts (the paper's Fig. 5: cells per number of segments),
// XY line plots with optional log axes (benchmarks: error against time), heat maps of 2D scalar
// grids (field slices with their zero contour; the paper's Fig. 6 density slice), all on white
// paper with ticks, labels, a title and a legend or colour bar.
#pragma once
#include <array>
#include <string>
#include <vector>

#include "core/types.h"
#include "io/png_image.h"
#include "render/color.h"

namespace hairfit {

struct BarPlot {
  std::string title, x_label, y_label;
  std::vector<double> values;  // bar heights (non-finite bars are left out)
  double x_start = 0.0;        // x of the centre of bar 0
  double x_step = 1.0;         // distance between bar centres (> 0); bars fill 80% of it
  Color color{0.31f, 0.47f, 0.65f};
};
Image render_bar_plot(const BarPlot& plot, int width = 800, int height = 500);

struct Series {
  std::string name;          // legend entry (none when empty)
  std::vector<double> x, y;  // same length; points with a non-finite (or, on log axes, ≤ 0) coordinate are skipped
  int color_id = -1;         // palette_color(color_id); −1 = the series' index
  bool markers = true;       // a dot at every point
  bool lines = true;         // join consecutive points
};
struct LinePlot {
  std::string title, x_label, y_label;
  bool log_x = false, log_y = false;
  std::vector<Series> series;
};
// Throws std::invalid_argument when a series' x and y differ in length.
Image render_line_plot(const LinePlot& plot, int width = 800, int height = 500);

// A 2D scalar grid: values at nodes (i, j), i along x (fastest), j along y, spanning
// [x_min, x_max] × [y_min, y_max] with the first and last nodes on the edges. Non-finite values
// mean "no data" (e.g. outside a narrow band) and are drawn grey.
struct ScalarGrid {
  int width = 0;   // nodes along x (≥ 2)
  int height = 0;  // nodes along y (≥ 2)
  std::vector<double> values;
  double x_min = 0.0, x_max = 1.0, y_min = 0.0, y_max = 1.0;  // world units (cm)
  double at(int i, int j) const { return values[static_cast<std::size_t>(j) * width + i]; }
};

enum class ColorScale {
  diverging,   // symmetric about 0: blue negative, white 0, red positive (signed distances)
  sequential,  // from 0 (dark) to the maximum (light) (densities)
};

struct HeatMap {
  std::string title, x_label, y_label, value_label;  // value_label names the colour bar
  ScalarGrid grid;
  ColorScale scale = ColorScale::diverging;
  double range = 0.0;    // colour range: ±range or [0, range]; 0 = the data's max |value|
  bool iso_lines = true;  // thin contours at the colour bar's ticks
  bool zero_contour = true;  // the 0 level bold (diverging only)
  bool smooth = true;     // bilinear between nodes; false: each node's cell in one colour
};
// The plot keeps the grid's world aspect ratio. Throws std::invalid_argument for a grid smaller
// than 2 × 2, a value count ≠ width·height or an empty extent.
Image render_heat_map(const HeatMap& map, int width = 800, int height = 600);

// Marching squares: the segments (world coordinates) where the bilinear interpolant of the grid
// crosses `level`; cells with a non-finite corner are skipped. Saddle cells are resolved by the
// cell-centre average, so contours of neighbouring cells join.
std::vector<std::array<Vec2, 2>> contour_segments(const ScalarGrid& grid, double level);

}  // namespace hairfit
