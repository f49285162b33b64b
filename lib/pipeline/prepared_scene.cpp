#include "pipeline/prepared_scene.h"

#include <system_error>

#include "core/error.h"
#include "pipeline/inputs.h"
#include "spec/scene.h"

namespace hairfit {

namespace {

namespace fs = std::filesystem;

// The folder the files are first written into: beside `dir`, hidden, removed on every way out.
struct Staging {
  fs::path path;
  explicit Staging(const fs::path& dir) {
    const fs::path normal = fs::absolute(dir).lexically_normal();
    const fs::path name = normal.has_filename() ? normal.filename() : normal.parent_path().filename();
    const fs::path parent = normal.has_filename() ? normal.parent_path() : normal.parent_path().parent_path();
    path = parent / ("." + name.string() + ".prepare-staging");
    std::error_code ec;
    fs::remove_all(path, ec);
    fs::create_directories(path, ec);
    if (ec) throw InputError(dir.string(), "cannot create the staging folder " + path.string() + ": " + ec.message());
  }
  ~Staging() {
    std::error_code ec;
    fs::remove_all(path, ec);
  }
};

constexpr const char* kPreparedFiles[] = {"volume.obj", "scalp.obj", "prepare.json", "scene.toml"};

}  // namespace

void write_validated_prepared(const Prepared& p, const fs::path& scan, const PrepareOptions& o, const fs::path& dir) {
  std::error_code ec;
  if (fs::exists(dir, ec) && !fs::is_directory(dir, ec))
    throw InputError(dir.string(), "exists and is not a folder; --out names the folder to write the scene into");
  const Staging staging(dir);
  write_prepared(p, scan, o, staging.path);
  try {
    const Scene scene = parse_scene(staging.path / "scene.toml");
    load_inputs(scene, 1);
  } catch (const InputError& e) {
    // The staged file's name stands for the file that would have been written.
    std::string what = e.what();
    const std::string staged = staging.path.string();
    for (std::size_t at = what.find(staged); at != std::string::npos; at = what.find(staged))
      what.replace(at, staged.size(), dir.string());
    throw InputError(scan.string(), "prepare derived files that `hairfit run` would refuse, so it wrote nothing: " + what +
                                        " (in the scan: the hull cut at the hairline, " + p.scalp_how +
                                        "); repair the scan near the hairline, or try another --scalp-voxel or "
                                        "--crown-thickness");
  }
  fs::create_directories(dir, ec);
  if (ec) throw InputError(dir.string(), "cannot create the folder: " + ec.message());
  for (const char* name : kPreparedFiles) {
    fs::rename(staging.path / name, dir / name, ec);
    if (ec) throw InputError((dir / name).string(), "cannot be written: " + ec.message());
  }
}

}  // namespace hairfit
