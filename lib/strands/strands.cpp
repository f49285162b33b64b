#include "strands/strands.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/parallel.h"
#include "strands/guide_track.h"

namespace hairfit {

namespace {

double smoothstep(double e0, double e1, double x) {
  const double t = std::clamp((x - e0) / (e1 - e0), 0.0, 1.0);
  return t * t * (3.0 - 2.0 * t);
}

// Share of the fibre over which it moves from its pore's own offset to its place in the wisp.
constexpr double kSettle = 0.2;

struct FibreLayout {
  double a, b, c;  // pore offset from the guide root in the root frame (d1, d2, t)
  double u1, u2;   // its place in the wisp's unit disk
};

// Where point i of a fibre sits relative to the guide: t_i = i/(n−1) along the reach, and its
// offsets along the frame (d1, d2) and the root tangent. None of these depend on the reach, so
// they are computed once per fibre rather than in every step of the length solve (the cos/sin of
// the winding used to dominate it); the values are the same expressions as before, bit for bit.
struct SweepPoint {
  double t;        // i/(n−1)
  double along_d1, along_d2, along_root_tangent;
};

std::vector<SweepPoint> sweep_points(const FibreLayout& f, const StrandOptions& o, int n) {
  std::vector<SweepPoint> out(n);
  for (int i = 0; i < n; ++i) {
    const double t = static_cast<double>(i) / (n - 1);
    const double w = smoothstep(0.0, kSettle, t);
    const double radius = o.root_radius + (o.tip_radius - o.root_radius) * t;
    const double x = (1.0 - w) * f.a + w * f.u1 * radius;
    const double y = (1.0 - w) * f.b + w * f.u2 * radius;
    const double angle = 2.0 * M_PI * o.turns * t;
    const double ca = std::cos(angle), sa = std::sin(angle);
    out[i] = {t, ca * x - sa * y, sa * x + ca * y, (1.0 - w) * f.c};
  }
  return out;
}

// The guide's position and frame at its root (arc length 0).
struct RootFrame {
  Vec3 position, tangent, d1, d2;
};

// Points of a fibre that runs along the guide up to arc length `reach`. Arc length 0 (the first
// point, and every point of the solve's first, zero-reach sweep) takes the root frame found once
// per fibre instead of asking the track again.
void sweep(const GuideTrack& track, const std::vector<SweepPoint>& layout, const RootFrame& root, double reach,
           std::vector<Vec3>& out) {
  const int n = static_cast<int>(out.size());
  std::size_t segment = 0;  // arc lengths reach·t_i only grow along the fibre
  for (int i = 0; i < n; ++i) {
    const SweepPoint& q = layout[i];
    const double s = reach * q.t;
    Vec3 g = root.position, tangent = root.tangent, d1 = root.d1, d2 = root.d2;
    if (s != 0.0) track.at(s, g, tangent, d1, d2, segment);
    out[i] = g + q.along_d1 * d1 + q.along_d2 * d2 + q.along_root_tangent * root.tangent;
  }
}

double polyline_length(const std::vector<Vec3>& p) {
  double length = 0.0;
  for (std::size_t i = 1; i < p.size(); ++i) length += (p[i] - p[i - 1]).norm();
  return length;
}

// The fibre of exactly `length` along the track; with `out_of_head`, every point but the root is
// passed through it inside the length solve, so the moved fibre still has exactly its length.
std::vector<Vec3> fibre_along(const GuideTrack& track, const Vec3& pore, double length, double wisp_extent,
                              const StrandOptions& o, const HeadExit* out_of_head = nullptr) {
  RootFrame root;
  track.at(0.0, root.position, root.tangent, root.d1, root.d2);
  const Vec3& t0 = root.tangent;
  const Vec3 delta = pore - root.position;
  FibreLayout f{delta.dot(root.d1), delta.dot(root.d2), delta.dot(t0), 0.0, 0.0};
  if (wisp_extent > 0.0) {
    f.u1 = f.a / wisp_extent;
    f.u2 = f.b / wisp_extent;
  }
  std::vector<Vec3> points(std::max(2, o.points));
  const std::vector<SweepPoint> layout = sweep_points(f, o, static_cast<int>(points.size()));
  // The polyline's length grows with how far along the guide it reaches; find the reach that
  // gives exactly `length` by the Illinois variant of regula falsi on a bracket.
  auto excess = [&](double reach) {
    sweep(track, layout, root, reach, points);
    double unused;
    if (out_of_head)
      for (std::size_t i = 1; i < points.size(); ++i) points[i] = (*out_of_head)(points[i], unused);
    return polyline_length(points) - length;
  };
  double lo = 0.0, f_lo = excess(lo);
  if (f_lo >= 0.0) {  // too short for its own wisp offsets: a straight fibre along the root tangent
    for (std::size_t i = 0; i < points.size(); ++i)
      points[i] = pore + length * static_cast<double>(i) / (points.size() - 1) * t0;
    return points;
  }
  double hi = length, f_hi = excess(hi);
  while (f_hi < 0.0) {
    lo = hi, f_lo = f_hi;
    hi *= 2.0;
    f_hi = excess(hi);
  }
  int side = 0;
  for (int iteration = 0; iteration < 100; ++iteration) {
    const double mid = (lo * f_hi - hi * f_lo) / (f_hi - f_lo);
    const double f_mid = excess(mid);
    if (std::fabs(f_mid) <= 1e-12 * length || hi - lo <= 1e-15 * length) break;
    if ((f_mid < 0.0) == (f_lo < 0.0)) {
      lo = mid, f_lo = f_mid;
      if (side == -1) f_hi *= 0.5;
      side = -1;
    } else {
      hi = mid, f_hi = f_mid;
      if (side == 1) f_lo *= 0.5;
      side = 1;
    }
  }
  points[0] = pore;  // exactly, not up to round-off
  return points;
}

// fibre_along, with the points behind the scalp moved out when `out_of_head` is given. Most
// fibres never enter the head; only those that do pay for field lookups inside the length solve.
// `scalp` (if given) receives what out_of_head reported at each point of the result (NaN at the
// root and throughout a moved fibre).
std::vector<Vec3> fibre_kept_out(const GuideTrack& track, const Vec3& pore, double length, double wisp_extent,
                                 const StrandOptions& o, const HeadExit& out_of_head, std::vector<double>* scalp = nullptr) {
  std::vector<Vec3> fibre = fibre_along(track, pore, length, wisp_extent, o);
  if (!out_of_head) return fibre;
  std::vector<double> values(fibre.size(), std::numeric_limits<double>::quiet_NaN());
  for (std::size_t i = 1; i < fibre.size(); ++i)
    if (out_of_head(fibre[i], values[i]) != fibre[i]) {
      fibre = fibre_along(track, pore, length, wisp_extent, o, &out_of_head);
      values.assign(fibre.size(), std::numeric_limits<double>::quiet_NaN());
      break;
    }
  if (scalp) *scalp = std::move(values);
  return fibre;
}

}  // namespace

std::vector<Vec3> make_fibre(const std::vector<Vec3>& guide, const Vec3& pore, double length, double wisp_extent,
                             const StrandOptions& options, const HeadExit& out_of_head) {
  return fibre_kept_out(GuideTrack(guide), pore, length, wisp_extent, options, out_of_head);
}

std::vector<Vec3> make_fibre(const GuideTrack& guide, const Vec3& pore, double length, double wisp_extent,
                             const StrandOptions& options, const HeadExit& out_of_head) {
  return fibre_kept_out(guide, pore, length, wisp_extent, options, out_of_head);
}

Strands make_strands(const Curves& guides, const Pores& pores, const StrandOptions& options, const DistanceFunction& volume,
                     const HeadExit& out_of_head, FibreFieldValues* values) {
  const int guide_count = static_cast<int>(guides.count());
  std::vector<GuideTrack> tracks;
  tracks.reserve(guide_count);
  for (int g = 0; g < guide_count; ++g)
    tracks.emplace_back(std::vector<Vec3>(guides.points.begin() + guides.offsets[g], guides.points.begin() + guides.offsets[g + 1]));

  // A wisp's extent is the largest in-plane distance of its pores from the guide root.
  std::vector<RootFrame> roots(guide_count);
  for (int g = 0; g < guide_count; ++g) tracks[g].at(0.0, roots[g].position, roots[g].tangent, roots[g].d1, roots[g].d2);
  std::vector<double> extent(guide_count, 0.0);
  for (std::size_t i = 0; i < pores.positions.size(); ++i) {
    const RootFrame& root = roots[pores.guide[i]];
    const Vec3 delta = pores.positions[i] - root.position;
    extent[pores.guide[i]] = std::max(extent[pores.guide[i]], std::hypot(delta.dot(root.d1), delta.dot(root.d2)));
  }

  const int count = static_cast<int>(pores.positions.size());
  const bool cutting = options.cutting && volume;
  std::vector<std::vector<Vec3>> fibres(count);
  std::vector<std::vector<double>> distances(cutting && values ? count : 0);
  std::vector<std::vector<double>> scalp(out_of_head && values ? count : 0);
  std::vector<char> cut(count, 0);
  ProgressCounter progress(options.progress);
  parallel_for(count, options.threads, [&](int i) {
    std::vector<Vec3> fibre = fibre_kept_out(tracks[pores.guide[i]], pores.positions[i], pores.lengths[i],
                                             extent[pores.guide[i]], options, out_of_head, scalp.empty() ? nullptr : &scalp[i]);
    if (cutting) {
      CutResult r = cut_at_exit(fibre, volume, options.cut_threshold);
      cut[i] = r.cut;
      if (!scalp.empty()) {  // a value holds where the kept point is the point it was asked about
        scalp[i].resize(r.points.size(), std::numeric_limits<double>::quiet_NaN());
        for (std::size_t k = 0; k < r.points.size(); ++k)
          if (k >= fibre.size() || r.points[k] != fibre[k]) scalp[i][k] = std::numeric_limits<double>::quiet_NaN();
      }
      fibre = std::move(r.points);
      if (!distances.empty()) distances[i] = std::move(r.distances);
    }
    fibres[i] = std::move(fibre);
    progress.item_done();
  });

  // The fibres laid end to end in pore order, each copied on its own thread.
  Strands strands;
  Curves& out = strands.fibres;
  out.offsets.resize(count + 1);
  for (int i = 0; i < count; ++i) out.offsets[i + 1] = out.offsets[i] + static_cast<std::uint32_t>(fibres[i].size());
  out.points.resize(out.offsets[count]);
  out.guide.assign(pores.guide.begin(), pores.guide.end());
  if (values) {
    values->volume.assign(distances.empty() ? 0 : out.points.size(), 0.0);
    values->scalp.assign(scalp.empty() ? 0 : out.points.size(), 0.0);
  }
  parallel_for(count, options.threads, [&](int i) {
    std::copy(fibres[i].begin(), fibres[i].end(), out.points.begin() + out.offsets[i]);
    if (!distances.empty()) std::copy(distances[i].begin(), distances[i].end(), values->volume.begin() + out.offsets[i]);
    if (!scalp.empty()) std::copy(scalp[i].begin(), scalp[i].end(), values->scalp.begin() + out.offsets[i]);
  });
  for (int i = 0; i < count; ++i) strands.cut_count += cut[i];
  strands.cut = std::move(cut);
  return strands;
}

}  // namespace hairfit
