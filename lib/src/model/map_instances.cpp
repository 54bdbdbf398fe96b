// The impact map's explicit instantiations, one scalar type per translation unit.
// lib/CMakeLists.txt compiles this file once for every type of a list of the scalar set
// (scalar/scalar_set.hpp), with BOUNCER_MAP_LIST naming the list, BOUNCER_MAP_INDEX the
// type's place in it and BOUNCER_MAP_COUNT the list's length as CMake knows it:
//   list 0, Scalars:           ImpactMap<T> and make_model<T> (and the batched step of double);
//   list 1, AnalysisScalars:   ImpactMap<Dual<T>> and make_model<Dual<T>> (Jacobians, Newton,
//                              Lyapunov exponents; analysis/jacobian.hpp);
//   list 2, EnclosureScalars:  ImpactMap<Dual<T>> (the Lohner enclosure; verify/enclosure.hpp).
// Why one type per unit: GCC's inliner has a budget per translation unit (--param
// inline-unit-growth). With the seven types in one unit it ran out, and the small operators
// of DoubleInterval, DoubleDouble, Dual<double> and Dual<DoubleInterval> were called, not
// inlined, inside their steps (-fopt-info-inline-missed: "inline-unit-growth limit
// reached"; in a scan 13% of the time went to calls of Dual<double>'s + - * /). Alone in
// its unit each step inlines them. The results are the same bit for bit: inlining moves
// no rounding (-ffp-contract=off, SSE2 doubles).
#include <tuple>
#include <type_traits>

#include "bouncer/model/impact_map_impl.hpp"
#include "bouncer/scalar/dual.hpp"
#include "bouncer/scalar/scalar_set.hpp"

#if !defined(BOUNCER_MAP_LIST) || !defined(BOUNCER_MAP_INDEX) || !defined(BOUNCER_MAP_COUNT)
#error "compiled only through lib/CMakeLists.txt (bouncer_map_instances), once per scalar type"
#endif

namespace bouncer {
namespace {
using Lists = std::tuple<Scalars, AnalysisScalars, EnclosureScalars>;
using List = std::tuple_element_t<BOUNCER_MAP_LIST, Lists>;
static_assert(std::tuple_size_v<List> == BOUNCER_MAP_COUNT,
              "lib/CMakeLists.txt compiles map_instances.cpp once per type of each list: its count "
              "(bouncer_map_instances) must be the list's length in scalar/scalar_set.hpp");
using T = std::tuple_element_t<BOUNCER_MAP_INDEX, List>;
}  // namespace

#if BOUNCER_MAP_LIST == 0
template class ImpactMap<T>;
template Model<T> make_model<T>(const ModelSpec&, long);
#if BOUNCER_MAP_INDEX == 0
static_assert(std::is_same_v<T, double>, "the batched step is double's: Scalars must start with double");
template unsigned ImpactMap<double>::step_n<kStepLanes>(const State<double>*, StepResult<double>*, Reason*) const;
#endif
#elif BOUNCER_MAP_LIST == 1
template class ImpactMap<Dual<T>>;
template Model<Dual<T>> make_model<Dual<T>>(const ModelSpec&, long);
#else
template class ImpactMap<Dual<T>>;
#endif

}  // namespace bouncer
