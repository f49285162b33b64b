#include "pipeline/stage_codec.h"

#include <stdexcept>

namespace hairfit {

// A new member in one of these types must be added to its member list below (and
// kStageCodecVersion bumped); these sizes make the compiler say so instead of the cache silently
// dropping the member. Update the number once the codec handles it.
static_assert(sizeof(ScalpChart) == 320, "ScalpChart changed: update stage_codec.cpp");
static_assert(sizeof(RootSet) == 192, "RootSet changed: update stage_codec.cpp");
static_assert(sizeof(Roots) == 216, "Roots changed: update stage_codec.cpp");
static_assert(sizeof(Clusters) == 312, "Clusters changed: update stage_codec.cpp");
static_assert(sizeof(PreguideRoots) == 200, "PreguideRoots changed: update stage_codec.cpp");
static_assert(sizeof(PreGuide) == 248, "PreGuide changed: update stage_codec.cpp");
static_assert(sizeof(Guide) == 432, "Guide changed: update stage_codec.cpp");
static_assert(sizeof(Strands) == 136, "Strands changed: update stage_codec.cpp");
static_assert(sizeof(Curves) == 96, "Curves changed: update stage_codec.cpp");

namespace {

// One list of members per type serves both directions, so encoding and decoding cannot drift
// apart: `io` is an Encoder (writes each member) or a Decoder (reads it back in place).
struct Encoder {
  ByteWriter& out;
  template <class T>
  void operator()(const T& x) { out.put(x); }
  template <class T>
  void items(std::vector<T>& xs) {
    out.put<std::uint64_t>(xs.size());
    for (T& x : xs) members(*this, x);
  }
};

struct Decoder {
  ByteReader& in;
  template <class T>
  void operator()(T& x) { in.get(x); }
  template <class T>
  void items(std::vector<T>& xs) {
    const auto n = in.get<std::uint64_t>();
    if (n > in.remaining()) throw CodecError("cache payload holds an impossible length");  // each item takes bytes
    xs.resize(n);
    for (T& x : xs) members(*this, x);
  }
};

template <class IO>
void members(IO& io, SurfacePoint& p) {
  io(p.triangle);
  io(p.barycentric);
}

template <class IO>
void members(IO& io, Mesh& m) {
  io(m.positions);
  io(m.triangles);
}

template <class IO>
void members(IO& io, RootSet& r) {
  io.items(r.where);
  io(r.positions);
  io(r.normals);
  io(r.directions);
  io(r.lengths);
  io(r.chart);
  io(r.heights);
  io(r.hang_weights);
}

template <class IO>
void members(IO& io, FibreShape& s) {
  io(s.nodes);
  io(s.tangents);
  io(s.darboux);
}

template <class IO>
void members(IO& io, Curves& c) {
  io(c.points);
  io(c.offsets);
  io(c.guide);
  io(c.widths);
}

template <class IO>
void members(IO& io, ScalpChart& c) {
  members(io, c.mesh);
  io(c.chart);
  io(c.vertex_normals);
  io(c.boundary);
  io(c.boundary_triangles);
  io(c.outward);
  io(c.front);
  io(c.down);
  io(c.area);
  io(c.height_low);
  io(c.height_high);
  io(c.flipped_triangles);
  io(c.grid.cells);
  io(c.grid.cell_start);
  io(c.grid.cell_triangles);
  io(c.solver);
}

template <class IO>
void members(IO& io, Roots& r) {
  members(io, r.pores);
  io(r.expected_count);
  io(r.hair_area);
  io(r.candidates);
}

template <class IO>
void members(IO& io, Clusters& c) {
  members(io, c.bases);
  io(c.centre_pore);
  io(c.radius);
  io(c.pore_cluster);
  io(c.members);
  io(c.candidate_clusters);
}

template <class IO>
void members(IO& io, PreguideRoots& r) {
  members(io, r.roots);
  io(r.spacing);
}

template <class IO>
void members(IO& io, PreGuide& g) {
  io(g.root);
  io(g.normal);
  io(g.direction);
  io(g.length);
  io(g.height);
  io(g.force);
  io(g.root_moment);
  members(io, g.shape);
  io(g.thickness);
  io(g.target_depth);
  io(g.depth);
  io(g.reached);
  io(g.solves);
  io(g.weight_share);
}

template <class IO>
void members(IO& io, PreGuides& p) {
  io.items(p.items);
  io(p.shared_solves);
}

template <class IO>
void members(IO& io, Guide& g) {
  io(g.root);
  io(g.normal);
  io(g.direction);
  io(g.length);
  io(g.force);
  io(g.root_moment);
  io(g.terminal_torque);
  io(g.point_forces);
  io(g.force_scale);
  io(g.moment_scale);
  members(io, g.shape);
  io(g.neighbours);
  io(g.neighbour_weights);
  io(g.iterations);
  io(g.evaluations);
  io(g.converged);
  io(g.termination);
  io(g.initial_cost);
  io(g.cost);
  io(g.f1);
  io(g.f2);
  io(g.f3);
  io(g.f4);
  io(g.f5);
  io(g.contact_force);
  io(g.contact_share);
}

template <class IO>
void members(IO& io, Guides& g) {
  io.items(g.items);
}

template <class IO>
void members(IO& io, Strands& s) {
  members(io, s.fibres);
  io(s.cut);
  io(s.cut_count);
  io(s.cut_at_scalp);
  io(s.scalp_crossings);
}

// The encoders only read the value; the member lists take it by non-const reference to serve both.
template <class T>
void encode_members(ByteWriter& out, const T& value) {
  Encoder io{out};
  members(io, const_cast<T&>(value));
}

template <class T>
T decode_members(ByteReader& in) {
  T value;
  Decoder io{in};
  members(io, value);
  return value;
}

void check_curves(const Curves& c) {
  if (c.offsets.empty() || c.offsets.back() != c.points.size() || c.guide.size() != c.offsets.size() - 1)
    throw CodecError("curve offsets do not match their points");
}

}  // namespace

void encode(ByteWriter& out, const DistanceField& f) {
  out.put(f.origin());
  out.put(f.voxel());
  out.put(f.dims());
  out.put(f.band_width());
  out.put(f.band_voxels());
  out.put(f.samples());
  out.put(f.flags());
}

DistanceField decode_distance_field(ByteReader& in) {
  DistanceFieldParts parts;
  in.get(parts.origin);
  in.get(parts.voxel);
  in.get(parts.dims);
  in.get(parts.band_width);
  in.get(parts.band_voxels);
  in.get(parts.samples);
  in.get(parts.flags);
  try {
    return DistanceField::from_parts(std::move(parts));
  } catch (const std::invalid_argument& e) {
    throw CodecError(e.what());
  }
}

void encode(ByteWriter& out, const DensityGrid& grid) {
  out.put(grid.geometry().origin);
  out.put(grid.geometry().voxel);
  out.put(grid.geometry().dims);
  out.put(grid.values());
}

DensityGrid decode_density_grid(ByteReader& in) {
  GridGeometry geometry;
  in.get(geometry.origin);
  in.get(geometry.voxel);
  in.get(geometry.dims);
  std::vector<double> values;
  in.get(values);
  try {
    return DensityGrid::from_values(geometry, std::move(values));
  } catch (const std::invalid_argument& e) {
    throw CodecError(e.what());
  }
}

void encode(ByteWriter& out, const ScalpChart& chart) { encode_members(out, chart); }
void encode(ByteWriter& out, const Roots& roots) { encode_members(out, roots); }
void encode(ByteWriter& out, const Clusters& clusters) { encode_members(out, clusters); }
void encode(ByteWriter& out, const PreguideRoots& roots) { encode_members(out, roots); }
void encode(ByteWriter& out, const PreGuides& preguides) { encode_members(out, preguides); }
void encode(ByteWriter& out, const Guides& guides) { encode_members(out, guides); }
void encode(ByteWriter& out, const Strands& strands) { encode_members(out, strands); }

ScalpChart decode_scalp_chart(ByteReader& in) { return decode_members<ScalpChart>(in); }
Roots decode_roots(ByteReader& in) { return decode_members<Roots>(in); }
Clusters decode_clusters(ByteReader& in) { return decode_members<Clusters>(in); }
PreguideRoots decode_preguide_roots(ByteReader& in) { return decode_members<PreguideRoots>(in); }
PreGuides decode_preguides(ByteReader& in) { return decode_members<PreGuides>(in); }
Guides decode_guides(ByteReader& in) { return decode_members<Guides>(in); }
Strands decode_strands(ByteReader& in) {
  Strands s = decode_members<Strands>(in);
  check_curves(s.fibres);
  return s;
}

}  // namespace hairfit
