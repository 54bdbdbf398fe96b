// The guess THETA,V of periodic, continue and certify-periodic: two decimals, a valid state
// of the model (InputError names --guess). Shared by their request readers, the command
// line and the Python module.
#pragma once

#include <optional>

#include "bouncer/io/scene.hpp"

namespace bouncer {

// nullopt when --guess is not given.
std::optional<InitialCondition> guess_from(const Options& o, const ModelSpec& spec);

}  // namespace bouncer
