// Every output is written to a temporary name beside its destination and renamed into place, so a
// failed or interrupted run never leaves a half-written file and never damages an earlier one.
#pragma once
#include <filesystem>
#include <functional>
#include <ostream>
#include <string_view>

namespace hairfit {

// Runs write(stream) on a temporary file, then renames it to `path` (creating parent folders).
// If write throws, the stream fails or a SIGINT/SIGTERM arrived (core/interrupt.h), the temporary
// file is removed and `path` is untouched.
void write_file_atomically(const std::filesystem::path& path,
                           const std::function<void(std::ostream&)>& write);

void write_text_file_atomically(const std::filesystem::path& path, std::string_view text);

}  // namespace hairfit
