// bouncer continue --certify: the Krawczyk certifier (verify/periodic_certify.hpp) run on
// the branch side of a located border collision. In its own translation unit
// (cmd_continue_certify.cpp), so that cmd_continue.cpp needs no verify header.
#pragma once

#include <nlohmann/json.hpp>

#include <string>

#include "bouncer/model/spec.hpp"

namespace bouncer::cli {

struct EndToCertify {
  ModelSpec model;     // any value of the varied parameter (replaced by the range's end)
  Parameter vary = Parameter::a;
  long period = 1;
  std::string theta, v;  // the last orbit point on the branch side (decimal texts)
  std::string lo, hi;    // the parameter interval next to a*, on the branch side
  bool high_end = true;  // the branch lies below hi (high end) or above lo (low end)
};

// {"range": [lo, hi], "certified_to": c or null, "certified_range": [..] or null,
//  "theorem": ..., "pieces": n, "seconds": ...}; c is the end, nearest to a*, of the
// certified run of pieces that starts at the branch side of the interval.
nlohmann::ordered_json certify_end(const EndToCertify& e);

}  // namespace bouncer::cli
