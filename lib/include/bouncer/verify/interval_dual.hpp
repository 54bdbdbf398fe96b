// Dual<Mpfi>: forward-mode derivatives evaluated in interval arithmetic. Evaluated on a box
// X, the derivative components enclose the Jacobian of the branch over all of X (every
// branch is decided for the whole box through the three-valued predicates, so the step is
// one smooth formula on X). Used by the Lohner enclosure (verify/enclosure.hpp).
//
// Its traits are the generic ScalarTraits<Dual<S>> of scalar/dual.hpp (an IntervalScalar,
// since Mpfi is one); this header only names the type and declares the step's explicit
// instantiation.
#pragma once

#include "bouncer/model/impact_map.hpp"
#include "bouncer/scalar/dual.hpp"
#include "bouncer/scalar/scalar_set.hpp"

namespace bouncer {

using IDual = Dual<Mpfi>;

// The step for interval duals (over the enclosure scalars of scalar/scalar_set.hpp) is
// instantiated once, in lib/src/model/map_instances.cpp.
#define BOUNCER_X(S, kind) extern template class ImpactMap<Dual<S>>;
BOUNCER_FOR_EACH_ENCLOSURE_SCALAR(BOUNCER_X)
#undef BOUNCER_X

}  // namespace bouncer
