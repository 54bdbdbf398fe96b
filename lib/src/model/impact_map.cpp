// What of the impact map is not a template. Its explicit instantiations, so that tools and
// tests include only declarations and compile fast, are in map_instances.cpp (one scalar
// type per translation unit; that file says why).
#include "bouncer/model/impact_map.hpp"

namespace bouncer {

const char* name(EventKind k) {
  switch (k) {
    case EventKind::impact: return "impact";
    case EventKind::sticking: return "sticking";
    case EventKind::ride: return "ride";
  }
  return "?";
}

}  // namespace bouncer
