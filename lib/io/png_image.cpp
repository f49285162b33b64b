#include "io/png_image.h"

#include <stb_image.h>
#include <stb_image_write.h>

#include <algorithm>
#include <fstream>
#include <iterator>
#include <stdexcept>

#include "core/error.h"
#include "io/atomic_file.h"
#include "io/png_chunks.h"

namespace hairfit {

Image make_image(int width, int height, std::uint8_t r, std::uint8_t g, std::uint8_t b, std::uint8_t a) {
  if (width <= 0 || height <= 0)
    throw std::invalid_argument("make_image: size must be positive, got " + std::to_string(width) + "x" +
                                std::to_string(height));
  Image image;
  image.width = width;
  image.height = height;
  image.rgba.resize(static_cast<std::size_t>(width) * height * 4);
  for (std::size_t i = 0; i < image.rgba.size(); i += 4) {
    image.rgba[i] = r;
    image.rgba[i + 1] = g;
    image.rgba[i + 2] = b;
    image.rgba[i + 3] = a;
  }
  return image;
}

std::vector<std::uint8_t> encode_png(const Image& image) {
  const std::size_t pixels = static_cast<std::size_t>(std::max(image.width, 0)) * std::max(image.height, 0);
  if (pixels == 0 || image.rgba.size() != pixels * 4)
    throw std::invalid_argument("encode_png: image is empty or its buffer does not match " +
                                std::to_string(image.width) + "x" + std::to_string(image.height));
  bool opaque = true;
  for (std::size_t i = 3; i < image.rgba.size() && opaque; i += 4) opaque = image.rgba[i] == 255;
  std::vector<std::uint8_t> rgb;
  const std::uint8_t* data = image.rgba.data();
  int channels = 4;
  if (opaque) {
    rgb.resize(pixels * 3);
    for (std::size_t i = 0; i < pixels; ++i)
      for (int c = 0; c < 3; ++c) rgb[i * 3 + c] = image.rgba[i * 4 + c];
    data = rgb.data();
    channels = 3;
  }
  std::vector<std::uint8_t> bytes;
  auto sink = [](void* context, void* chunk, int size) {
    auto* out = static_cast<std::vector<std::uint8_t>*>(context);
    const auto* begin = static_cast<const std::uint8_t*>(chunk);
    out->insert(out->end(), begin, begin + size);
  };
  if (!stbi_write_png_to_func(sink, &bytes, image.width, image.height, channels, data, image.width * channels))
    throw std::runtime_error("PNG encoding failed");
  return bytes;
}

void write_png(const std::filesystem::path& path, const Image& image) {
  const std::vector<std::uint8_t> bytes = encode_png(image);
  write_file_atomically(path, [&](std::ostream& out) {
    out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  });
}

Image load_png_image(const std::filesystem::path& path) {
  const std::string file = path.string();
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(file, "cannot be opened; check the path");
  const std::string bytes =
      without_empty_idat_chunks(std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>()));
  int width = 0, height = 0, channels = 0;
  stbi_uc* data = stbi_load_from_memory(reinterpret_cast<const stbi_uc*>(bytes.data()), static_cast<int>(bytes.size()),
                                        &width, &height, &channels, 4);
  if (!data) throw InputError(file, "cannot be read as a PNG image (" + stb_failure_text(stbi_failure_reason()) + ")");
  Image image;
  image.width = width;
  image.height = height;
  image.rgba.assign(data, data + static_cast<std::size_t>(width) * height * 4);
  stbi_image_free(data);
  return image;
}

}  // namespace hairfit
