// The fuzz build compiles the third-party parsers the loaders call into the fuzz programs, so
// libFuzzer sees their coverage and AddressSanitizer checks their memory accesses; these
// definitions take precedence over the (uninstrumented) Debian shared libraries at link time.
#define STB_IMAGE_IMPLEMENTATION
#include <stb_image.h>

#define TINYOBJLOADER_IMPLEMENTATION
#include <tiny_obj_loader.h>
