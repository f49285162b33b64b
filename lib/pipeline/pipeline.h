// The stages in order, run as pure functions of the scene and the earlier stages' values:
//   fields → chart → roots → preguides → guides → strands → density
// The density stage exists only when the scene declares a density model (effects.density); then
// the guides stage also optimises in batches against the density (make_guides_with_density).
#pragma once
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "density/grid.h"
#include "field/distance_field.h"
#include "guides/guides.h"
#include "pipeline/inputs.h"
#include "pipeline/progress.h"
#include "pipeline/report.h"
#include "scalp/roots.h"
#include "spec/scene.h"
#include "strands/strands.h"

namespace hairfit {

struct RunOptions {
  std::filesystem::path out_dir;  // where outputs and report.json go
  std::string until;              // last stage to run ("" = all)
  int threads = 1;                // already resolved (≥ 1)
  bool write_outputs = true;      // false: compute only (render)
  // Where stage values are cached (pipeline/stage_cache.h); empty: every stage is computed.
  std::filesystem::path cache_dir;
  ProgressReporter* progress = nullptr;  // stage starts, ends and loop progress; null: silent
};

// Every stage's value; a stage not run (beyond --until) stays empty.
struct StageValues {
  // scalp_field is the skin the stages keep hair in front of: the closed head's distance field
  // (scalp_distance itself), or with fields.skin_beyond_hairline = "shell" that field continued
  // past the hairline under the hull (field/skin_beyond_hairline.h), which bounds no distance.
  std::shared_ptr<const DistanceField> scalp_field, volume_field, scalp_distance;
  std::shared_ptr<const ScalpChart> chart;
  std::shared_ptr<const Roots> roots;
  std::shared_ptr<const Clusters> clusters;
  std::shared_ptr<const PreguideRoots> preguide_roots;
  std::shared_ptr<const PreGuides> preguides;
  std::shared_ptr<const Guides> guides;
  std::shared_ptr<const Strands> strands;
  // Only with a density model: the model's grid after the last guide batch (BOM occupancy or CDM),
  // and the CDM density of the final fibres (the density stage).
  std::shared_ptr<const DensityGrid> guide_density, fibre_density;
};

// The stages this build runs, in order ("density" is skipped, and absent from the report, when
// the scene declares no density model).
const std::vector<std::string>& stage_names();

// Throws InputError listing the valid stages unless `stage` is one (or empty).
void check_stage_name(const std::string& stage, const std::string& option = "--until");

// Runs the stages up to options.until, writes their outputs and report.json into out_dir (unless
// write_outputs is false), and returns the values and the report. With a cache_dir, a stage whose
// key (pipeline/stage_plan.h) has a valid entry is loaded instead of computed (status "cached");
// values, digests, figures and output files are byte-identical either way.
struct PipelineResult {
  StageValues values;
  RunReport report;
};
PipelineResult run_pipeline(const Scene& scene, const Inputs& inputs, const RunOptions& options);

// Where `hairfit run` caches stage values unless told otherwise: `.hairfit-cache` beside the scene.
std::filesystem::path default_cache_dir(const Scene& scene);

}  // namespace hairfit
