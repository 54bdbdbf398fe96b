// The Arnold tongues of the paper's fig. arnold (`bouncer tongues`), exactly. The period-p
// fixed points of eq. 5 (a flight of exactly p wall periods, launched and landing on the
// rising wall at the same phase theta*) have v* = a p / 2 (back at the same height after
// time p) and v* = 4(1+eps)/(1-eps) (eq. 2 with v^- = -v*, fdot = 4), so they lie on
//     a = 8 (1 + eps) / (p (1 - eps)),   p = 1, 2, ...
// (paper::fixed_point_a, analysis/periodic.hpp). proofs/fixed_point_family.cpp proved
// (README Claims, row 1) that the family is theta* in (fixed_point_theta_min, 1/2): all of
// (0, 1/2) iff eps >= 1/(4p-1), i.e. a <= 16/(2p-1) on the curve (the switch).
//
// Points are uniform in a within the window (exact rationals), eps = (a p - 8)/(a p + 8) is
// the inverse of the formula; no scalar type is involved. Implemented in
// lib/src/analysis/tongues.cpp.
#pragma once

#include <gmpxx.h>

#include <utility>
#include <vector>

#include "bouncer/scalar/decimal.hpp"
#include "bouncer/scalar/mpfr.hpp"

namespace bouncer {

struct TonguesRequest {
  long p_max = 10;    // curves p = 1..p_max
  long samples = 600; // points per curve, uniform in a (at least 2)
  std::pair<Decimal, Decimal> a_range{Decimal::from_int(0), Decimal::from_int(30)};
  std::pair<Decimal, Decimal> eps_range{Decimal::from_int(0), Decimal::from_int(1)};
};

struct TonguePoint {
  mpq_class a, eps;
  mpq_class theta_min;  // the lower end of the proved family (0 on the solid part)
  bool full = false;    // eps >= 1/(4p-1): the family is all of (0, 1/2) (solid)
  bool at_switch = false;  // the switch point itself (eps = 1/(4p-1), a = 16/(2p-1))
};

struct TongueCurve {
  long p = 1;
  std::vector<TonguePoint> points;  // by increasing a; empty when the curve misses the window
  mpq_class switch_a, switch_eps;   // 16/(2p-1) and 1/(4p-1), inside the window or not
};

struct Tongues {
  std::vector<TongueCurve> curves;  // p = 1..p_max
  long points = 0;                  // over all curves
};

// The curves p = 1..p_max inside the window: `samples` points uniform in a over the part of
// the window the curve crosses, plus the switch point when it is strictly inside.
Tongues arnold_tongues(const TonguesRequest& r);

// The sine wall's tongues (`bouncer tongues --wall sine`; docs/guide/sine-wall.md). Its
// period-p orbits (flight time p, v* = a p / 2, cos(2 pi theta*) = a p (1-eps) / (4 pi (1+eps)),
// derived in tests/test_sine_wall.cpp) exist for a <= a_sn and the one with
// sin(2 pi theta*) > 0 is stable for a_pd < a < a_sn:
//     a_sn(p, eps) = 4 pi (1+eps) / (p (1-eps))                       (saddle-node),
//     a_pd(p, eps) = 4 pi^2 (1+eps)^2 / sqrt(4 (1+eps^2)^2 + pi^2 p^2 (1-eps^2)^2)   (period doubling):
// tongues of positive width, where the triangle's eq. 5 curves have none. Points uniform in
// eps over the window (exact rationals; eps = 0 is left out, where every collision sticks,
// and eps = 1, where a_sn is infinite), both
// values computed at kSineTongueBits (a dozen rounded MPFR operations: a relative error of a
// few 2^-128, far below what a picture or a double shows).
constexpr long kSineTongueBits = 128;

struct SineTonguePoint {
  mpq_class eps;
  Mpfr a_pd, a_sn;
};

struct SineTongueCurve {
  long p = 1;
  std::vector<SineTonguePoint> points;  // by increasing eps
};

struct SineTongues {
  std::vector<SineTongueCurve> curves;  // p = 1..p_max
  long points = 0;
};

SineTongues sine_tongues(const TonguesRequest& r);

// The double nearest to q (mpq_class::get_d truncates).
double nearest_double(const mpq_class& q);

}  // namespace bouncer
