// Reference hair from hair cards: the strips an artist lays root to tip, textured so that the
// painted strands run along one texture axis (issue 47's round trip; MakeHuman's hair proxies).
// Per UV island (triangles joined across edges whose two corners share texture coordinates):
// - along which axis the hair runs: the axis whose two ends lie farther apart in space, the ends
//   being the island's area below the `end_share` quantile of that coordinate and above the
//   1 − end_share quantile. A strip is long along its strands; a tube's around-axis starts and
//   ends at its seam, in the same place.
// - which end is the root: the end nearer the scalp, where the two ends' mean distances from the
//   scalp differ by at least `sense_tolerance`; else (a strip lying on the head) the end where
//   that coordinate is highest, as on every MakeHuman island whose sense the scalp decides but
//   braid01's end piece (the texture's top holds the roots).
// The hair's direction in a triangle is the iso-line of the across coordinate, oriented root to
// tip: n × ∇across, with the sign that makes it climb the along coordinate toward the tip.
#pragma once
#include <vector>

#include "core/mesh.h"
#include "io/obj_mesh.h"
#include "reference/reference_match.h"

namespace hairfit {

struct CardOptions {
  double end_share = 0.1;        // share of an island's area in each of its two ends
  double sense_tolerance = 0.5;  // cm: ends nearer the scalp by at least this decide the root
  int min_island_triangles = 8;  // smaller islands (single quads, tube caps) tell no axis: left out
  double samples_per_cm2 = 4.0;  // reference points per cm² of card area
};

struct CardIsland {
  int triangles = 0;
  double area = 0.0;                 // cm²
  int along = 1;                     // the texture axis along the hair: 0 = u, 1 = v
  double end_separation = 0.0;       // cm: between the two ends along `along`
  double across_separation = 0.0;    // cm: the same along the other axis
  bool root_at_high = true;          // the root is where the along coordinate is highest
  double root_scalp_distance = 0.0;  // cm: mean distance of the root end's area from the scalp
  double tip_scalp_distance = 0.0;   // cm: the same for the tip end
  bool sense_from_scalp = false;     // the distances decided the root (else the texture's top)
  bool used = false;                 // large enough to tell its axis, with texture coordinates
};

struct ReferenceHair {
  OrientedPoints samples;                 // area samples of the used islands, the direction there
  std::vector<Vec3> triangle_directions;  // per card triangle: unit, root to tip; zero where unused
  std::vector<int> triangle_island;       // per card triangle: its island, −1 without texture coordinates
  std::vector<CardIsland> islands;
  double used_area = 0.0, total_area = 0.0;  // cm²
  double sensed_area = 0.0;                  // cm² of used islands whose root the scalp decided
};

// `cards` as load_obj_textured reads it (cm), `scalp` in cm. Triangles without texture
// coordinates, or of zero area in space or in the texture, belong to no island. Deterministic.
ReferenceHair reference_from_cards(const TexturedMesh& cards, const Mesh& scalp, const CardOptions& options = {});

}  // namespace hairfit
