// `bouncer certify-periodic`'s request: what the command line
// (tools/cmd_certify_periodic.cpp) and bouncer.Model.certify_periodic (python/module.cpp)
// read from their options before they call certify_periodic, certify_periodic_range
// (verify/periodic_certify.hpp) or certify_ladder (verify/accelerator.hpp). One reader: the
// ranges, defaults and messages of both are one text. --json and --out are the command's own.
#pragma once

#include <optional>

#include "bouncer/io/scene.hpp"
#include "bouncer/verify/periodic_certify.hpp"

namespace bouncer {

struct CertifyPeriodicRequest {
  // model, period (--period Q, required, in [1, kMaxCertifiedPeriod = 2000]), guess, vary (--vary, or the
  // parameter of --a-range | --eps-range | --c-range, at most one, instead of its value),
  // range, family, schedule (--max-bits, --start-bits), max_depth and max_pieces (with a
  // range only), newton (--max-iter, --grid).
  PeriodicQuestion question;
  // --lift D: an accelerator ladder P(x) = x + (0, D), proved in exact arithmetic (elastic
  // law, period 1, with --guess, no range).
  std::optional<Decimal> lift;
};

// Validates every option above; throws InputError naming the option.
CertifyPeriodicRequest certify_periodic_request(const Options& o);

}  // namespace bouncer
