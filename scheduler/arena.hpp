#pragma once
// Running work on a number of threads the caller asked for.

#include <algorithm>
#include <memory>
#include <vector>

#include <tbb/info.h>
#include <tbb/task_arena.h>

namespace batchccd {

// The calling thread's arena of `threads` workers, made on its first call
// and kept for the next ones: an arena made per call allocates its slots
// every call (a frame loop must not), and one per calling thread keeps
// calls from several host threads as independent as before.
inline tbb::task_arena& arena_of(int threads) {
  thread_local std::vector<std::unique_ptr<tbb::task_arena>> arenas;  // by thread count
  const auto slot = static_cast<std::size_t>(threads);
  if (arenas.size() <= slot) arenas.resize(slot + 1);
  if (!arenas[slot]) arenas[slot] = std::make_unique<tbb::task_arena>(threads);
  return *arenas[slot];
}

// Runs `work` with `threads` workers: in an arena of that many, or in the
// caller's arena when it asks for none (0 or negative). The arena is capped at
// the processors this process may use: TBB would not start more workers
// anyway, and asking for more prints a warning on stderr.
template <class Work>
void in_arena(int threads, const Work& work) {
  if (threads > 0) {
    arena_of(std::min(threads, tbb::info::default_concurrency())).execute(work);
  } else {
    work();
  }
}

}  // namespace batchccd
