// `bouncer continue --certify`: the Krawczyk certifier (periodic_certify.hpp) run over a
// short parameter interval on the branch side of a located border collision. A certified
// run of pieces that starts at the branch side proves, for every parameter in it, a period-Q
// orbit with a fixed event sequence, so the branch reaches at least the run's inner end:
// a* >= that end at a high end, a* <= it at a low end. One side of the bracket only: past
// a* the orbit does not exist, and Krawczyk proves existence, not non-existence.
#pragma once

#include <gmpxx.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <optional>
#include <string>
#include <tuple>
#include <utility>

#include "bouncer/analysis/continuation.hpp"
#include "bouncer/model/spec.hpp"
#include "bouncer/scalar/traits.hpp"

namespace bouncer {

struct BranchEndQuestion {
  ModelSpec model;                // any value of the varied parameter (replaced by lo)
  Parameter vary = Parameter::a;
  long period = 1;
  InitialCondition last_point;    // the last orbit point on the branch side
  Decimal lo, hi;                 // the parameter interval next to a*, on the branch side
  bool high_end = true;           // the branch lies below hi (high end) or above lo (low end)
};

struct BranchEndCertificate {
  bool certified = false;  // a certified run of pieces starts at the branch side
  // When certified: the run [from, to], and its end nearest a* (to at a high end, from at a
  // low end), the one-sided bound on a*.
  mpq_class from, to, bound;
  std::string events;      // the certifier's event sequence on the piece at the branch side
  std::string theorem;     // certify_periodic_range's statement over [lo, hi]
  size_t pieces = 0;       // certification runs of the bisection
};

// The interval next to an end located in the bracket (bracket_lo, bracket_hi): width
// 1e-6 max(1, |g|) on the branch side of g, the bracket's end on the branch side (bracket_lo
// at a high end, bracket_hi at a low end), as the round-trip texts of T (lo, hi). span > 0:
// the branch's length, and the width at most span / 4, so that the interval stays on the
// branch (the period 1096 at veldep c = 1000 lives on a window of 8.9e-6 around a = 21;
// 1e-6 |a| would reach past its other end, where the orbit's events differ).
template <class T>
std::pair<std::string, std::string> branch_end_interval(const T& bracket_lo, const T& bracket_hi, bool high_end, long bits,
                                                        double span = 0) {
  using Tr = ScalarTraits<T>;
  const T& g = high_end ? bracket_lo : bracket_hi;
  double width = std::max(1.0, std::fabs(Tr::to_double(g))) * 1e-6;
  if (span > 0) width = std::min(width, span / 4);
  const T w = Tr::from_decimal(ScalarTraits<double>::to_string(width), bits);
  const T far = high_end ? T(g - w) : T(g + w);
  return {Tr::to_string(high_end ? far : g), Tr::to_string(high_end ? g : far)};
}

// Adaptive bisection of [lo, hi] (depth 10, at most 512 pieces, 64 to 256 bits: the pieces
// next to a* straddle the border and fail, and a short schedule bounds their cost).
BranchEndCertificate certify_branch_end(const BranchEndQuestion& q);

}  // namespace bouncer
