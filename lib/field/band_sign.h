// Signs for the band's samples from an InsideTest, asked as rarely as the geometry allows.
// Internal to lib/field.
//
// Across a sheet the inside changes exactly where the sheet is, and along it only where something
// else is near: a rim, a non-manifold edge, or a seam where an open mesh's inside changes in empty
// space. So each face is probed on both sides of its centroid, just off it and a band width out;
// where the two probes of a side agree and no rim, non-manifold edge or flipped patch's border lies
// within two band widths, every sample on that side of the face (its closest feature
// the face, or an edge or vertex all of whose faces agree) takes that answer. Every other sample
// is asked itself.
#pragma once
#include <array>
#include <vector>

#include "field/band_scan.h"
#include "field/distance_field.h"

namespace hairfit::field {

// The faces' settled answers, and the test for everything else.
class SettledSigns {
 public:
  // `band` (its keys and pseudo-normal-signed values): a face side is probed only where at least
  // kWorthProbing of the band's samples could take its answer (keyed to the face, or to an edge or
  // vertex of it, on that side); elsewhere asking the samples themselves costs fewer tests.
  SettledSigns(const MeshFeatures& features, double r, const InsideTest& inside, int threads,
               const BandScan* band = nullptr);
  static constexpr int kWorthProbing = 3;  // a side's two probes against the samples they answer
  // The test's answer at p, whose closest feature is `key` (band_scan.h's keys; −1 for none) and
  // which lies in front of it (side 0) or behind it (side 1): the settled answer where there is
  // one, the test's own elsewhere.
  bool inside(const Vec3& p, int key, int side) const;

 private:
  int settled(int key, int side) const;  // 0 or 1, or −1 where unsettled

  const MeshFeatures& features_;
  const InsideTest& inside_;
  std::vector<std::array<signed char, 2>> faces_;  // per face and side: −1 unsettled, 0 outside, 1 inside
};

// Replaces the sign of every band sample (band.value, signed by the pseudo-normal's side) with the
// test's. Deterministic for any thread count.
void sign_band(const SettledSigns& signs, const GridGeometry& grid, BandScan& band, int threads);

}  // namespace hairfit::field
