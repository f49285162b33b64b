// Nothing lost (issue 12): SIGINT and SIGTERM stop a run between work items, the atomic writer drops
// the file it was writing, earlier outputs stay byte-identical and the program says so and exits
// with 128 + the signal number.
#include <doctest/doctest.h>

#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <csignal>
#include <filesystem>
#include <map>
#include <thread>

#include "../support/run_hairfit.h"
#include "core/interrupt.h"
#include "core/parallel.h"
#include "io/atomic_file.h"
#include "../support/scratch.h"

using namespace hairfit;
using hairfit::testing::read_all;
using hairfit::testing::source_path;
namespace fs = std::filesystem;

namespace {

fs::path fresh_folder(const std::string& name) {
  return hairfit::testing::fresh_scratch_folder("interrupt-" + name);
}

// Every regular file below `dir` with its bytes, by path relative to `dir`.
std::map<std::string, std::string> snapshot(const fs::path& dir) {
  std::map<std::string, std::string> files;
  for (const auto& e : fs::recursive_directory_iterator(dir))
    if (e.is_regular_file()) files[fs::relative(e.path(), dir).string()] = read_all(e.path().string());
  return files;
}

bool has_temporary_file(const fs::path& dir) {
  for (const auto& e : fs::recursive_directory_iterator(dir))
    if (e.path().filename().string().find(".tmp-") != std::string::npos) return true;
  return false;
}

// The flag is process-wide: every test leaves it cleared.
struct ClearFlag {
  ~ClearFlag() { set_interrupt_signal(0); }
};

}  // namespace

TEST_CASE("after a signal the atomic writer leaves the destination and no temporary file") {
  const ClearFlag clear;
  const fs::path dir = fresh_folder("writer");
  write_text_file_atomically(dir / "earlier.txt", "earlier result\n");
  set_interrupt_signal(SIGINT);
  CHECK_THROWS_AS(write_text_file_atomically(dir / "earlier.txt", "half a new result"), Interrupted);
  CHECK_THROWS_AS(write_text_file_atomically(dir / "new.txt", "new"), Interrupted);
  CHECK(read_all((dir / "earlier.txt").string()) == "earlier result\n");
  CHECK_FALSE(fs::exists(dir / "new.txt"));
  CHECK_FALSE(has_temporary_file(dir));
  fs::remove_all(dir);
}

TEST_CASE("parallel_for starts no item after a signal and throws Interrupted, for 1 and 3 threads") {
  const ClearFlag clear;
  for (int threads : {1, 3}) {
    INFO("threads " << threads);
    set_interrupt_signal(0);
    std::atomic<int> ran{0};
    // Item 10 raises the flag as the handler would; items already running finish, no new one starts.
    CHECK_THROWS_AS(parallel_for(100000, threads,
                                 [&](int i) {
                                   ++ran;
                                   if (i == 10) set_interrupt_signal(SIGTERM);
                                 }),
                    Interrupted);
    CHECK(ran.load() < 100000);
    if (threads == 1) CHECK(ran.load() == 11);
  }
}

TEST_CASE("the handlers turn SIGTERM and SIGINT into Interrupted with exit codes 143 and 130") {
  const ClearFlag clear;
  for (int signal : {SIGTERM, SIGINT}) {
    set_interrupt_signal(0);
    install_interrupt_handlers();
    std::raise(signal);  // handled: the test process goes on
    REQUIRE(interrupt_signal() == signal);
    try {
      throw_if_interrupted();
      FAIL("no exception");
    } catch (const Interrupted& e) {
      CHECK(e.exit_code() == 128 + signal);
      CHECK(std::string(e.what()) == (signal == SIGINT ? "interrupted by SIGINT" : "interrupted by SIGTERM"));
    }
  }
  // The handler restored the default action; leave it so for the rest of the program.
  std::signal(SIGINT, SIG_DFL);
  std::signal(SIGTERM, SIG_DFL);
}

TEST_CASE("Ctrl-C during `hairfit run` of the spheroid: exit 130, a message, earlier outputs and cache intact, no temporary file") {
  const fs::path dir = fresh_folder("run"), cache = fresh_folder("cache");
  const std::string scene = source_path("fixtures/spheroid/scene.toml");
  const std::string common = " --threads 2 --out " + dir.string() + " --cache " + cache.string();
  // The earlier outputs (and cache entries): the first stage, run to completion.
  const auto first = testing::run_hairfit("run " + scene + " --until fields" + common);
  REQUIRE(first.exit_code == 0);
  const std::map<std::string, std::string> before = snapshot(dir), cached = snapshot(cache);
  REQUIRE(before.count("fields/volume.nrrd") == 1);
  REQUIRE(before.count("report.json") == 1);

  // The whole run into the same folders, interrupted once the roots are written, i.e. during the
  // pre-guides (a second or more on the spheroid).
  const std::string err = (dir.parent_path() / (dir.filename().string() + ".err")).string();
  const pid_t child = ::fork();
  REQUIRE(child >= 0);
  if (child == 0) {
    const int null = ::open("/dev/null", O_WRONLY), log = ::open(err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    ::dup2(null, 1);
    ::dup2(log, 2);
    const std::string out = dir.string(), cache_dir = cache.string();
    ::execl(HAIRFIT_BINARY, HAIRFIT_BINARY, "run", scene.c_str(), "--threads", "2", "--out", out.c_str(), "--cache",
            cache_dir.c_str(), (char*)nullptr);
    ::_exit(127);
  }
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
  int status = 0;
  bool exited = false;
  while (!fs::exists(dir / "roots.ply") && std::chrono::steady_clock::now() < deadline) {
    if (::waitpid(child, &status, WNOHANG) == child) {
      exited = true;
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  REQUIRE_FALSE(exited);  // the run must still be going when the signal comes
  ::kill(child, SIGINT);
  REQUIRE(::waitpid(child, &status, 0) == child);
  REQUIRE(WIFEXITED(status));
  CHECK(WEXITSTATUS(status) == 130);
  const std::string message = read_all(err);
  CHECK(message.find("hairfit run: interrupted by SIGINT; the files written before it are complete and intact, "
                     "nothing half-written was left\n") != std::string::npos);

  CHECK_FALSE(has_temporary_file(dir));
  CHECK_FALSE(has_temporary_file(cache));
  // Every earlier output and cache entry is still there, byte for byte (a stage the second run
  // repeated wrote identical bytes: the run is deterministic); report.json too: the run did not finish.
  for (const auto& folder : {std::make_pair(before, snapshot(dir)), std::make_pair(cached, snapshot(cache))})
    for (const auto& [path, bytes] : folder.first) {
      INFO(path);
      REQUIRE(folder.second.count(path) == 1);
      CHECK(folder.second.at(path) == bytes);
    }
  CHECK(snapshot(dir).count("guides.obj") == 0);  // the guide stage never finished
  fs::remove_all(dir);
  fs::remove_all(cache);
  fs::remove(err);
}
