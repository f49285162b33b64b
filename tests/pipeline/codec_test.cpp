// The stage codec (pipeline/stage_codec.h): every stage value survives encode → decode bit for bit,
// and anything that is not exactly one encoded value is refused.
#include <doctest/doctest.h>

#include "density/accumulator.h"
#include "pipeline/pipeline.h"
#include "pipeline/stage_codec.h"
#include "../support/run_hairfit.h"

using namespace hairfit;
using hairfit::testing::source_path;

namespace {

// The smoke fixture with the continuous density model, so that both density grids exist too.
const PipelineResult& smoke() {
  static const PipelineResult result = [] {
    Scene scene = parse_scene(source_path("fixtures/smoke/scene.toml"));
    scene.effects.density = DensityModel::continuous;
    scene.guides.weights = SceneWeights{0.3, 0.2, 0.3, 0.2};
    scene.density.batch = 8;
    static const Inputs inputs = load_inputs(scene);
    RunOptions o;
    o.threads = 2;
    o.write_outputs = false;
    return run_pipeline(scene, inputs, o);
  }();
  return result;
}

// Encodes, decodes and encodes again: the two encodings must be the same bytes, and the decoded
// value is returned for checks against the original.
template <class T, class Decode>
T round_trip(const T& value, Decode decode) {
  const std::string bytes = encode_value(value);
  REQUIRE(!bytes.empty());
  T back = decode_value<T>(bytes, decode);
  CHECK(encode_value(back) == bytes);
  // Any shorter or longer byte string is refused.
  CHECK_THROWS_AS(decode_value<T>(std::string_view(bytes).substr(0, bytes.size() - 1), decode), CodecError);
  CHECK_THROWS_AS(decode_value<T>(bytes + '\0', decode), CodecError);
  return back;
}

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

}  // namespace

TEST_CASE("distance fields round-trip: every sample and every query the same bits") {
  const DistanceField& field = *smoke().values.volume_field;
  const DistanceField back = round_trip(field, decode_distance_field);
  CHECK(back.dims() == field.dims());
  CHECK(back.origin() == field.origin());
  CHECK(back.band_voxels() == field.band_voxels());
  CHECK(back.memory_bytes() == field.memory_bytes());
  bool samples = true;
  for (int k = 0; k < field.dims().z(); ++k)
    for (int j = 0; j < field.dims().y(); ++j)
      for (int i = 0; i < field.dims().x(); ++i)
        samples = samples && same_bits(back.sample(i, j, k), field.sample(i, j, k)) && back.in_band(i, j, k) == field.in_band(i, j, k);
  CHECK(samples);
  // Queries inside, outside and far beyond the grid (the coarse far field and the clamping).
  for (const Vec3& p : {Vec3(0.3, 1.7, -2.2), Vec3(40, -35, 12), Vec3(-500, 3, 900)}) {
    const FieldValueGradient a = field.value_and_gradient(p), b = back.value_and_gradient(p);
    CHECK(same_bits(a.value, b.value));
    CHECK(a.gradient == b.gradient);
  }
}

TEST_CASE("charts, roots, clusters and pre-guide roots round-trip (their digests cover every member)") {
  const StageValues& v = smoke().values;
  const ScalpChart chart = round_trip(*v.chart, decode_scalp_chart);
  CHECK(digest(chart).hex() == digest(*v.chart).hex());
  CHECK(chart.solver == v.chart->solver);
  CHECK(chart.grid.cell_triangles == v.chart->grid.cell_triangles);
  const Roots roots = round_trip(*v.roots, decode_roots);
  CHECK(digest(roots).hex() == digest(*v.roots).hex());
  CHECK(roots.candidates == v.roots->candidates);
  const Clusters clusters = round_trip(*v.clusters, decode_clusters);
  CHECK(digest(clusters).hex() == digest(*v.clusters).hex());
  CHECK(clusters.members == v.clusters->members);
  const PreguideRoots preguide_roots = round_trip(*v.preguide_roots, decode_preguide_roots);
  CHECK(digest(preguide_roots).hex() == digest(*v.preguide_roots).hex());
}

TEST_CASE("pre-guides and guides round-trip, solver records included") {
  const StageValues& v = smoke().values;
  const PreGuides preguides = round_trip(*v.preguides, decode_preguides);
  CHECK(digest(preguides).hex() == digest(*v.preguides).hex());
  REQUIRE(preguides.size() == v.preguides->size());
  for (int i = 0; i < preguides.size(); ++i) CHECK(preguides.items[i].solves == v.preguides->items[i].solves);
  const Guides guides = round_trip(*v.guides, decode_guides);
  CHECK(digest(guides).hex() == digest(*v.guides).hex());
  REQUIRE(guides.size() == v.guides->size());
  for (int i = 0; i < guides.size(); ++i) {
    CHECK(guides.items[i].termination == v.guides->items[i].termination);
    CHECK(same_bits(guides.items[i].f4, v.guides->items[i].f4));
    CHECK(guides.items[i].neighbours == v.guides->items[i].neighbours);
  }
}

TEST_CASE("strands and density grids round-trip") {
  const StageValues& v = smoke().values;
  const Strands strands = round_trip(*v.strands, decode_strands);
  CHECK(strands.fibres.points == v.strands->fibres.points);
  CHECK(strands.fibres.widths == v.strands->fibres.widths);
  CHECK(strands.fibres.guide == v.strands->fibres.guide);
  CHECK(strands.cut == v.strands->cut);
  CHECK(strands.cut_count == v.strands->cut_count);
  for (const std::shared_ptr<const DensityGrid>& grid : {v.guide_density, v.fibre_density}) {
    REQUIRE(grid);
    const DensityGrid back = round_trip(*grid, decode_density_grid);
    CHECK(back.values() == grid->values());
    CHECK(back.geometry().dims == grid->geometry().dims);
    CHECK(back.geometry().origin == grid->geometry().origin);
    const Vec3 p = grid->geometry().cell_centre(3, 4, 5) + Vec3(0.01, 0.02, 0.03);
    CHECK(same_bits(back.value(p), grid->value(p)));
  }
}

TEST_CASE("a payload claiming more elements than it holds is refused before allocating") {
  ByteWriter out;
  out.put<std::uint64_t>(std::uint64_t(1) << 40);  // a vector of 2^40 doubles, with no bytes behind
  CHECK_THROWS_AS(decode_value<Strands>(out.bytes(), decode_strands), CodecError);
  CHECK_THROWS_AS(decode_value<Guides>(out.bytes(), decode_guides), CodecError);
  CHECK_THROWS_AS(decode_value<DensityGrid>(std::string(), decode_density_grid), CodecError);
}

TEST_CASE("empty vectors and strings round-trip (memcpy never sees the null data() of an empty vector)") {
  ByteWriter out;
  out.put(std::vector<double>{});
  out.put(std::string());
  out.put(std::vector<Vec3>{});
  out.put(std::vector<int>{7});
  ByteReader in(out.bytes());
  std::vector<double> doubles{1.0};
  std::string text = "x";
  std::vector<Vec3> points{Vec3(1, 2, 3)};
  std::vector<int> ints;
  in.get(doubles);
  in.get(text);
  in.get(points);
  in.get(ints);
  CHECK(doubles.empty());
  CHECK(text.empty());
  CHECK(points.empty());
  CHECK(ints == std::vector<int>{7});
  CHECK_NOTHROW(in.expect_end());
}
