// A pass over a PNG file's chunk stream before stb_image decodes it, for what stb mishandles.
#pragma once
#include <string>

namespace hairfit {

// The PNG bytes without their zero-length IDAT chunks (also one whose CRC is cut off by the end of
// the file); everything else byte for byte. A zero-length IDAT is valid PNG and carries no image
// data, so the decoded pixels are the same; but when it is the first IDAT, stb_image passes a null
// buffer to memcpy (undefined behaviour, found by the PNG fuzz target; Debian's stb cannot be
// patched here, and a sanitizer suppression would hide it rather than keep the loader well-defined).
// Bytes that do not parse as chunks (a length running past the end) are kept as they are, for stb
// to report as corrupt.
std::string without_empty_idat_chunks(const std::string& png);

}  // namespace hairfit

namespace hairfit {

// stb_image's reason for the last failure, or a generic one: stb leaves it null on some paths and
// empty for an all-zero chunk type (a file cut off after its header).
std::string stb_failure_text(const char* reason);

}  // namespace hairfit
