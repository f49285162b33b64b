// What a run shows on stderr while it works: with a terminal, a bar for the stages with loops
// (items done, rate, time left) redrawn in place; otherwise plain lines (each stage's start and
// end, and 25/50/75 % of the long ones); nothing when quiet. Only ever prints: results are the
// same with any style.
#pragma once
#include <chrono>
#include <cstdio>
#include <mutex>
#include <string>

#include "core/progress.h"

namespace hairfit {

enum class ProgressStyle { quiet, lines, bar };

// bar when `stream` is a terminal, lines otherwise, quiet when asked.
ProgressStyle progress_style_for(std::FILE* stream, bool quiet);

class ProgressReporter {
 public:
  explicit ProgressReporter(ProgressStyle style, std::FILE* stream = stderr) : style_(style), stream_(stream) {}

  // A stage starts; `items` is the length of its loop (0: no loop worth showing).
  void stage_begins(const std::string& stage, std::size_t items);
  // The callback the stage's loop reports to (ProgressCounter); valid until stage_ends.
  const ProgressCallback& callback() const { return callback_; }
  // status: computed | cached.
  void stage_ends(const std::string& stage, const std::string& status, double seconds);
  // A remark between stages (e.g. a rejected cache entry).
  void note(const std::string& text);

 private:
  void items_done(std::size_t done);
  void draw_bar(std::size_t done, double elapsed);

  ProgressStyle style_;
  std::FILE* stream_;
  std::mutex mutex_;
  std::string stage_;
  std::size_t items_ = 0, shown_ = 0;
  int quarters_shown_ = 0;
  std::chrono::steady_clock::time_point start_, last_draw_;
  bool bar_drawn_ = false;
  ProgressCallback callback_ = [this](std::size_t done) { items_done(done); };
};

}  // namespace hairfit
