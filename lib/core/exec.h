// How a stage's loops run, apart from what they compute: the threads and who hears of progress.
// Neither ever changes a result. Interruption needs nothing here: parallel_for checks the
// process's flag (core/interrupt.h).
#pragma once
#include "core/progress.h"

namespace hairfit {

struct Exec {
  int threads = 1;            // ≥ 1
  ProgressCallback progress;  // items finished so far; empty: nobody listens
};

}  // namespace hairfit
