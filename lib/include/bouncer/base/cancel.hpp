// Cooperative cancellation, for hosts that run bouncer inside their own process (the Python
// module: Ctrl-C in a notebook). A host gives the computation on its thread a flag with
// CancelScope; the long loops (orbit steps, certified steps, grid points, sweep precisions)
// call throw_if_cancelled(), which throws Cancelled once the flag is set. Cancelled unwinds
// like any error: output sets are written all or none, so no partial file is left behind.
// The grid runner hands its caller's flag to its worker threads. With no scope (the
// command-line tool, which ends on a signal instead: base/output.hpp) the check is one
// thread-local load.
#pragma once

#include <atomic>
#include <stdexcept>

namespace bouncer {

class Cancelled : public std::runtime_error {
 public:
  Cancelled() : std::runtime_error("interrupted") {}
};

namespace detail {
inline thread_local const std::atomic<bool>* cancel_flag = nullptr;
}

// The flag of the computation on this thread (nullptr: none).
inline const std::atomic<bool>* current_cancel_flag() { return detail::cancel_flag; }

// Sets this thread's flag for the scope's life (nullptr clears it).
class CancelScope {
 public:
  explicit CancelScope(const std::atomic<bool>* flag) : previous_(detail::cancel_flag) { detail::cancel_flag = flag; }
  ~CancelScope() { detail::cancel_flag = previous_; }
  CancelScope(const CancelScope&) = delete;
  CancelScope& operator=(const CancelScope&) = delete;

 private:
  const std::atomic<bool>* previous_;
};

inline void throw_if_cancelled() {
  const std::atomic<bool>* f = detail::cancel_flag;
  if (f && f->load(std::memory_order_relaxed)) throw Cancelled();
}

// For per-step loops: checks every 256th step only.
inline void throw_if_cancelled(long long step) {
  if ((step & 255) == 0) throw_if_cancelled();
}

}  // namespace bouncer
