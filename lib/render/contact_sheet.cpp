#include "render/contact_sheet.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "render/canvas.h"

namespace hairfit {

Image contact_sheet(const std::vector<Image>& images, const std::vector<std::string>& captions, int columns,
                    const Color& background) {
  if (images.empty()) throw std::invalid_argument("contact_sheet: no images");
  const int count = static_cast<int>(images.size());
  if (columns <= 0) columns = static_cast<int>(std::ceil(std::sqrt(static_cast<double>(count)) - 1e-9));
  columns = std::min(columns, count);
  const int rows = (count + columns - 1) / columns;
  int cell_w = 1, cell_h = 1;
  for (const Image& image : images) cell_w = std::max(cell_w, image.width), cell_h = std::max(cell_h, image.height);
  bool any_caption = false;
  for (const std::string& c : captions) any_caption = any_caption || !c.empty();
  const int gap = 8, caption_h = any_caption ? 30 : 0;
  const int width = columns * cell_w + (columns + 1) * gap;
  const int height = rows * (cell_h + caption_h) + (rows + 1) * gap;
  Canvas canvas(width, height, background);
  const float lum = 0.3f * background.r + 0.59f * background.g + 0.11f * background.b;
  const Color text = lum < 0.5f ? Color{0.9f, 0.9f, 0.9f} : Color{0.1f, 0.1f, 0.12f};
  for (int k = 0; k < count; ++k) {
    const int col = k % columns, row = k / columns;
    const int x = gap + col * (cell_w + gap), y = gap + row * (cell_h + caption_h + gap);
    canvas.draw_image(images[k], x + (cell_w - images[k].width) / 2, y + (cell_h - images[k].height) / 2);
    if (k < static_cast<int>(captions.size()) && !captions[k].empty())
      canvas.text(x + 0.5 * cell_w, y + cell_h + 8, captions[k], text, 2.0, TextAlign::centre);
  }
  return canvas.image();
}

Image averaged_down(const Image& image, int factor) {
  if (factor < 1) throw std::invalid_argument("averaged_down: factor must be at least 1");
  if (factor == 1) return image;
  Image out;
  out.width = image.width / factor;
  out.height = image.height / factor;
  out.rgba.resize(static_cast<std::size_t>(out.width) * out.height * 4);
  const int area = factor * factor;
  for (int y = 0; y < out.height; ++y)
    for (int x = 0; x < out.width; ++x)
      for (int c = 0; c < 4; ++c) {
        int sum = 0;
        for (int dy = 0; dy < factor; ++dy)
          for (int dx = 0; dx < factor; ++dx) sum += image.pixel(x * factor + dx, y * factor + dy)[c];
        out.rgba[(static_cast<std::size_t>(y) * out.width + x) * 4 + c] = static_cast<std::uint8_t>((sum + area / 2) / area);
      }
  return out;
}

Image side_by_side(const std::vector<Image>& images) {
  return contact_sheet(images, {}, static_cast<int>(images.size()), {1.0f, 1.0f, 1.0f});
}

}  // namespace hairfit
