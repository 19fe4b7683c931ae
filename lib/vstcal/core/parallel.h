// Runs independent tasks on a few threads. Determinism is the caller's contract: each task writes
// only its own outputs, and any reduction over tasks happens afterwards in task order — so results
// never depend on the thread count or on which thread ran which task.
#pragma once

#include <cstddef>
#include <functional>

namespace vstcal {

// Threads to use for `requested` (0 → std::thread::hardware_concurrency(), at least 1).
unsigned ResolveThreads(unsigned requested);

// Calls task(t) for every t in [0, num_tasks) on up to `threads` threads (0 → all cores). The
// first exception a task throws is rethrown here after every thread has stopped (an exception
// escaping a std::thread would abort the process; the library never aborts).
void ParallelFor(size_t num_tasks, unsigned threads, const std::function<void(size_t task)>& task);

}  // namespace vstcal
