// The scalp chart as a picture (paper §3, Fig. 3): the unit disk with the chart's triangles as thin
// lines, the pores coloured by cluster, the cluster circles and the guide bases highlighted.
#pragma once
#include <string>
#include <vector>

#include "core/types.h"
#include "io/png_image.h"

namespace hairfit {

struct ChartCircle {
  Vec2 centre;        // chart coordinates (unit disk)
  double radius = 0;  // chart units
  int id = -1;        // cluster id → palette colour (−1: grey)
};

struct ChartDrawing {
  std::string title;
  std::vector<Vec2> vertices;    // chart positions of the scalp vertices
  std::vector<Vec3i> triangles;  // indices into vertices
  std::vector<Vec2> points;      // pores
  std::vector<int> point_ids;    // cluster of each pore (palette colour), or empty (all dark grey)
  std::vector<ChartCircle> circles;
  std::vector<Vec2> highlights;  // guide bases: drawn as larger ringed dots
  std::string up_label = "front";  // written above the disk: what the chart's +v axis points to
};

// Chart coordinate (u, v) is drawn with v upward. Throws std::invalid_argument for a triangle
// index out of range or point_ids of the wrong length.
Image render_chart(const ChartDrawing& chart, int width = 800, int height = 800);

}  // namespace hairfit
