#include "io/png_chunks.h"

#include <algorithm>
#include <cstdint>

namespace hairfit {

std::string without_empty_idat_chunks(const std::string& png) {
  constexpr std::size_t kSignature = 8, kFrame = 12;  // a chunk is length, type, data, CRC
  if (png.size() < kSignature) return png;
  std::string kept = png.substr(0, kSignature);
  std::size_t at = kSignature;
  while (png.size() - at >= 8) {  // a chunk's length and type are there
    std::uint32_t length = 0;
    for (int i = 0; i < 4; ++i) length = length << 8 | static_cast<unsigned char>(png[at + i]);
    if (length == 0 && png.compare(at + 4, 4, "IDAT") == 0) {  // dropped even when its CRC is cut off
      at += std::min(kFrame, png.size() - at);
      continue;
    }
    if (png.size() - at < kFrame || length > png.size() - at - kFrame) break;  // runs past the end: stb reports it
    kept.append(png, at, kFrame + length);
    at += kFrame + length;
  }
  kept.append(png, at, std::string::npos);
  return kept;
}

std::string stb_failure_text(const char* reason) {
  return reason && *reason ? reason : "its chunks are cut off or malformed";
}

}  // namespace hairfit
