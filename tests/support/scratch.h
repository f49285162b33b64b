// Where tests write files: one folder per test process, <temp>/hairfit-test-<pid>, removed with
// everything in it when the process exits, so repeated test runs leave nothing behind. Set
// HAIRFIT_KEEP_TEST_FILES=1 to keep it for a look after a failure (its path is printed).
#pragma once
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <system_error>
#include <unistd.h>

namespace hairfit::testing {

class ScratchRoot {
 public:
  ScratchRoot()
      : path_(std::filesystem::temp_directory_path() / ("hairfit-test-" + std::to_string(::getpid()))) {
    std::filesystem::create_directories(path_);
  }
  ~ScratchRoot() {
    const char* keep = std::getenv("HAIRFIT_KEEP_TEST_FILES");
    if (keep && std::string(keep) == "1") {
      std::fprintf(stderr, "test files kept in %s\n", path_.c_str());
      return;
    }
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
  }
  ScratchRoot(const ScratchRoot&) = delete;
  ScratchRoot& operator=(const ScratchRoot&) = delete;
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

// `name` inside this process's scratch folder; not created.
inline std::filesystem::path scratch_path(const std::string& name) {
  static const ScratchRoot root;
  return root.path() / name;
}

// A fresh, empty folder `name` inside this process's scratch folder.
inline std::filesystem::path fresh_scratch_folder(const std::string& name) {
  const std::filesystem::path dir = scratch_path(name);
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

}  // namespace hairfit::testing
