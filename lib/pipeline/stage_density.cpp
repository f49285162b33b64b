// The density stage (paper §3.5, Fig. 5–6; docs/design.md §6): what the final fibres' density
// looks like, measured the same way for every model (a CDM deposit of the final, cut fibres) so
// models can be compared. It runs after strands because the fibres exist only then, and exists
// only when the scene declares a density model.
#include "core/parallel.h"
#include "density/accumulator.h"
#include "io/atomic_file.h"
#include "pipeline/stage.h"
#include "pipeline/stage_codec.h"
#include "pipeline/stage_options.h"

namespace hairfit {

namespace {

// The model the scene declares (a figure: every model is measured the same way) and the grid.
struct DensityOptions {
  DensityModel model = DensityModel::none;
  DensityGridSpec grid;
};

void encode(ByteWriter& out, const DensityOptions& o) {
  out.put(o.model);
  encode(out, o.grid);
}

void compute(StageRun& run, const DensityOptions& o, StageReport& stage) {
  const int threads = run.options.threads;
  StageValues& v = run.values;
  const GridGeometry grid = density_geometry(o.grid, run.inputs.volume.mesh);
  DensityAccumulator accumulator(grid);
  std::vector<std::int32_t> segment_counts;  // the histogram's, from the deposit's traversal
  accumulator.add_fibres(v.strands->fibres, threads, &segment_counts);
  v.fibre_density = std::make_shared<const DensityGrid>(std::move(accumulator).freeze());
  // The digest (one serial chain over the grid) beside the region test and the files.
  const std::vector<double>& values = v.fibre_density->values();
  run.digest = std::async(std::launch::async, [&values] {
    return Digest().add_bytes(values.data(), values.size() * sizeof(double)).hex();
  });
  // Boundary::acceptable(p) at every cell centre (beyond_volume(p) = volume(p) ≤ 0 and
  // beyond_scalp(p) = −scalp(p) ≤ 0): where a field's lookup cell settles the sign
  // (sides_on_lattice, per-axis tables), no value is interpolated; elsewhere it is, at the same
  // centre (GridGeometry::cell_centre, coordinate by coordinate).
  const DistanceField& volume = *v.volume_field;
  const DistanceField& scalp = *v.scalp_field;
  const GridGeometry& g = v.fibre_density->geometry();
  std::vector<double> centres[3];
  for (int d = 0; d < 3; ++d)
    for (int n = 0; n < g.dims[d]; ++n) centres[d].push_back(g.origin[d] + g.voxel * (n + 0.5));
  const std::vector<std::int8_t> volume_sides = volume.sides_on_lattice(centres[0], centres[1], centres[2], threads);
  const std::vector<std::int8_t> scalp_sides = scalp.sides_on_lattice(centres[0], centres[1], centres[2], threads);
  std::vector<char> in_region(static_cast<std::size_t>(g.count()), 0);
  parallel_for(g.dims.z(), threads, [&](int k) {
    for (int j = 0; j < g.dims.y(); ++j)
      for (int i = 0; i < g.dims.x(); ++i) {
        const std::int64_t c = g.index(i, j, k);
        const int in_volume = volume_sides[c], in_front = scalp_sides[c];
        if (in_volume > 0 || in_front < 0) continue;
        const Vec3 p = g.cell_centre(i, j, k);
        if (in_volume == 0 && !(volume.value(p) <= 0.0)) continue;
        in_region[c] = in_front > 0 || -scalp.value(p) <= 0.0;
      }
  });
  const DensityStatistics s = density_statistics(*v.fibre_density, in_region);
  stage.add("model", o.model == DensityModel::binary ? std::string("binary") : std::string("continuous"));
  stage.add("voxel_cm", grid.voxel);
  stage.add("grid", std::to_string(grid.dims.x()) + "x" + std::to_string(grid.dims.y()) + "x" + std::to_string(grid.dims.z()));
  stage.add("region_cells", s.region_cells);
  stage.add("occupied_cells", s.occupied_cells);
  stage.add("mean_density", s.mean);
  stage.add("coefficient_of_variation", s.coefficient_of_variation);
  stage.add("empty_share", s.empty_share);
  run.histogram = histogram_of_counts(segment_counts);
  stage.add("max_segments_per_cell",
            static_cast<std::int64_t>(run.histogram->cells_with.empty() ? 0 : run.histogram->cells_with.size() - 1));
}

void encode_value(ByteWriter& out, const StageValues& v) { encode(out, *v.fibre_density); }
void decode_value(ByteReader& in, StageValues& v) {
  v.fibre_density = std::make_shared<const DensityGrid>(decode_density_grid(in));
}

ConfiguredStage configure(const Scene& scene) {
  ConfiguredStage c = configured(DensityOptions{scene.effects.density, density_grid_spec(scene)}, compute);
  c.files = {"volume"};
  c.consumes = {"fields", "strands"};
  c.cached = false;  // as the strands it is made from
  return c;
}

void write(StageRun& run, const Scene& scene) {
  if (!run.histogram)  // a cached stage: recomputed from the fibres rather than stored
    run.histogram = segment_histogram(run.values.fibre_density->geometry(),
                                                run.values.strands->fibres, run.options.threads);
  run.output("density/histogram.csv",
             [&](const std::filesystem::path& p) { write_text_file_atomically(p, histogram_csv(*run.histogram)); });
  // Centre sagittal slice (Fig. 6): normal = the head's left–right axis = front × up.
  const Vec3 up = -scene.units.down;
  const Vec3 left_right = scene.units.front.cross(up);
  run.output("density/sagittal.nrrd", [&](const std::filesystem::path& p) {
    write_nrrd(p, run.in_scene_frame(slice_to_nrrd(centre_slice(*run.values.fibre_density, left_right, up))));
  });
}

}  // namespace

const StageDescriptor& density_stage() {
  static const StageDescriptor d{"density", 1, density_declared, configure, nullptr, encode_value, decode_value, write};
  return d;
}

}  // namespace hairfit
