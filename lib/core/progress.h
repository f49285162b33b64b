// How a stage's loop says how far it got, without knowing who listens (lib/pipeline/progress.h
// draws it). Reporting never changes results: the callback only receives counts.
#pragma once
#include <atomic>
#include <cstddef>
#include <functional>
#include <utility>

namespace hairfit {

// Called with the number of items finished so far; may be called from any thread, concurrently,
// and not necessarily in increasing order. Empty = nobody listens.
using ProgressCallback = std::function<void(std::size_t done)>;

// Counts finished items from any thread and passes the running total on.
class ProgressCounter {
 public:
  explicit ProgressCounter(const ProgressCallback& report) : report_(report) {}
  void item_done() {
    if (report_) report_(++done_);
  }

 private:
  const ProgressCallback& report_;
  std::atomic<std::size_t> done_{0};
};

}  // namespace hairfit
