// `hairfit prepare` never writes what `run` refuses: its files are written into a staging folder
// first and read back there exactly as `run` reads a scene (parse_scene, load_inputs), and only
// files that pass are moved into the output folder.
#pragma once
#include <filesystem>

#include "prepare/prepare.h"

namespace hairfit {

// write_prepared into `dir`, once run's own checks accept the files: on failure nothing of `dir`
// is touched (the staging folder beside it is removed) and InputError names the scan, what `run`
// refused and what in the scan causes it.
void write_validated_prepared(const Prepared& prepared, const std::filesystem::path& scan, const PrepareOptions& options,
                              const std::filesystem::path& dir);

}  // namespace hairfit
