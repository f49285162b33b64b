#include "core/parallel.h"

#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <cstdlib>
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

namespace {

// Worker threads kept for the life of the process: a loop hands its worker function to as many of
// them as it needs and runs it on the calling thread too. Starting threads for every loop cost
// about 55 µs a loop on the benchmark machine (a paper-scale run has about 200 loops), and every
// fresh thread set up its thread-local scratch, malloc cache and stack pages again.
// One loop at a time: a loop started while another runs (from inside a loop body, or from another
// thread) gets threads of its own, as before; results never depend on which threads run a loop.
class WorkerPool {
 public:
  static WorkerPool& instance() {
    // Never destroyed: the workers sleep until the process ends (joining them from a static
    // destructor could race with loops still running at exit).
    static WorkerPool* pool = new WorkerPool;
    return *pool;
  }

  // Runs `work` (which must not throw) on the calling thread and on `helpers` pool threads, and
  // returns when all have returned from it. False, with nothing run, while another loop has the
  // pool.
  bool run(int helpers, const std::function<void()>& work) {
    bool expected = false;
    if (!busy_.compare_exchange_strong(expected, true)) return false;
    {
      std::unique_lock<std::mutex> lock(mutex_);
      while (static_cast<int>(threads_.size()) < helpers) {
        const int index = static_cast<int>(threads_.size());
        threads_.emplace_back([this, index] { serve(index); });
      }
      work_ = &work;
      wanted_ = helpers;
      running_ = helpers;
      ++generation_;
    }
    wake_.notify_all();
    work();
    {
      std::unique_lock<std::mutex> lock(mutex_);
      done_.wait(lock, [this] { return running_ == 0; });
      work_ = nullptr;
    }
    busy_.store(false);
    return true;
  }

 private:
  void serve(int index) {
    reserve_arena();
    std::uint64_t seen = 0;
    for (;;) {
      const std::function<void()>* work;
      {
        std::unique_lock<std::mutex> lock(mutex_);
        wake_.wait(lock, [&] { return generation_ != seen && index < wanted_; });
        seen = generation_;
        work = work_;
      }
      (*work)();
      {
        std::lock_guard<std::mutex> lock(mutex_);
        --running_;
      }
      done_.notify_one();
    }
  }

  // glibc gives each thread a malloc arena of its own, which grows by exactly what an allocation
  // lacks, one mprotect call at a time: about 3500 calls in a paper-scale run, each a page-table
  // change (expensive in a VM). One large block taken and given back at the thread's start leaves
  // the arena that much room (address space only: nothing is touched, and the executable's
  // M_TRIM_THRESHOLD keeps the room), so later allocations rarely grow it.
  static void reserve_arena() {
    constexpr std::size_t kRoom = std::size_t(24) << 20;  // below glibc's largest mmap threshold
    void* volatile room = std::malloc(kRoom);  // volatile: the pair must not be optimised away
    std::free(room);
  }

  std::atomic<bool> busy_{false};
  std::mutex mutex_;
  std::condition_variable wake_, done_;
  std::vector<std::thread> threads_;
  const std::function<void()>* work_ = nullptr;
  int wanted_ = 0;   // pool threads taking part in the current loop (the first `wanted_`)
  int running_ = 0;  // of those, still working
  std::uint64_t generation_ = 0;
};

}  // namespace

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
  const std::function<void()> worker = [&] {
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
  if (!WorkerPool::instance().run(threads - 1, worker)) {
    std::vector<std::thread> pool;
    for (int t = 1; t < threads; ++t) pool.emplace_back(worker);
    worker();
    for (std::thread& t : pool) t.join();
  }
  throw_if_interrupted();
  if (error) std::rethrow_exception(error);
}

void parallel_for_ranges(int count, int block, int threads, const std::function<void(int, int)>& body) {
  parallel_for((count + block - 1) / block, threads,
               [&](int k) { body(k * block, std::min(count, (k + 1) * block)); });
}

}  // namespace hairfit
