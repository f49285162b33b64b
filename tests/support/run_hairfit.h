// Runs the built `hairfit` program from a test and captures its exit code, stdout and stderr.
#pragma once
#include <array>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <sys/wait.h>
#include <unistd.h>

#include "scratch.h"

namespace hairfit::testing {

struct CommandResult {
  int exit_code = -1;
  std::string out;
  std::string err;
};

inline std::string read_all(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// `arguments` is appended to the program path as shell text (quote it yourself).
inline CommandResult run_hairfit(const std::string& arguments) {
  static int counter = 0;
  const std::string base = scratch_path("run-" + std::to_string(counter++)).string();
  const std::string command = std::string(HAIRFIT_BINARY) + " " + arguments + " >" + base + ".out 2>" + base + ".err";
  const int status = std::system(command.c_str());
  CommandResult r;
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.out = read_all(base + ".out");
  r.err = read_all(base + ".err");
  // Under tests/sanitize.sh a report from the program exits 99 (no test expects it); show the
  // report, which would otherwise vanish with the captured stderr.
  if (r.err.find("runtime error: ") != std::string::npos || r.err.find("Sanitizer") != std::string::npos)
    std::fprintf(stderr, "sanitizer report from `hairfit %s`:\n%s\n", arguments.c_str(), r.err.c_str());
  std::remove((base + ".out").c_str());
  std::remove((base + ".err").c_str());
  return r;
}

inline std::string source_path(const std::string& relative) { return std::string(HAIRFIT_SOURCE_DIR) + "/" + relative; }

}  // namespace hairfit::testing
