// Whether a winding number exceeds ½ (winding_above_half, HairRegion::inside_hull) against the
// direct sums over every triangle, on open surfaces, where w takes every value between 0 and 1 and
// a hierarchical estimate alone is wrong close to ½.
#include <doctest/doctest.h>

#include <cmath>

#include "core/fast_winding.h"
#include "core/random.h"
#include "core/shapes.h"
#include "field/hair_region.h"
#include "test_meshes.h"

using namespace hairfit;

namespace {

// Points where the β = 4 estimate over an open cap (level 3, radius 1, cut at 0.3) lies on the
// other side of ½ than the direct sum: w = 0.49994, 0.49735, 0.49791 and 0.49799.
const Vec3 kCapFence[] = {{-0.55512515551183605, 0.05066403725681079, 0.29369233539034267},
                          {-0.13094002736310473, -0.48869184776614039, 0.27758781461864146},
                          {-0.57468332772826924, -0.050546187698164102, 0.29174189446109455},
                          {-0.13214466051764062, 0.45017321126077947, 0.279187111081177}};

// Of `count` points uniform in the box [-1.5, 1.5]² × [z0, z1] and the given ones, how many `above` decides
// otherwise than `direct` > ½, and how many lie within 0.25 of ½ (where an estimate without a
// bound decided before).
template <class Above, class Direct>
void compare(const std::vector<Vec3>& given, int count, double z0, double z1, Above&& above, Direct&& direct, int& wrong,
             int& fence) {
  Random rng(50, RandomStage::test, 0);
  std::vector<Vec3> points = given;
  for (int n = 0; n < count; ++n) points.emplace_back(rng.uniform(-1.5, 1.5), rng.uniform(-1.5, 1.5), rng.uniform(z0, z1));
  wrong = fence = 0;
  for (const Vec3& p : points) {
    const double w = direct(p);
    if (std::abs(w - 0.5) < 1e-12) continue;  // the direct sum's own round-off decides
    fence += std::abs(w - 0.5) < 0.25;
    wrong += above(p) != (w > 0.5);
  }
}

}  // namespace

TEST_CASE("winding_above_half: the direct sum's answer on open caps, also right next to ½") {
  const Mesh cap = test::open_cap(3, 1.0, 0.3);
  const FastWindingNumber winding(cap, HairRegion::kFirstBeta);
  int wrong = 0, fence = 0;
  compare(std::vector<Vec3>(std::begin(kCapFence), std::end(kCapFence)), 20000, -1.5, 1.5,
          [&](const Vec3& p) { return winding_above_half(winding, p); }, [&](const Vec3& p) { return winding.direct(p); },
          wrong, fence);
  CHECK(fence > 1000);
  CHECK(wrong == 0);
  for (const Vec3& p : kCapFence) {
    CHECK(std::abs(winding.direct(p) - 0.5) < 3e-3);
    CHECK(winding_above_half(winding, p) == (winding.direct(p) > 0.5));
  }
}

TEST_CASE("HairRegion::inside_hull: H = w_hull − w_scalp as the direct sums decide it, open and closed") {
  // An open hull over a smaller scalp that does not meet it, so that H is near ½ about the hull's
  // opening (z = 0.3), where the samples are; and a closed hull.
  const Mesh hull = test::open_cap(3, 1.0, 0.3);
  const Mesh scalp = spherical_cap(0.7, 6, 16, 0.6), sphere = test::icosphere(3, 1.0);
  for (bool closed : {false, true}) {
    const Mesh& outer = closed ? sphere : hull;
    const HairRegion region(outer, scalp, closed, 2);
    const FastWindingNumber hull_direct(outer), scalp_direct(scalp);
    int wrong = 0, fence = 0;
    compare({}, 20000, 0.0, 0.6,
            [&](const Vec3& p) { return region.inside_hull(p); },
            [&](const Vec3& p) { return closed ? hull_direct.direct(p) : hull_direct.direct(p) - scalp_direct.direct(p); },
            wrong, fence);
    CHECK(wrong == 0);
    if (!closed) CHECK(fence > 1000);
  }
}
