// Hard numerical cases (issue 12): scenes at the edge of what the method can do. Each runs the
// whole pipeline on a tiny scene (8 guides, a few hundred fibres) and checks that every value is
// finite and that the trouble shows in the report's figures (failures, flagged pre-guides, the
// inside fractions, the guides' weight and length flags) instead of in NaN, a crash or a hang.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <string>

#include "../support/run_hairfit.h"
#include "pipeline/pipeline.h"

using namespace hairfit;
using hairfit::testing::source_path;

namespace {

// The smoke fixture, smaller still; `extra` adds keys (TOML tables may be repeated only once, so
// the base leaves out the tables the cases change: [fields], [hair], [guides], [effects], [density]).
const std::string kBase = R"(format = "hairfit-scene/1"
seed = 5
[inputs]
scalp = "../meshes/scalp.obj"
volume = "../meshes/spheroid_volume.obj"
[roots]
guides = 8
preguide_spacing = 4.0
[rod]
segments = 16
[strands]
points = 8
[output]
renders = []
)";

const std::string kHair = "[hair]\ndensity = 0.5\nlength = 12\n";

Scene scene_with(const std::string& extra, double voxel) {
  return parse_scene_text(kBase + "[fields]\nvoxel = " + std::to_string(voxel) + "\nband = 3\n" + extra,
                          source_path("fixtures/smoke/hard.toml"));
}

PipelineResult run(const std::string& extra, double voxel = 0.5) {
  const Scene scene = scene_with(extra, voxel);
  RunOptions options;
  options.threads = 2;
  options.write_outputs = false;
  return run_pipeline(scene, load_inputs(scene), options);
}

template <class T>
T figure(const PipelineResult& r, const std::string& stage, const std::string& key) {
  for (const StageReport& s : r.report.stages)
    if (s.name == stage)
      for (const auto& [name, value] : s.figures)
        if (name == key) return std::get<T>(value);
  FAIL("no figure " << stage << "." << key);
  return T{};
}

bool finite(const Vec3& v) { return v.allFinite(); }

// Every number the run produced: pre-guides, guides (shape and loads), fibres, report figures.
void check_all_finite(const PipelineResult& r) {
  const StageValues& v = r.values;
  REQUIRE(v.preguides);
  REQUIRE(v.guides);
  REQUIRE(v.strands);
  for (const PreGuide& p : v.preguides->items) {
    for (const Vec3& x : p.shape.nodes) REQUIRE(finite(x));
    REQUIRE(finite(p.force));
    REQUIRE(std::isfinite(p.depth));
  }
  for (const Guide& g : v.guides->items) {
    for (const Vec3& x : g.shape.nodes) REQUIRE(finite(x));
    REQUIRE(finite(g.force));
    REQUIRE(finite(g.root_moment));
    REQUIRE(finite(g.terminal_torque));
    REQUIRE(std::isfinite(g.cost));
  }
  REQUIRE(v.strands->fibres.count() > 0);
  for (const Vec3& x : v.strands->fibres.points) REQUIRE(finite(x));
  for (const StageReport& s : r.report.stages)
    for (const auto& [name, value] : s.figures)
      if (const double* d = std::get_if<double>(&value)) {
        INFO(s.name << "." << name);
        CHECK(std::isfinite(*d));
      }
}

}  // namespace

TEST_CASE("hard: the growth direction tangent to the scalp (tilt 90°)") {
  const PipelineResult r = run("[hair]\ndensity = 0.5\nlength = 12\ntilt = 90\n");
  check_all_finite(r);
  const RootSet& pores = r.values.roots->pores;
  for (int i = 0; i < pores.size(); ++i) CHECK(std::abs(pores.directions[i].dot(pores.normals[i])) < 1e-9);
  // Rods that start along the skin dip behind it: the report shows it.
  CHECK(figure<double>(r, "guides", "inside_head_fraction") > 0.0);
}

TEST_CASE("hard: guides whose straight start lies far outside the field's band") {
  // 60 cm hair in a volume a few cm thick, started straight along the growth direction: the start
  // reaches ~50 cm past the band of exact distances (1.5 cm), where only the far field answers.
  const PipelineResult r = run("[hair]\ndensity = 0.5\nlength = 60\n[guides]\nstart = \"straight\"\n");
  check_all_finite(r);
  CHECK(figure<std::int64_t>(r, "preguides", "flagged") == figure<std::int64_t>(r, "preguides", "preguides"));
  CHECK(figure<double>(r, "guides", "outside_volume_fraction") > 0.1);
}

