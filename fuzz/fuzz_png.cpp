// libFuzzer target: the grey-map loader (PNG signature, size limits, 8/16-bit, colour rejection)
// and bilinear sampling of what it returns.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>

#include "core/error.h"
#include "fuzz_input_file.h"
#include "io/png_map.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::filesystem::path path = hairfit::fuzz::write_input(data, size, ".png");
  try {
    const hairfit::GreyMap map = hairfit::load_grey_map(path);
    for (double u : {-0.5, 0.0, 0.37, 1.0, 1.5})
      if (!std::isfinite(map.sample(hairfit::Vec2(u, 1.0 - u)))) std::abort();
  } catch (const hairfit::InputError&) {
  }
  return 0;
}
