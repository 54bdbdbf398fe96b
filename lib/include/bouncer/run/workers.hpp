// Independent pieces of work on several threads: the workers share a queue (the caller's
// `work` takes the next piece until none is left), so fewer threads only take longer.
#pragma once

#include <functional>

namespace bouncer {

// Runs `work` on `count` threads (on the calling thread when count <= 1) and joins them all.
// A thread that cannot be created (a process or memory limit) is not an error: the workers
// already running take its share (none running: the calling thread does the work). Each
// thread frees MPFR's caches when it ends (scalar/thread_caches.hpp). `work`
// must catch its own exceptions (and stop its peers): one escaping a thread would end the
// process.
void run_workers(unsigned count, const std::function<void()>& work);

}  // namespace bouncer
