// Hair that suits its shell (issue 23): when a scene leaves hair.length and the tilt unset, the run
// derives them from the layer the hull and the scalp enclose, as `hairfit prepare` does for the
// scenes it writes. The layer is at most T thick (the 90th percentile of its thickness over the
// scalp's vertices, robust to a few stray cards) and its points lie up to `reach` along the scalp
// from where it ends (scalp/growth_field.h layer_end_distance), so hair tilts by
// 90° − atan(T / reach) (at most kMaxShellTilt), rising T over that distance, and is ⅔·reach long
// (rounded to 0.5 cm): on a disk-like cap, the mean distance from a root to the innermost point,
// toward which it grows.
#pragma once

#include "scalp/chart.h"
#include "scalp/roots.h"

namespace hairfit {

// The largest derived tilt: a root's growth direction must clear the scalp's facets, whose
// normals differ from the interpolated vertex normals by a few degrees on real scalps (MakeHuman
// short04: tilt 88° put 3.4 % of the guides' points in the head, 80° 1.2 %).
constexpr double kMaxShellTilt = 80.0;

struct ShellHair {
  bool layer_ends = false;  // the layer ends somewhere on the scalp (else nothing is derived)
  double thickness = 0.0;   // cm, T
  double reach = 0.0;       // cm
  double tilt = 0.0;        // degrees, whole
  double length = 0.0;      // cm
};

// tilt and length from T and reach (cm), the rule above.
ShellHair hair_for_shell(double thickness, double reach);

// T: the 90th percentile of the layer's thickness over the scalp's vertices (`thickness` gives the
// layer's depth below the hull), whether or not the layer ends.
double shell_thickness(const ScalpChart& chart, const ThicknessField& thickness, int threads);

// The rule applied to the layer over this scalp: `thickness` gives the layer's depth below the hull.
ShellHair shell_hair(const ScalpChart& chart, const ThicknessField& thickness, int threads);

}  // namespace hairfit
