// Explicit instantiation of the impact map for the supported scalar set, so that tools
// and tests include only declarations and compile fast.
#include "bouncer/model/impact_map_impl.hpp"

namespace bouncer {

const char* name(EventKind k) {
  switch (k) {
    case EventKind::impact: return "impact";
    case EventKind::sticking: return "sticking";
    case EventKind::ride: return "ride";
  }
  return "?";
}

#define BOUNCER_INSTANTIATE(T)                                   \
  template class ImpactMap<T>;                                   \
  template Model<T> make_model<T>(const ModelSpec&, long);

BOUNCER_INSTANTIATE(double)
BOUNCER_INSTANTIATE(long double)
BOUNCER_INSTANTIATE(Quad)
BOUNCER_INSTANTIATE(Mpfr)
BOUNCER_INSTANTIATE(Mpfi)

#undef BOUNCER_INSTANTIATE

}  // namespace bouncer
