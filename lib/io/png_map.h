// Loading grey-value PNG maps (8- or 16-bit) into immutable GreyMap values.
#pragma once
#include <filesystem>

#include "core/grey_map.h"

namespace hairfit {

// Throws InputError naming the file for a missing, unreadable, corrupt or non-grey image. Grey
// with alpha is accepted (alpha ignored); an RGB(A) image is accepted only when every pixel has
// equal channels, otherwise the error names the first coloured pixel.
GreyMap load_grey_map(const std::filesystem::path& path);

// Writes an 8-bit grey PNG (values clamped to [0, 1]); used by the fixture generator and tests.
void write_grey_png(const std::filesystem::path& path, const GreyMap& map);

}  // namespace hairfit
