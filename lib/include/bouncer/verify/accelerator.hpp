// Accelerator modes of the elastic map, proved in exact rational arithmetic.
//
// A lifted orbit P^Q(x) = x + (0, D) is an accelerator mode (it gains D every Q impacts
// forever) only where the map commutes with the shift along the whole orbit. For this map
// that happens on "ladders": every flight lands where it started. A flight from (theta0, v)
// that lasts exactly m whole periods lands at the launch phase and so at the launch height;
// energy then gives the landing velocity -v, and the elastic law v' = 2u - v^- gives
// v' = v + 2u (u the wall's velocity at theta0). The next flight lasts m + 4u/a periods, so
// the ladder continues forever iff
//   (1) the law is elastic and theta0 lies strictly inside a segment with u > 0, D = 2u;
//   (2) m0 = 2 v0 / a is a whole number and J = 2D/a = 4u/a is a whole number >= 1;
//   (3) no flight meets the wall before its end. The gap particle - wall over the flight k
//       is g_k(t) = h0 - f(theta0 + t) + a t (m_k - t)/2, concave on each wall segment, so:
//       flight 0 is checked exactly at every knot it passes and at both ends (v0 > u);
//       for k >= 1, on (0, 1] and [m_k - 1, m_k) g_k >= g_0 (m_k >= m0), and on
//       [1, m_k - 1] g_k >= a (m_1 - 1)/2 - (top - h0), checked exactly once.
// Every check is exact (GMP rationals from the exact decimals), so a certified ladder is a
// theorem: P^k(theta0, v0) = (theta0, v0 + kD) for every k >= 0. A start that fails a
// condition is reported with the condition (not a mode of this kind; nothing else claimed).
// All exact accelerator modes with Q > 1 whose flights each land at their launch phase are
// the same ladders, so Q = 1 is the only period asked for.
#pragma once

#include <gmpxx.h>

#include <string>

#include "bouncer/model/spec.hpp"

namespace bouncer {

struct LadderCertificate {
  bool certified = false;
  std::string statement;  // the theorem, or which condition fails
  mpq_class m0, J;        // flight periods of the first block, and their increase per block
  mpq_class u, D;         // wall velocity at theta0 and the gain 2u
  mpq_class min_gap;      // least gap of flight 0 at the knots it passes (exact)
};

// Throws InputError("model") for a model that is not elastic.
LadderCertificate certify_ladder(const ModelSpec& m, const InitialCondition& start, const Decimal& lift);

}  // namespace bouncer
