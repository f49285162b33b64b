// Pictures of every stage (docs/design.md §8: every stage can be rendered), drawn from the stage
// values with lib/render.
#pragma once
#include <string>
#include <vector>

#include "io/png_image.h"
#include "pipeline/pipeline.h"
#include "render/camera.h"

namespace hairfit {

// The stages `hairfit render --stage` accepts, in pipeline order, plus "all" (a contact sheet).
const std::vector<std::string>& picture_stages();

// Throws InputError listing the valid stages unless `stage` is one.
void check_picture_stage(const std::string& stage);

// The last pipeline stage a picture of `stage` needs.
std::string stage_needed_for_picture(const std::string& stage);

// Renders one stage from one view. Throws InputError for an unknown stage, listing the valid ones.
Image render_stage(const std::string& stage, const Scene& scene, const Inputs& inputs, const StageValues& values,
                   ViewName view, int width, int height, int threads);

}  // namespace hairfit
