// The strip that joins a level-set sheet (scalp_level_set.h: the zero set's piece, clipped 1.5
// voxels from the hairline) to the loop above it: the hull's hairline for the scalp, the scalp
// piece's end for the floor.
//
// The strip is a zipper pairing the vertices of both loops by their places along the hairline.
// Where noise roughens the hull near its hairline, or the hairline bends so that one piece vertex
// fans to many hairline vertices, its chords can graze the hull and cross it. lower_strip finds
// the strip triangles that cross the hull (exact tests) and gives the hairline vertices around
// them feet below them along the scan's smoothed inward normal: there the strip leaves the
// hairline steeply, for a share of ε, and its chords run from the feet.
#pragma once
#include <vector>

#include "core/mesh.h"
#include "field/distance_field.h"

namespace hairfit {

// A level set's piece and its strip, as scalp_level_set.cpp builds them.
struct LevelSetSheet {
  Mesh mesh;                      // the level set's piece, then the strip joining it to the outer loop
  std::vector<double> thickness;  // per vertex: the thickness the scalp was placed for
  std::vector<int> outer;         // mesh vertices copied from the outer loop, in its order
  std::vector<int> inner;         // the piece's boundary, from its vertex nearest the outer loop's first
  std::vector<int> feet;          // per outer vertex: the strip's foot under it (lower_strip), or the outer vertex
  std::vector<double> inner_at, outer_at;  // the two loops' places along the reference (parameters_along)
  std::size_t piece_vertices = 0; // the piece's vertices come first, then the outer loop's, then the feet
  std::size_t strip_begin = 0;    // the strip's first triangle
  int dropped_parts = 0;
  int holes_filled = 0;           // holes of the piece filled (holes.h), and the longest of them (cm)
  double longest_hole = 0.0;
};

// The strip between the piece's boundary and the outer loop, (re)built: where depth[j] > 0 the
// outer vertex j gets a foot `depth[j]` below it along `inward[j]`, a band joins the outer loop to
// its feet and the zipper joins the feet (the outer vertex itself where there is none) to the
// piece, pairing the vertices of both loops by their places along the reference.
void zip_strip(LevelSetSheet& s, const std::vector<double>& depth, const std::vector<Vec3>& inward);

// The outer-loop indices of the strip triangles that cross `hull`, ascending (exact tests;
// triangles that share a vertex are not counted, and the strip's outer loop is `hairline`, the
// hull's vertices). Only hull triangles whose box meets a strip triangle's are tested.
std::vector<int> strip_crossings(const LevelSetSheet& s, const Mesh& hull, const std::vector<int>& hairline, int threads);

// Rounds deepen the feet (½, ¾ and 1 times ε) and widen the run of hairline vertices given them
// (kFootRun more on each side each round, tapering over as many again) until no strip triangle
// crosses `hull`; `hairline` (the hull's vertices) is the sheet's outer loop, and `field` the
// scan's distance, whose C² gradient gives the inward normal (so the feet do not follow the noise
// of single triangles). Returns how many hairline vertices got feet (0: the strip is as zipped).
constexpr int kFootRun = 2;
constexpr int kFootRounds = 3;
int lower_strip(LevelSetSheet& s, const Mesh& hull, const std::vector<int>& hairline, const DistanceField& field, double epsilon,
                int threads);

}  // namespace hairfit