TEST_CASE("hard: a volume thinner than a voxel in places") {
  // 3 cm voxels: near the hairline the hair layer is thinner than one voxel.
  const PipelineResult r = run(kHair, 3.0);
  check_all_finite(r);
  double thinnest = 1e9;
  for (const PreGuide& p : r.values.preguides->items) thinnest = std::min(thinnest, p.thickness);
  CHECK(thinnest < 3.0);  // the case is real
  CHECK(figure<std::int64_t>(r, "preguides", "flagged") > 0);
}

TEST_CASE("hard: a saturating density grid (BOM, 4 cm cells, threshold 0)") {
  // Every cell a wisp touches is occupied at once: the surcharge applies everywhere after the
  // first batch of 4 guides.
  const PipelineResult r = run(kHair +
                               "[effects]\ndensity = \"binary\"\n[guides.weights]\ndirection = 0.4\nsimilarity = 0.2\n"
                               "boundary = 0.3\ndensity = 0.1\n[density]\nvoxel = 4\nthreshold = 0\nbatch = 4\n");
  check_all_finite(r);
  CHECK(figure<std::int64_t>(r, "guides", "density_batches") == 2);
  CHECK(figure<double>(r, "guides", "mean_f4") > 0.0);
  for (double x : r.values.guide_density->values()) CHECK(std::isfinite(x));
}

// ρA|g|L³/EI computed here from the scene, independently of the rod code: EI = E·A²/(4π).
double expected_max_weight(const PipelineResult& r, const Scene& scene) {
  double longest = 0.0;
  for (const Guide& g : r.values.guides->items) longest = std::max(longest, g.length);
  const double a = scene.hair.cross_section;
  return scene.hair.mass_density * a * scene.rod.gravity * std::pow(longest, 3) /
         (scene.hair.youngs_modulus * a * a / (4.0 * M_PI));
}

TEST_CASE("hard: huge stiffness under gravity (E = 1e15 dyn/cm², the largest allowed)") {
  const std::string extra = "[hair]\ndensity = 0.5\nlength = 12\nyoungs_modulus = 1e15\n[effects]\ngravity = true\n";
  const PipelineResult r = run(extra);
  check_all_finite(r);
  for (const Guide& g : r.values.guides->items) {
    CHECK(std::isfinite(g.force_scale));  // EI/L²: the cgs loads stay finite too
    CHECK(finite(g.force * g.force_scale));
  }
  // The report shows that gravity no longer matters: w = ρA|g|L³/EI ≈ 2e-3 (real hair: ≈ 48).
  const double w = figure<double>(r, "guides", "max_weight");
  CHECK(w == doctest::Approx(expected_max_weight(r, scene_with(extra, 0.5))).epsilon(1e-12));
  CHECK(w < 1e-2);
  CHECK(figure<std::int64_t>(r, "guides", "unresolved_weight") == 0);
}

TEST_CASE("hard: tiny stiffness under gravity: finite up to the weight the integrator follows, refused beyond") {
  // E = 1e3 dyn/cm²: dimensionless weight ρAgL³/EI ≈ 1.9e9 for 12 cm (real hair: ≈ 48). The
  // rod's boundary layer (L/√w ≈ 3e-4 cm) is far below one of its 16 segments, so the shapes are
  // finite but not accurate; the fibres leave the volume, which the strands' inside fraction shows.
  const std::string extra = "[hair]\ndensity = 0.5\nlength = 12\nyoungs_modulus = 1e3\n[effects]\ngravity = true\n";
  const PipelineResult r = run(extra);
  check_all_finite(r);
  CHECK(figure<double>(r, "strands", "inside_fraction") < 0.9);
  // Flagged: every guide's bending layer L/√w is shorter than one of its 16 segments (w > 16²).
  CHECK(figure<double>(r, "guides", "max_weight") ==
        doctest::Approx(expected_max_weight(r, scene_with(extra, 0.5))).epsilon(1e-12));
  CHECK(figure<std::int64_t>(r, "guides", "unresolved_weight") == figure<std::int64_t>(r, "guides", "guides"));
  // E = 1e-6: weight ≈ 1.9e18; the integrator overflowed here (it crashed the run before the check).
  const Scene limp = scene_with("[hair]\ndensity = 0.5\nlength = 12\nyoungs_modulus = 1e-6\n[effects]\ngravity = true\n", 0.5);
  try {
    load_inputs(limp);
    FAIL("accepted");
  } catch (const InputError& e) {
    CHECK(std::string(e.what()).find("hard.toml:21:18: error: with effects.gravity, hair of 12 cm with "
                                     "hair.youngs_modulus = 1e-06 dyn/cm² has a dimensionless weight ρAgL³/EI = 1.87e+18, "
                                     "beyond the 1e+10 the rod integrator can follow") != std::string::npos);
  }
}

