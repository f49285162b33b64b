// Scan-like test cases built from the sculpted busts (sculpted_bust.h): what real sculpture scans
// do to `hairfit prepare` that a clean sampled bust does not. Each is a closed raw scan with the
// hair painted kHairColor, in cm:
//   far      the plain bust 10⁴ times its size from the origin (coordinates ~5·10⁵ cm, where a
//            float's step is 0.03 cm);
//   coarse   the bun sampled at 5 cm (about 600 triangles: as coarse as a decimated scan, the bun
//            overhanging the nape in a few long triangles);
//   tilted   the plain bust turned by 30° (forward and to the side);
//   dressed  braids, bows and a bun at once, the head turned by 30° (at 0.3 cm at most);
//   noisy    the braids with scan noise: every vertex moved along its normal by up to ±0.05 cm
//            (add_scan_noise).
// The bust is quantised to multiples of 2⁻²⁴ cm before it is moved, so the far scan is the centred
// one plus the offset exactly (a test of translation, not of rounding).
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "prepare/sculpted_bust.h"

namespace hairfit {

struct ScanLikeCase {
  std::string name;
  SculptFeatures features;
  double spacing = 0.4;          // cm, of the sampling grid (coarser: fewer, longer triangles)
  double noise = 0.0;            // cm, the largest move along the normal
  Vec3 offset = Vec3::Zero();    // cm, the whole scan moved by this
};

// The five cases above, at `spacing` cm (the coarse one at its own 5 cm, the dressed one at 0.3 at most).
std::vector<ScanLikeCase> scan_like_cases(double spacing = 0.4);
ScanLikeCase scan_like_case(const std::string& name, double spacing = 0.4);  // one of them by name

BustScan make_scan_like(const ScanLikeCase& c);

// Moves every vertex along its area-weighted normal by up to ±amplitude (cm): uniform noise per
// vertex (a counter-based stream each), averaged twice with the neighbours and scaled so the
// largest move is the amplitude. Uncorrelated noise of that size folds the sampled scan's tiny
// triangles (the scan then crosses itself).
void add_scan_noise(Mesh& mesh, double amplitude, std::uint64_t seed);

}  // namespace hairfit
