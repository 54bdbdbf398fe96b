// `bouncer attractors`: its request read from the options (scene + command line), with the
// ranges, defaults and messages of its options in one place. Throws InputError naming the
// option; find_attractors (run/attractors.hpp) checks the request itself too.
#pragma once

#include "bouncer/io/scene.hpp"
#include "bouncer/run/attractors.hpp"

namespace bouncer {

AttractorsRequest attractors_request(const Options& o);

}  // namespace bouncer
