// `bouncer certify-sticking`'s request: what the command line
// (tools/cmd_certify_sticking.cpp) and bouncer.Model.certify_sticking (python/module.cpp)
// read from their options before they call certify_sticking or certify_sticking_range
// (verify/sticking.hpp). One reader: the ranges, defaults and messages of both are one text.
// --json and --out are the command's own.
#pragma once

#include "bouncer/io/scene.hpp"
#include "bouncer/verify/sticking.hpp"

namespace bouncer {

struct CertifyStickingRequest {
  // model (constant law only), start (--theta, --v), a_range (--a-range A0:A1 instead of
  // --a), max_steps, schedule (--max-bits, --start-bits), method, prove_attractor.
  StickingQuestion question;
  RangeOptions range;  // --max-depth, --max-pieces: only with --a-range
};

// The command's defaults that are option texts, filled in where not given: --model constant
// and the release state --theta 0.5 --v 4 (the provenance records them as inputs).
void certify_sticking_defaults(Options& o);

// certify_sticking_defaults, then validates every option above; throws InputError naming
// the option.
CertifyStickingRequest certify_sticking_request(const Options& given);

}  // namespace bouncer
