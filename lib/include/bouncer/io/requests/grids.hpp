// The requests of the grid commands read from their options (scene + command line): one
// reader per command, used by the command line (tools/cmd_basin.cpp, cmd_scan.cpp,
// cmd_bifurcation.cpp) and the Python module, so that their ranges, defaults and messages
// exist once. Each throws InputError naming the option; the library's grid then checks the
// request itself (run/basin.hpp, run/scan.hpp, run/bifurcation.hpp).
#pragma once

#include <optional>

#include "bouncer/io/scene.hpp"
#include "bouncer/run/basin.hpp"
#include "bouncer/run/bifurcation.hpp"
#include "bouncer/run/scan.hpp"

namespace bouncer {

// `bouncer basin`: the request, and whether --certify.
struct BasinOptions {
  BasinRequest request;
  bool certify = false;
};
BasinOptions basin_options(const Options& o);

// `bouncer scan`: the request, --certify, and what the picture shows.
struct ScanOptions {
  ScanRequest request;
  bool certify = false;
  std::optional<OrbitClass> show;   // none: "regular" (fixed + periodic)
  bool fixed_point_curves = false;  // --curves fixed-points: the paper's eq. 5 over the picture
};
ScanOptions scan_options(const Options& o);

// `bouncer bifurcation`: the request and what the picture shows.
struct BifurcationOptions {
  BifurcationRequest request;
  bool show_theta = true;  // --show theta | v
  long bins = 400;
};
BifurcationOptions bifurcation_options(const Options& o);

}  // namespace bouncer
