#include "io/png_chunks.h"

#include <cstdint>

namespace hairfit {

std::string without_empty_idat_chunks(const std::string& png) {
  constexpr std::size_t kSignature = 8, kFrame = 12;  // a chunk is length, type, data, CRC
  if (png.size() < kSignature) return png;
  std::string kept = png.substr(0, kSignature);
  std::size_t at = kSignature;
  while (png.size() - at >= kFrame) {
    std::uint32_t length = 0;
    for (int i = 0; i < 4; ++i) length = length << 8 | static_cast<unsigned char>(png[at + i]);
    if (length > png.size() - at - kFrame) break;  // runs past the end: stb reports it
    const std::size_t chunk = kFrame + length;
    if (!(length == 0 && png.compare(at + 4, 4, "IDAT") == 0)) kept.append(png, at, chunk);
    at += chunk;
  }
  kept.append(png, at, std::string::npos);
  return kept;
}

}  // namespace hairfit
