// How closely generated hair follows reference hair that the method did not make (issue 47):
// point by point, each point carrying the hair's unit direction there. A generated point matches
// when a reference point lies within `radius` whose direction differs by at most `max_angle`, and
// a reference point matches the other way round; precision, recall and their harmonic mean F
// follow, beside the share of the reference reached at all and the median angle to the nearest
// reference point.
#pragma once
#include <vector>

#include "core/curves.h"
#include "core/types.h"

namespace hairfit {

// Points on hair, each with the hair's unit direction there (root to tip).
struct OrientedPoints {
  std::vector<Vec3> points;      // cm
  std::vector<Vec3> directions;  // unit, one per point
};

// Points every `spacing` cm of arc length along each curve, from its root (s = 0, spacing,
// 2·spacing, … up to its length), each with the unit direction of the segment it lies on (at a
// segment's end, the next segment's). Zero-length segments carry no direction and are stepped
// over. Equal spacing makes the figures shares of hair length, whatever the points per curve.
// Throws std::invalid_argument unless spacing > 0.
OrientedPoints curve_points(const Curves& curves, double spacing);

struct MatchOptions {
  double radius = 2.0;       // cm: how near a matching point lies (inclusive)
  double max_angle = 45.0;   // degrees: how far its direction may turn (inclusive)
  // false: directions compare as lines (the angle between d and ±d′, in [0°, 90°]); true: as
  // vectors root to tip (in [0°, 180°]), so hair running the wrong way does not match.
  bool signed_directions = false;
  int threads = 1;           // the figures are the same for any count
};

struct MatchFigures {
  int generated = 0, reference = 0;  // points compared
  double precision = 0.0;  // share of generated points with a matching reference point
  double recall = 0.0;     // share of reference points with a matching generated point
  double f = 0.0;          // 2PR / (P + R); 0 when both are 0
  double reached = 0.0;    // share of reference points with a generated point within radius, any direction
  double near = 0.0;       // share of generated points with a reference point within radius, any direction
  // Degrees: the median over generated points of the angle to the nearest reference point (of
  // equally near ones, the first), as options.signed_directions compares them; the mean of the
  // middle two for an even count. 0 without points on either side.
  double median_angle = 0.0;
};

// The angle between unit directions a and b in degrees, as lines or as vectors (MatchOptions).
double direction_angle(const Vec3& a, const Vec3& b, bool signed_directions);

// Throws std::invalid_argument for a radius ≤ 0, an angle outside [0°, 180°], or directions
// that do not pair with the points.
MatchFigures match_reference(const OrientedPoints& generated, const OrientedPoints& reference,
                             const MatchOptions& options = {});

// Per point of `from`: 1 where a point of `to` matches it (within options.radius, turned by at
// most options.max_angle), else 0: the points precision counts when `from` is the generated hair,
// recall when it is the reference. For pictures of where the two agree.
std::vector<unsigned char> matched_points(const OrientedPoints& from, const OrientedPoints& to,
                                          const MatchOptions& options = {});

}  // namespace hairfit
