#include "core/parallel.h"

#include <algorithm>
#include <atomic>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

#include "core/interrupt.h"

namespace hairfit {

int resolve_thread_count(int requested) {
  if (requested > 0) return requested;
  return std::max(1u, std::thread::hardware_concurrency());
}

void parallel_for(int count, int threads, const std::function<void(int)>& body) {
  threads = std::max(1, std::min(threads, count));
  // A signal stops the loop between items (SIGINT, SIGTERM: core/interrupt.h).
  if (threads == 1) {
    for (int i = 0; i < count; ++i) {
      throw_if_interrupted();
      body(i);
    }
    return;
  }
  // Dynamic scheduling of small chunks balances uneven items (guides converge at different
  // speeds); the output stays deterministic because each item writes only its own slot.
  const int chunk = std::max(1, count / (threads * 16));
  std::atomic<int> next{0};
  // On failure every item still runs, and the error of the lowest failing index is the one
  // reported, so even the error message does not depend on the thread count.
  std::exception_ptr error;
  int error_index = count;
  std::mutex error_mutex;
  auto worker = [&] {
    for (;;) {
      const int begin = next.fetch_add(chunk);
      if (begin >= count) return;
      const int end = std::min(count, begin + chunk);
      for (int i = begin; i < end; ++i) {
        if (interrupted()) return;
        try {
          body(i);
        } catch (...) {
          std::lock_guard<std::mutex> lock(error_mutex);
          if (i < error_index) {
            error_index = i;
            error = std::current_exception();
          }
        }
      }
    }
  };
  std::vector<std::thread> pool;
  for (int t = 1; t < threads; ++t) pool.emplace_back(worker);
  worker();
  for (std::thread& t : pool) t.join();
  throw_if_interrupted();
  if (error) std::rethrow_exception(error);
}

}  // namespace hairfit
