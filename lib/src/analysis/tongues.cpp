// The Arnold tongues (analysis/tongues.hpp): eq. 5's curves in (a, eps), exactly.
#include "bouncer/analysis/tongues.hpp"

#include <mpfr.h>

#include "bouncer/analysis/periodic.hpp"

namespace bouncer {

namespace {

// The curve of period p inside the window, or no points: uniform in a, plus the switch
// point eps = 1/(4p-1) when it is inside.
TongueCurve curve(const TonguesRequest& r, long p) {
  TongueCurve c;
  c.p = p;
  c.switch_eps = mpq_class(1, 4 * p - 1);
  c.switch_a = mpq_class(16, 2 * p - 1);
  const mpq_class alo = r.a_range.first.value(), ahi = r.a_range.second.value();
  const mpq_class elo = r.eps_range.first.value(), ehi = r.eps_range.second.value();
  // eps(a) increases with a; eps < 1 for every finite a, and eps >= 0 iff a >= 8/p.
  mpq_class lo = alo, hi = ahi;
  const mpq_class a_at_elo = paper::fixed_point_a(elo, p);
  if (lo < a_at_elo) lo = a_at_elo;
  if (ehi < 1) {
    const mpq_class a_at_ehi = paper::fixed_point_a(ehi, p);
    if (a_at_ehi < hi) hi = a_at_ehi;
  }
  if (!(lo < hi)) return c;
  auto add = [&](const mpq_class& a, const mpq_class& eps) {
    c.points.push_back({a, eps, fixed_point_theta_min(eps, p), eps >= c.switch_eps, eps == c.switch_eps});
  };
  bool switch_done = !(lo < c.switch_a && c.switch_a < hi);
  const long n = r.samples;
  for (long i = 0; i < n; ++i) {
    const mpq_class a = lo + (hi - lo) * i / (n - 1);
    if (!switch_done && c.switch_a < a) {
      add(c.switch_a, c.switch_eps);
      switch_done = true;
    }
    add(a, paper::fixed_point_eps(a, p));
  }
  return c;
}

}  // namespace

Tongues arnold_tongues(const TonguesRequest& r) {
  Tongues t;
  for (long p = 1; p <= r.p_max; ++p) {
    t.curves.push_back(curve(r, p));
    t.points += static_cast<long>(t.curves.back().points.size());
  }
  return t;
}

double nearest_double(const mpq_class& q) {
  mpfr_t x;
  mpfr_init2(x, 53);
  mpfr_set_q(x, q.get_mpq_t(), MPFR_RNDN);
  const double d = mpfr_get_d(x, MPFR_RNDN);
  mpfr_clear(x);
  return d;
}

}  // namespace bouncer
