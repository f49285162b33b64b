// The scalp chart (paper §3.3, docs/design.md §3): Floater's mean-value parameterisation of the disk-like
// scalp onto the unit disk. It is the texture space of the density, tilt and length maps.
//
// Orientation convention (exact):
//   * The chart looks DOWN on the scalp from outside, from above (from −down toward down).
//   * Chart +y points to `front`: the boundary vertex with the largest position·front (the lowest
//     index among exact ties) lies at chart angle +90°, i.e. at (0, 1).
//   * The chart is not mirrored: seen from above with the front at the top, the person's right is
//     on the right, so chart +x points roughly along front × up = down × front (the person's right).
//     Equivalently the hairline runs counter-clockwise in the chart exactly when it runs
//     counter-clockwise about up (= −down) in 3D. This holds whichever way the triangles are
//     oriented: the boundary direction comes from the vector area of the scalp, not the winding.
//   * Boundary vertices lie on the unit circle at angles proportional to the chord length along
//     the hairline (starting from the front vertex at +90°, increasing counter-clockwise).
// Map addressing: a chart point (x, y) in the unit disk picks image coordinates
//   u = (x + 1) / 2 (left → right),  v = (1 − y) / 2 (row 0 at the top = front),
// sampled bilinearly by GreyMap::sample. The image's inscribed circle is the scalp; the corners
// are unused. In chart.obj the texture coordinates are written as vt = (u, 1 − v) =
// ((x + 1)/2, (y + 1)/2), because OBJ puts vt's origin at the image's bottom-left.
#pragma once
#include <string>
#include <vector>

#include "core/digest.h"
#include "core/mesh.h"

namespace hairfit {

// A point on the scalp as a triangle and barycentric weights of its three corners (sum 1).
struct SurfacePoint {
  int triangle = -1;
  Vec3 barycentric = Vec3::Zero();
};

// Uniform grid over [−1, 1]² listing the triangles whose chart bounding box meets each cell.
struct ChartGrid {
  int cells = 0;                         // per side
  std::vector<int> cell_start;           // cells² + 1 offsets into cell_triangles
  std::vector<int> cell_triangles;
};

struct ScalpChart {
  Mesh mesh;                         // the scalp, cm, as given
  std::vector<Vec2> chart;           // per vertex: chart coordinates in the closed unit disk
  std::vector<Vec3> vertex_normals;  // per vertex: unit outward normal (angle-weighted)
  std::vector<int> boundary;         // hairline loop, counter-clockwise in the chart, from the front vertex
  std::vector<int> boundary_triangles;  // the triangle holding hairline edge boundary[k] → boundary[k+1]
  int outward = 1;                   // +1 when triangles turn counter-clockwise seen from outside, else −1
  Vec3 front{0, 0, 1}, down{0, -1, 0};  // unit, as given
  double area = 0.0;                 // cm², 3D surface area
  double height_low = 0.0, height_high = 0.0;  // extent of the vertices along up = −down, cm
  int flipped_triangles = 0;         // triangles whose chart orientation is reversed (0: one-to-one)
  ChartGrid grid;                    // point location
  std::string solver;                // which sparse solver produced the interior ("SparseLU")
};

// Builds the chart of `scalp` (positions in cm). front and down are world directions (need not be
// unit; must not be parallel). Interior: Floater's mean-value weights w_ij = (tan(α/2)+tan(β/2))/|e_ij|
// (all positive, hence a convex-combination map: one-to-one for the convex circle boundary), one
// sparse LU solve for both coordinates. Throws InputError naming `file_for_errors` if the scalp is
// not a topological disk, is inconsistently oriented, has coincident vertices, or its hairline is
// edge-on when seen from above (down is tangent to the scalp's mean plane).
ScalpChart make_scalp_chart(const Mesh& scalp, const Vec3& front, const Vec3& down,
                            const std::string& file_for_errors);

// The checks make_scalp_chart makes before any work (disk, consistent orientation, front and down,
// hairline not edge-on), on their own, so inputs can be refused before a run writes anything.
// Returns the sign (+1 or −1) that turns the triangles' normals outward, i.e. upward.
int check_scalp_for_chart(const Mesh& scalp, const Vec3& front, const Vec3& down, const std::string& file_for_errors);

// Image coordinates (u, v) ∈ [0, 1]² of a chart point (see the convention above).
inline Vec2 chart_to_image(const Vec2& chart) { return Vec2((chart.x() + 1.0) / 2.0, (1.0 - chart.y()) / 2.0); }

// The triangle holding a chart point and its barycentric coordinates. A point outside the chart
// polygon (between the hairline polygon and the unit circle, or beyond) is moved to the nearest
// point of the polygon first. Expected O(1) through the grid.
SurfacePoint locate_in_chart(const ScalpChart& chart, const Vec2& chart_point);

// Position (cm), unit outward normal (interpolated vertex normals) and chart point of a surface point.
Vec3 surface_position(const ScalpChart& chart, const SurfacePoint& point);
Vec3 surface_normal(const ScalpChart& chart, const SurfacePoint& point);
Vec2 chart_position(const ScalpChart& chart, const SurfacePoint& point);

// Height in [0, 1] along up = −down: 0 at the lowest scalp vertex, 1 at the highest (top of head).
double height_of(const ScalpChart& chart, const Vec3& position);

// Signed chart area of a triangle (positive when counter-clockwise in the chart).
double chart_triangle_area(const ScalpChart& chart, int triangle);

Digest digest(const ScalpChart& chart);

}  // namespace hairfit
