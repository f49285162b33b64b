// Deterministic parallel loops: items are handed out in small chunks and every item writes
// only its own, index-addressed output, so results never depend on the number of threads.
#pragma once
#include <functional>

namespace hairfit {

// Calls body(i) for every i in [0, count) on up to `threads` threads (1 = the calling thread only).
// If items throw, the exception of the lowest failing index is rethrown after all have run.
// After SIGINT or SIGTERM no new item starts and Interrupted is thrown (core/interrupt.h).
void parallel_for(int count, int threads, const std::function<void(int)>& body);

// Calls body(begin, end) for consecutive ranges of at most `block` items covering [0, count), as
// parallel_for calls its items: for loops whose items are too cheap for a call each, or that want
// scratch space per range.
void parallel_for_ranges(int count, int block, int threads, const std::function<void(int, int)>& body);

// The number of threads to use when the user asked for `requested` (0 = all hardware threads).
int resolve_thread_count(int requested);

}  // namespace hairfit
