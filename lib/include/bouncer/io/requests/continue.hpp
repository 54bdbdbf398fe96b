// `bouncer continue`'s request: what the command line (tools/cmd_continue.cpp) and
// bouncer.Model.continue_branch (python/module.cpp) read from their options before they call
// continue_branch (analysis/continuation.hpp). One reader, so that the ranges, defaults and
// messages of both are the same text. The picture options (--show, --out, --format, ...)
// are the command's own.
#pragma once

#include "bouncer/analysis/continuation.hpp"
#include "bouncer/io/scene.hpp"

namespace bouncer {

struct ContinueRequest {
  ModelSpec model;               // at the start value of the varied parameter
  Parameter vary = Parameter::a; // --vary a (default) | eps (constant law) | c (veldep law)
  Decimal lo, hi;                // --range LO:HI (required), both valid models, start inside
  long period = 0;               // --period Q (required), in [1, kMaxBranchPeriod = 2000]
  InitialCondition guess;        // --guess THETA,V (required), a valid state of the model
  Precision precision;           // --precision: an analysis scalar (default double)
  ContinuationOptions opt;       // --step, --max-points, --max-iter, --beyond, the classifier
  bool certify = false;          // --certify: Krawczyk on the branch side of each border end
};

// Validates every option above; throws InputError naming the option. The varied parameter
// defaults to the range's low end (default_to_range_start).
ContinueRequest continue_request(const Options& given);

}  // namespace bouncer
