// The loaders read files by path, so each fuzz input is written to one scratch file first (in
// /dev/shm when it exists: no disk traffic). Only InputError may escape a loader; anything else
// (another exception, a crash, a sanitizer report) is a finding.
#pragma once
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>

namespace hairfit::fuzz {

inline std::filesystem::path scratch_file(const std::string& extension) {
  const std::filesystem::path folder = std::filesystem::exists("/dev/shm") ? "/dev/shm" : "/tmp";
  return folder / ("hairfit-fuzz-" + std::to_string(::getpid()) + extension);
}

inline std::filesystem::path write_input(const uint8_t* data, size_t size, const std::string& extension) {
  const std::filesystem::path path = scratch_file(extension);
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  return path;
}

}  // namespace hairfit::fuzz
