// The request of `bouncer portrait` read from its options (scene + command line): the reader
// the command line (tools/cmd_portrait.cpp) and the Python module share, so that ranges,
// defaults and messages exist once. Throws InputError naming the option; the library's
// PortraitGrid then checks the request itself (run/portrait.hpp).
#pragma once

#include "bouncer/io/curve_figures.hpp"
#include "bouncer/io/scene.hpp"
#include "bouncer/run/portrait.hpp"

namespace bouncer {

// The orbits to compute and how the picture shows them (--polar, --theta-range, --v-range).
struct PortraitOptions {
  PortraitRequest request;
  PortraitView view;
};
PortraitOptions portrait_options(const Options& o);

}  // namespace bouncer
