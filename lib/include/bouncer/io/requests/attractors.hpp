// `bouncer attractors`: its request read from the options (scene + command line), with the
// ranges, defaults and messages of its options in one place. Throws InputError naming the
// option; find_attractors (run/attractors.hpp) checks the request itself too.
#pragma once

#include <optional>

#include "bouncer/io/scene.hpp"
#include "bouncer/run/attractors.hpp"
#include "bouncer/run/attractors_sweep.hpp"

namespace bouncer {

AttractorsRequest attractors_request(const Options& o);

// With --vary a|eps|c: the sweep (--range LO:HI, --values N in [2, 1000], default 11; the
// varied parameter's own option defaults to LO; --no-branches: the chains are not continued,
// --no-certify: their branches' ends are not proved); nothing without --vary.
std::optional<AttractorsSweepRequest> attractors_sweep_request(const Options& o);

}  // namespace bouncer
