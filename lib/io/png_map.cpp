#include "io/png_map.h"

#include <stb_image.h>
#include <stb_image_write.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iterator>
#include <memory>

#include "core/error.h"
#include "io/atomic_file.h"
#include "io/png_chunks.h"

namespace hairfit {

GreyMap load_grey_map(const std::filesystem::path& path) {
  namespace fs = std::filesystem;
  const std::string file = path.string();
  std::error_code ec;
  if (!fs::exists(path, ec)) throw InputError(file, "no such file; check the path (relative paths start at the scene file's folder)");
  if (fs::is_directory(path, ec)) throw InputError(file, "is a folder, not a PNG image");
  std::ifstream in(path, std::ios::binary);
  const std::string read((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (!in && !in.eof()) throw InputError(file, "cannot be read (permissions?)");
  static const char signature[] = "\x89PNG\r\n\x1a\n";
  if (read.size() < 8 || read.compare(0, 8, signature, 8) != 0)
    throw InputError(file, "is not a PNG file; maps must be grey-value PNG images (8 or 16 bit)");
  const std::string bytes = without_empty_idat_chunks(read);

  // stb_image calls a 0-pixel header an "unknown image type"; say what it is.
  auto header_number = [&](std::size_t at) {
    return static_cast<unsigned long>(static_cast<unsigned char>(bytes[at])) << 24 | static_cast<unsigned char>(bytes[at + 1]) << 16 |
           static_cast<unsigned char>(bytes[at + 2]) << 8 | static_cast<unsigned char>(bytes[at + 3]);
  };
  if (bytes.size() >= 24 && bytes.compare(12, 4, "IHDR") == 0 && (header_number(16) == 0 || header_number(20) == 0))
    throw InputError(file, "has no pixels (its header says " + std::to_string(header_number(16)) + "×" +
                               std::to_string(header_number(20)) + "); maps need at least 1×1 pixel");
  const auto* data = reinterpret_cast<const stbi_uc*>(bytes.data());
  const int size = static_cast<int>(bytes.size());
  int width = 0, height = 0, channels = 0;
  if (!stbi_info_from_memory(data, size, &width, &height, &channels))
    throw InputError(file, "is a corrupt PNG (" + stb_failure_text(stbi_failure_reason()) + "); re-export it as a grey PNG");
  if (width <= 0 || height <= 0) throw InputError(file, "has no pixels; maps need at least 1×1 pixel");
  // The header alone decides the allocation, so a few corrupt bytes must not ask for terabytes.
  constexpr int kMaxSide = 16384;
  constexpr long long kMaxPixels = 1LL << 26;
  if (width > kMaxSide || height > kMaxSide || static_cast<long long>(width) * height > kMaxPixels)
    throw InputError(file, "is " + std::to_string(width) + "×" + std::to_string(height) + " pixels; maps may have at most " +
                               std::to_string(kMaxSide) + " pixels per side and " + std::to_string(kMaxPixels) +
                               " pixels in all: downscale it (a scalp map needs far fewer)");

  GreyMap map;
  map.width = width;
  map.height = height;
  map.bits = stbi_is_16_bit_from_memory(data, size) ? 16 : 8;
  const std::size_t pixels = static_cast<std::size_t>(width) * height;
  map.values.resize(pixels);
  // Decode as stored; channel equality is checked before anything is averaged away.
  auto convert = [&](auto* decoded, double scale) {
    if (!decoded)
      throw InputError(file, "is a corrupt PNG (" + stb_failure_text(stbi_failure_reason()) + "); re-export it as a grey PNG");
    for (std::size_t i = 0; i < pixels; ++i) {
      const auto* px = decoded + i * channels;
      if (channels >= 3 && (px[0] != px[1] || px[1] != px[2])) {
        const std::size_t x = i % width, y = i / width;
        stbi_image_free(decoded);
        throw InputError(file, "is a colour image (pixel " + std::to_string(x) + "," + std::to_string(y) +
                                   " is not grey); maps must be grey-value images: convert it to greyscale");
      }
      map.values[i] = static_cast<float>(px[0] / scale);
    }
    stbi_image_free(decoded);
  };
  int w = 0, h = 0, c = 0;
  if (map.bits == 16)
    convert(stbi_load_16_from_memory(data, size, &w, &h, &c, 0), 65535.0);
  else
    convert(stbi_load_from_memory(data, size, &w, &h, &c, 0), 255.0);
  return map;
}

void write_grey_png(const std::filesystem::path& path, const GreyMap& map) {
  std::vector<unsigned char> pixels(map.values.size());
  for (std::size_t i = 0; i < pixels.size(); ++i)
    pixels[i] = static_cast<unsigned char>(std::lround(255.0 * std::clamp(map.values[i], 0.0f, 1.0f)));
  write_file_atomically(path, [&](std::ostream& out) {
    auto sink = [](void* context, void* data, int size) {
      static_cast<std::ostream*>(context)->write(static_cast<const char*>(data), size);
    };
    if (!stbi_write_png_to_func(sink, &out, map.width, map.height, 1, pixels.data(), map.width))
      throw std::runtime_error("PNG encoding failed for " + path.string());
  });
}

}  // namespace hairfit
