// The request of `bouncer lyapunov --vary` (exponent curves) read from its options (scene +
// command line): the reader the command line (tools/cmd_lyapunov.cpp) and the Python module
// share, so that ranges, defaults and messages exist once. Throws InputError naming the
// option; the library's ExponentCurveGrid then checks the request itself and computes the
// starts (run/exponent_curve.hpp).
#pragma once

#include "bouncer/io/scene.hpp"
#include "bouncer/run/exponent_curve.hpp"

namespace bouncer {

// --vary (required), --range (required), --samples (100), --ics (1), --theta/--v (the first
// start; both or neither), the exponent's --transient (1000), --steps (10000), --blocks (20),
// the classifier's --max-period and --recheck-factor (its transient 0, steps 500), --precision.
ExponentCurveRequest exponent_curve_request(const Options& o);

}  // namespace bouncer
