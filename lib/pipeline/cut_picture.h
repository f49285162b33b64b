// `hairfit render SCENE --stage cut`: what `hairfit prepare` cut from the scan, before any run.
// Left: the scan, shaded, with the hair volume tinted over it (what was selected). Right: the
// scalp, shaded, under the hull's outline (how thick the hair is taken to be).
#pragma once
#include <filesystem>

#include "io/png_image.h"
#include "render/camera.h"

namespace hairfit {

// Reads the scene, its meshes and the prepare.json beside it (which names the scan and its scale).
// Throws InputError naming the scene when there is no prepare.json (the scene was not written by
// `hairfit prepare`) or the scan it names cannot be read.
Image render_cut(const std::filesystem::path& scene_file, ViewName view, int width, int height, int threads);

}  // namespace hairfit
