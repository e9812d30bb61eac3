#pragma once
// Running work on a number of threads the caller asked for.

#include <algorithm>

#include <tbb/info.h>
#include <tbb/task_arena.h>

namespace batchccd {

// Runs `work` with `threads` workers: in an arena of that many, or in the
// caller's arena when it asks for none (0 or negative). The arena is capped at
// the processors this process may use: TBB would not start more workers
// anyway, and asking for more prints a warning on stderr.
template <class Work>
void in_arena(int threads, const Work& work) {
  if (threads > 0) {
    tbb::task_arena arena(std::min(threads, tbb::info::default_concurrency()));
    arena.execute(work);
  } else {
    work();
  }
}

}  // namespace batchccd
