// Several pictures on one sheet: the `--stage all` overview and side-by-side plot panels.
#pragma once
#include <string>
#include <vector>

#include "io/png_image.h"
#include "render/color.h"

namespace hairfit {

// Tiles the images row by row in `columns` columns (0 = ⌈√count⌉) of equal cells sized to the
// largest image, each centred in its cell with its caption (may be empty; missing captions count
// as empty) written below. Throws std::invalid_argument for no images.
Image contact_sheet(const std::vector<Image>& images, const std::vector<std::string>& captions = {}, int columns = 0,
                    const Color& background = {0.09f, 0.09f, 0.11f});

// The image averaged over factor × factor blocks (each channel, rounded): ⌊width / factor⌋ by
// ⌊height / factor⌋ pixels. Throws std::invalid_argument unless factor ≥ 1.
Image averaged_down(const Image& image, int factor);

// The images in one row, without captions, on white (plot panels).
Image side_by_side(const std::vector<Image>& images);

}  // namespace hairfit
