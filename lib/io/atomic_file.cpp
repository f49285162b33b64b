#include "io/atomic_file.h"

#include <fstream>
#include <stdexcept>
#include <system_error>
#include <unistd.h>

#include "core/error.h"
#include "core/interrupt.h"

namespace hairfit {

void write_file_atomically(const std::filesystem::path& path,
                           const std::function<void(std::ostream&)>& write) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (fs::is_directory(path, ec))
    throw InputError(path.string(), "is a folder; name the file to write (e.g. " + (path / "out.png").string() + ")");
  if (path.has_parent_path()) fs::create_directories(path.parent_path());
  fs::path temporary = path;
  temporary += ".tmp-" + std::to_string(::getpid());
  try {
    {
      std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
      if (!out) throw std::runtime_error("cannot open " + temporary.string() + " for writing");
      write(out);
      out.flush();
      if (!out) throw std::runtime_error("writing " + path.string() + " failed (disk full?)");
    }
    throw_if_interrupted();  // a file written while the signal arrived is dropped, not renamed
    fs::rename(temporary, path);
  } catch (...) {
    std::error_code ignored;
    fs::remove(temporary, ignored);
    throw;
  }
}

void write_text_file_atomically(const std::filesystem::path& path, std::string_view text) {
  write_file_atomically(path, [&](std::ostream& out) { out.write(text.data(), text.size()); });
}

}  // namespace hairfit
