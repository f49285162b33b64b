// 8-bit RGBA images as plain values and their PNG encoding: what every picture and plot is written
// as. The bytes depend only on the pixels (stb_image_write's encoder has no clock or randomness), so
// the same image always gives the same file.
#pragma once
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace hairfit {

struct Image {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> rgba;  // row-major, row 0 at the top, 4 bytes per pixel (R, G, B, A)

  const std::uint8_t* pixel(int x, int y) const { return &rgba[(static_cast<std::size_t>(y) * width + x) * 4]; }
};

// An image of the given size filled with one colour (components 0–255).
Image make_image(int width, int height, std::uint8_t r, std::uint8_t g, std::uint8_t b, std::uint8_t a = 255);

// PNG file bytes: 3 channels when every pixel is opaque, else 4. Throws std::invalid_argument for
// an empty image or a buffer whose size is not width·height·4.
std::vector<std::uint8_t> encode_png(const Image& image);

// Writes encode_png(image) atomically (temporary file, then rename).
void write_png(const std::filesystem::path& path, const Image& image);

// Reads any PNG as 8-bit RGBA (for tests and for tiling saved pictures). Throws InputError naming
// the file when it is missing or not a readable PNG.
Image load_png_image(const std::filesystem::path& path);

}  // namespace hairfit
