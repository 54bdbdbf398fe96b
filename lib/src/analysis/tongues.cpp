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

SineTongues sine_tongues(const TonguesRequest& r) {
  SineTongues t;
  const mpfr_prec_t bits = kSineTongueBits;
  Mpfr pi(bits), e(bits), x(bits), y(bits), num(bits);
  mpfr_const_pi(pi.get(), MPFR_RNDN);
  const mpq_class lo = r.eps_range.first.value(), hi = r.eps_range.second.value();
  const long n = r.samples;
  for (long p = 1; p <= r.p_max; ++p) {
    SineTongueCurve c;
    c.p = p;
    for (long i = 0; i < n; ++i) {
      const mpq_class eps = lo + (hi - lo) * i / (n - 1);
      if (eps <= 0 || eps >= 1) continue;  // eps = 0: every collision sticks; eps = 1: a_sn is infinite
      SineTonguePoint q{eps, Mpfr(bits), Mpfr(bits)};
      mpfr_set_q(e.get(), eps.get_mpq_t(), MPFR_RNDN);
      // a_sn = 4 pi (1 + e) / (p (1 - e))
      mpfr_add_ui(x.get(), e.get(), 1, MPFR_RNDN);
      mpfr_mul(num.get(), pi.get(), x.get(), MPFR_RNDN);
      mpfr_mul_ui(num.get(), num.get(), 4, MPFR_RNDN);
      mpfr_ui_sub(y.get(), 1, e.get(), MPFR_RNDN);
      mpfr_mul_ui(y.get(), y.get(), static_cast<unsigned long>(p), MPFR_RNDN);
      mpfr_div(q.a_sn.get(), num.get(), y.get(), MPFR_RNDN);
      // a_pd = 4 pi^2 (1 + e)^2 / sqrt(4 (1 + e^2)^2 + pi^2 p^2 (1 - e^2)^2)
      mpfr_mul(num.get(), num.get(), pi.get(), MPFR_RNDN);
      mpfr_mul(num.get(), num.get(), x.get(), MPFR_RNDN);  // 4 pi^2 (1 + e)^2
      mpfr_sqr(x.get(), e.get(), MPFR_RNDN);
      mpfr_ui_sub(y.get(), 1, x.get(), MPFR_RNDN);           // 1 - e^2
      mpfr_add_ui(x.get(), x.get(), 1, MPFR_RNDN);           // 1 + e^2
      mpfr_sqr(x.get(), x.get(), MPFR_RNDN);
      mpfr_mul_ui(x.get(), x.get(), 4, MPFR_RNDN);
      mpfr_mul(y.get(), y.get(), pi.get(), MPFR_RNDN);
      mpfr_mul_ui(y.get(), y.get(), static_cast<unsigned long>(p), MPFR_RNDN);
      mpfr_sqr(y.get(), y.get(), MPFR_RNDN);
      mpfr_add(x.get(), x.get(), y.get(), MPFR_RNDN);
      mpfr_sqrt(x.get(), x.get(), MPFR_RNDN);
      mpfr_div(q.a_pd.get(), num.get(), x.get(), MPFR_RNDN);
      c.points.push_back(std::move(q));
    }
    t.points += static_cast<long>(c.points.size());
    t.curves.push_back(std::move(c));
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
