#include "pipeline/stage_codec.h"

namespace hairfit {

// A new member in one of these types must be added to its encode and decode below (and
// kStageCodecVersion bumped); these sizes make the compiler say so instead of the cache silently
// dropping the member. Update the number once the codec handles it.
static_assert(sizeof(ScalpChart) == 320, "ScalpChart changed: update stage_codec.cpp");
static_assert(sizeof(RootSet) == 168, "RootSet changed: update stage_codec.cpp");
static_assert(sizeof(Roots) == 192, "Roots changed: update stage_codec.cpp");
static_assert(sizeof(Clusters) == 288, "Clusters changed: update stage_codec.cpp");
static_assert(sizeof(PreguideRoots) == 176, "PreguideRoots changed: update stage_codec.cpp");
static_assert(sizeof(PreGuide) == 240, "PreGuide changed: update stage_codec.cpp");
static_assert(sizeof(Guide) == 384, "Guide changed: update stage_codec.cpp");
static_assert(sizeof(Strands) == 128, "Strands changed: update stage_codec.cpp");
static_assert(sizeof(Curves) == 96, "Curves changed: update stage_codec.cpp");

// The private parts of the two values that only their builders may assemble.
struct StageCodecAccess {
  static void encode(ByteWriter& out, const DistanceField& f) {
    out.put(f.origin_);
    out.put(f.h_);
    out.put(f.dims_);
    out.put(f.band_cm_);
    out.put(f.band_voxels_);
    out.put(*f.fine_);
    out.put(f.coarse_factor_);
    out.put(f.coarse_dims_);
    out.put(*f.coarse_);
  }
  static DistanceField decode_field(ByteReader& in) {
    DistanceField f;
    in.get(f.origin_);
    in.get(f.h_);
    in.get(f.dims_);
    in.get(f.band_cm_);
    in.get(f.band_voxels_);
    std::vector<double> fine, coarse;
    in.get(fine);
    in.get(f.coarse_factor_);
    in.get(f.coarse_dims_);
    in.get(coarse);
    const Vec3i& d = f.dims_;
    const Vec3i& c = f.coarse_dims_;
    if (d.minCoeff() < 0 || c.minCoeff() < 0 || fine.size() != std::size_t(d.x()) * d.y() * d.z() ||
        coarse.size() != std::size_t(c.x()) * c.y() * c.z())
      throw CodecError("distance field grid sizes do not match their samples");
    f.fine_ = std::make_shared<const std::vector<double>>(std::move(fine));
    f.coarse_ = std::make_shared<const std::vector<double>>(std::move(coarse));
    return f;
  }
  static void encode(ByteWriter& out, const DensityGrid& g) {
    out.put(g.geometry_.origin);
    out.put(g.geometry_.voxel);
    out.put(g.geometry_.dims);
    out.put(*g.values_);
  }
  static DensityGrid decode_grid(ByteReader& in) {
    GridGeometry geometry;
    in.get(geometry.origin);
    in.get(geometry.voxel);
    in.get(geometry.dims);
    std::vector<double> values;
    in.get(values);
    if (geometry.dims.minCoeff() < 0 || std::int64_t(values.size()) != geometry.cell_count())
      throw CodecError("density grid size does not match its values");
    return DensityGrid(geometry, std::make_shared<const std::vector<double>>(std::move(values)));
  }
};

namespace {

void put(ByteWriter& out, const Mesh& m) {
  out.put(m.positions);
  out.put(m.triangles);
}
void get(ByteReader& in, Mesh& m) {
  in.get(m.positions);
  in.get(m.triangles);
}

void put(ByteWriter& out, const RootSet& r) {
  out.put<std::uint64_t>(r.where.size());
  for (const SurfacePoint& p : r.where) {
    out.put(p.triangle);
    out.put(p.barycentric);
  }
  out.put(r.positions);
  out.put(r.normals);
  out.put(r.directions);
  out.put(r.lengths);
  out.put(r.chart);
  out.put(r.heights);
}
void get(ByteReader& in, RootSet& r) {
  const auto n = in.get<std::uint64_t>();
  if (n > (1u << 30)) throw CodecError("root set holds an impossible length");
  r.where.resize(n);
  for (SurfacePoint& p : r.where) {
    in.get(p.triangle);
    in.get(p.barycentric);
  }
  in.get(r.positions);
  in.get(r.normals);
  in.get(r.directions);
  in.get(r.lengths);
  in.get(r.chart);
  in.get(r.heights);
}

void put(ByteWriter& out, const FibreShape& s) {
  out.put(s.nodes);
  out.put(s.tangents);
  out.put(s.darboux);
}
void get(ByteReader& in, FibreShape& s) {
  in.get(s.nodes);
  in.get(s.tangents);
  in.get(s.darboux);
}

void put(ByteWriter& out, const Curves& c) {
  out.put(c.points);
  out.put(c.offsets);
  out.put(c.guide);
  out.put(c.widths);
}
void get(ByteReader& in, Curves& c) {
  in.get(c.points);
  in.get(c.offsets);
  in.get(c.guide);
  in.get(c.widths);
  if (c.offsets.empty() || c.offsets.back() != c.points.size() || c.guide.size() != c.offsets.size() - 1)
    throw CodecError("curve offsets do not match their points");
}

}  // namespace

void encode(ByteWriter& out, const DistanceField& field) { StageCodecAccess::encode(out, field); }
DistanceField decode_distance_field(ByteReader& in) { return StageCodecAccess::decode_field(in); }
void encode(ByteWriter& out, const DensityGrid& grid) { StageCodecAccess::encode(out, grid); }
DensityGrid decode_density_grid(ByteReader& in) { return StageCodecAccess::decode_grid(in); }

void encode(ByteWriter& out, const ScalpChart& c) {
  put(out, c.mesh);
  out.put(c.chart);
  out.put(c.vertex_normals);
  out.put(c.boundary);
  out.put(c.boundary_triangles);
  out.put(c.outward);
  out.put(c.front);
  out.put(c.down);
  out.put(c.area);
  out.put(c.height_low);
  out.put(c.height_high);
  out.put(c.flipped_triangles);
  out.put(c.grid.cells);
  out.put(c.grid.cell_start);
  out.put(c.grid.cell_triangles);
  out.put(c.solver);
}
ScalpChart decode_scalp_chart(ByteReader& in) {
  ScalpChart c;
  get(in, c.mesh);
  in.get(c.chart);
  in.get(c.vertex_normals);
  in.get(c.boundary);
  in.get(c.boundary_triangles);
  in.get(c.outward);
  in.get(c.front);
  in.get(c.down);
  in.get(c.area);
  in.get(c.height_low);
  in.get(c.height_high);
  in.get(c.flipped_triangles);
  in.get(c.grid.cells);
  in.get(c.grid.cell_start);
  in.get(c.grid.cell_triangles);
  in.get(c.solver);
  return c;
}

void encode(ByteWriter& out, const Roots& r) {
  put(out, r.pores);
  out.put(r.expected_count);
  out.put(r.hair_area);
  out.put(r.candidates);
}
Roots decode_roots(ByteReader& in) {
  Roots r;
  get(in, r.pores);
  in.get(r.expected_count);
  in.get(r.hair_area);
  in.get(r.candidates);
  return r;
}

void encode(ByteWriter& out, const Clusters& c) {
  put(out, c.bases);
  out.put(c.centre_pore);
  out.put(c.radius);
  out.put(c.pore_cluster);
  out.put(c.members);
  out.put(c.candidate_clusters);
}
Clusters decode_clusters(ByteReader& in) {
  Clusters c;
  get(in, c.bases);
  in.get(c.centre_pore);
  in.get(c.radius);
  in.get(c.pore_cluster);
  in.get(c.members);
  in.get(c.candidate_clusters);
  return c;
}

void encode(ByteWriter& out, const PreguideRoots& r) {
  put(out, r.roots);
  out.put(r.spacing);
}
PreguideRoots decode_preguide_roots(ByteReader& in) {
  PreguideRoots r;
  get(in, r.roots);
  in.get(r.spacing);
  return r;
}

void encode(ByteWriter& out, const PreGuides& p) {
  out.put<std::uint64_t>(p.items.size());
  for (const PreGuide& g : p.items) {
    out.put(g.root);
    out.put(g.normal);
    out.put(g.direction);
    out.put(g.length);
    out.put(g.height);
    out.put(g.force);
    out.put(g.root_moment);
    put(out, g.shape);
    out.put(g.thickness);
    out.put(g.target_depth);
    out.put(g.depth);
    out.put(g.reached);
    out.put(g.solves);
  }
}
PreGuides decode_preguides(ByteReader& in) {
  PreGuides p;
  const auto n = in.get<std::uint64_t>();
  if (n > (1u << 30)) throw CodecError("pre-guides hold an impossible length");
  p.items.resize(n);
  for (PreGuide& g : p.items) {
    in.get(g.root);
    in.get(g.normal);
    in.get(g.direction);
    in.get(g.length);
    in.get(g.height);
    in.get(g.force);
    in.get(g.root_moment);
    get(in, g.shape);
    in.get(g.thickness);
    in.get(g.target_depth);
    in.get(g.depth);
    in.get(g.reached);
    in.get(g.solves);
  }
  return p;
}

void encode(ByteWriter& out, const Guides& guides) {
  out.put<std::uint64_t>(guides.items.size());
  for (const Guide& g : guides.items) {
    out.put(g.root);
    out.put(g.normal);
    out.put(g.direction);
    out.put(g.length);
    out.put(g.force);
    out.put(g.root_moment);
    out.put(g.terminal_torque);
    out.put(g.force_scale);
    out.put(g.moment_scale);
    put(out, g.shape);
    out.put(g.neighbours);
    out.put(g.neighbour_weights);
    out.put(g.iterations);
    out.put(g.evaluations);
    out.put(g.converged);
    out.put(g.termination);
    out.put(g.initial_cost);
    out.put(g.cost);
    out.put(g.f1);
    out.put(g.f2);
    out.put(g.f3);
    out.put(g.f4);
  }
}
Guides decode_guides(ByteReader& in) {
  Guides guides;
  const auto n = in.get<std::uint64_t>();
  if (n > (1u << 30)) throw CodecError("guides hold an impossible length");
  guides.items.resize(n);
  for (Guide& g : guides.items) {
    in.get(g.root);
    in.get(g.normal);
    in.get(g.direction);
    in.get(g.length);
    in.get(g.force);
    in.get(g.root_moment);
    in.get(g.terminal_torque);
    in.get(g.force_scale);
    in.get(g.moment_scale);
    get(in, g.shape);
    in.get(g.neighbours);
    in.get(g.neighbour_weights);
    in.get(g.iterations);
    in.get(g.evaluations);
    in.get(g.converged);
    in.get(g.termination);
    in.get(g.initial_cost);
    in.get(g.cost);
    in.get(g.f1);
    in.get(g.f2);
    in.get(g.f3);
    in.get(g.f4);
  }
  return guides;
}

void encode(ByteWriter& out, const Strands& s) {
  put(out, s.fibres);
  out.put(s.cut);
  out.put(s.cut_count);
}
Strands decode_strands(ByteReader& in) {
  Strands s;
  get(in, s.fibres);
  in.get(s.cut);
  in.get(s.cut_count);
  return s;
}

}  // namespace hairfit