TEST_CASE("hard: rods of near-zero length (1e-6 cm)") {
  const PipelineResult r = run("[hair]\ndensity = 0.5\nlength = 1e-6\n");
  check_all_finite(r);
  for (const Vec3& p : r.values.strands->fibres.points) CHECK(std::isfinite(p.norm()));
  for (const Guide& g : r.values.guides->items)
    CHECK((g.shape.nodes.back() - g.root).norm() <= 1e-6 * (1 + 1e-9));  // never longer than the rod
  // Flagged: every guide is shorter than a voxel (0.5 cm), so the fields cannot shape it.
  CHECK(figure<std::int64_t>(r, "guides", "shorter_than_voxel") == figure<std::int64_t>(r, "guides", "guides"));
}

TEST_CASE("hard: Ceres stopped after one iteration: every guide flagged, all finite") {
  const PipelineResult r = run(kHair + "[guides]\nmax_iterations = 1\n");
  check_all_finite(r);
  CHECK(figure<std::int64_t>(r, "guides", "failures") == figure<std::int64_t>(r, "guides", "guides"));
  // One iteration per solve: the first, and the retry from the other start for a guide whose
  // first solve leaves the acceptable region (guides.cpp); iterations count both.
  const auto max_iterations = figure<std::int64_t>(r, "guides", "max_iterations");
  CHECK(max_iterations >= 1);
  CHECK(max_iterations <= 2);
  for (const Guide& g : r.values.guides->items) CHECK_FALSE(g.converged);
  // 12 cm hair without gravity in 0.5 cm voxels raises none of the other flags.
  CHECK(figure<double>(r, "guides", "max_weight") == 0.0);
  CHECK(figure<std::int64_t>(r, "guides", "unresolved_weight") == 0);
  CHECK(figure<std::int64_t>(r, "guides", "shorter_than_voxel") == 0);
}

// Long hair under gravity on the scalp as a support (issue: long hair). 60 cm of real hair
// weighs w ≈ 6000 in rod units; grown tangent to the scalp it lies on it from the root on; a
// support a million times too stiff makes the rod's equations stiffer than its segments resolve;
// and 60 cm of hair does not fit in the spheroid's volume. Each stays finite, and the report says
// what happened: the weight, the contact, the failures, the inside fractions.
TEST_CASE("hard: long hair under gravity on the scalp as a support") {
  struct Case {
    const char* name;
    std::string extra;
  };
  const Case cases[] = {
      {"w ≈ 6000 (60 cm), longer than the volume holds", "[hair]\ndensity = 0.5\nlength = 60\n"},
      {"growing tangent to the scalp, in contact from the root on", "[hair]\ndensity = 0.5\nlength = 30\ntilt = 90\n"},
      {"a support 1e6 times too stiff", "[hair]\ndensity = 0.5\nlength = 30\n[contact]\nstiffness = 5e6\n"},
  };
  for (const Case& c : cases) {
    CAPTURE(std::string(c.name));
    const PipelineResult r = run(c.extra + "[effects]\ngravity = true\ncontact = true\n");
    check_all_finite(r);
    CHECK(figure<double>(r, "guides", "max_weight") > 500.0);
    CHECK(figure<double>(r, "guides", "max_contact_force") > 0.0);
    const double share = figure<double>(r, "guides", "contact_share");
    CHECK(share >= 0.0);
    CHECK(share <= 1.0);
    if (std::string(c.name).find("longer than the volume") != std::string::npos) {
      // The report names it: guides and pre-guides that end beyond the volume.
      CHECK(figure<std::int64_t>(r, "guides", "guides_ending_outside") > 0);
      CHECK(figure<double>(r, "guides", "outside_tip_fraction") > 0.0);
      CHECK(figure<std::int64_t>(r, "preguides", "flagged_tip_outside") > 0);
    }
    MESSAGE(std::string(c.name), ": guides inside ", figure<double>(r, "guides", "inside_fraction"), ", in the head ",
            figure<double>(r, "guides", "inside_head_fraction"), ", failures ",
            figure<std::int64_t>(r, "guides", "failures"), ", contact share ", share);
  }
}
