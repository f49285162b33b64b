// One function per subcommand of `hairfit`; each returns the process exit code
// (0 success, 2 bad input, 1 internal error) and may throw InputError or UsageError.
#pragma once
#include <string>
#include <vector>

namespace hairfit::cli {

using Arguments = std::vector<std::string>;

int command_validate(const Arguments& args);
int command_run(const Arguments& args);
int command_check(const Arguments& args);
int command_render(const Arguments& args);
int command_scene_keys(const Arguments& args);
int command_rod(const Arguments& args);
int command_field(const Arguments& args);
int command_prepare(const Arguments& args);

}  // namespace hairfit::cli
