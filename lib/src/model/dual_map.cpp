// The impact map instantiated for dual numbers (forward-mode derivatives), from the same
// templated step as every other scalar type.
#include "bouncer/scalar/dual.hpp"
#include "bouncer/model/impact_map_impl.hpp"

namespace bouncer {

template class ImpactMap<Dual<double>>;
template class ImpactMap<Dual<Mpfr>>;
template class ImpactMap<Dual<long double>>;
template class ImpactMap<Dual<Quad>>;
template Model<Dual<double>> make_model<Dual<double>>(const ModelSpec&, long);
template Model<Dual<Mpfr>> make_model<Dual<Mpfr>>(const ModelSpec&, long);
template Model<Dual<long double>> make_model<Dual<long double>>(const ModelSpec&, long);
template Model<Dual<Quad>> make_model<Dual<Quad>>(const ModelSpec&, long);

}  // namespace bouncer
