// Explicit instantiation of the impact map for the scalar set (scalar/scalar_set.hpp), so
// that tools and tests include only declarations and compile fast.
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

#define BOUNCER_X(T, kind)           \
  template class ImpactMap<T>;       \
  template Model<T> make_model<T>(const ModelSpec&, long);
BOUNCER_FOR_EACH_SCALAR(BOUNCER_X)
#undef BOUNCER_X
template unsigned ImpactMap<double>::step_n<kStepLanes>(const State<double>*, StepResult<double>*, Reason*) const;

}  // namespace bouncer
