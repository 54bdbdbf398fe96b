// The impact map instantiated for dual numbers (forward-mode derivatives) over the analysis
// scalars (scalar/scalar_set.hpp), from the same templated step as every other scalar type.
// (Dual<S> over the enclosure scalars: lib/src/verify/enclosure.cpp.)
#include "bouncer/scalar/dual.hpp"
#include "bouncer/model/impact_map_impl.hpp"

namespace bouncer {

#define BOUNCER_X(S, kind)            \
  template class ImpactMap<Dual<S>>;  \
  template Model<Dual<S>> make_model<Dual<S>>(const ModelSpec&, long);
BOUNCER_FOR_EACH_ANALYSIS_SCALAR(BOUNCER_X)
#undef BOUNCER_X

}  // namespace bouncer
