// MPFR keeps caches (constants such as log 2, and a pool of mpz limbs) per thread. A
// worker thread that ends without freeing them leaks them: LeakSanitizer reports it, and a
// long-running host that starts many pools would grow. Every thread bouncer starts holds
// one MpfrThreadCaches for its whole life. The main thread's caches stay reachable until
// exit, so it needs none.
#pragma once

#include <mpfr.h>

namespace bouncer {

struct MpfrThreadCaches {
  MpfrThreadCaches() = default;
  MpfrThreadCaches(const MpfrThreadCaches&) = delete;
  MpfrThreadCaches& operator=(const MpfrThreadCaches&) = delete;
  ~MpfrThreadCaches() { mpfr_free_cache2(MPFR_FREE_LOCAL_CACHE); }
};

}  // namespace bouncer
