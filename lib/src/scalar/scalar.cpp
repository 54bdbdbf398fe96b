#include <quadmath.h>

#include <algorithm>
#include <charconv>
#include <cstdlib>
#include <limits>
#include <stdexcept>
#include <string>

#include <qd/dd_real.h>

#include "bouncer/scalar/decimal.hpp"
#include "bouncer/scalar/shortest.hpp"
#include "bouncer/scalar/traits.hpp"

namespace bouncer {

const char* describe(Reason r) {
  switch (r) {
    case Reason::phase_at_corner: return "theta's enclosure straddles a wall corner";
    case Reason::impact_at_corner: return "the impact time straddles the end of a wall segment";
    case Reason::corner_approach: return "at a corner hit, approach or separation is undecided";
    case Reason::sticking_threshold: return "the velocity straddles the sticking threshold xi";
    case Reason::riding: return "the relative velocity straddles zero (riding the wall or flying)";
    case Reason::period_boundary: return "theta + flight time straddles a whole period";
    case Reason::walk_limit: return "the flight crosses more wall segments than the walk allows";
    case Reason::grazing: return "the flight may graze the smooth wall before its impact (the first root is undecided)";
    case Reason::nonfinite: return "a value is NaN or infinite (overflow)";
  }
  return "unknown reason";
}

void throw_undecided(Truth t, Reason where) {
  throw Undecided(t == Truth::invalid ? Reason::nonfinite : where);
}

namespace {

[[noreturn]] void bad_decimal(std::string_view text) {
  throw std::invalid_argument("not a decimal number: '" + std::string(text) + "'");
}

}  // namespace

std::string mpfr_to_string(mpfr_srcptr x, mpfr_rnd_t rnd) {
  // Enough digits that reading the string back at this precision gives x again.
  return mpfr_to_string_digits(x, rnd, mpfr_get_str_ndigits(10, mpfr_get_prec(x)));
}

std::string mpfr_to_string_digits(mpfr_srcptr x, mpfr_rnd_t rnd, size_t digits) {
  if (mpfr_nan_p(x)) return "nan";
  if (mpfr_inf_p(x)) return mpfr_sgn(x) > 0 ? "inf" : "-inf";
  if (mpfr_zero_p(x)) return mpfr_signbit(x) ? "-0" : "0";
  mpfr_exp_t e = 0;
  char* s = mpfr_get_str(nullptr, &e, 10, digits, x, rnd);
  std::string m(s);
  mpfr_free_str(s);
  std::string sign;
  if (m[0] == '-') { sign = "-"; m.erase(0, 1); }
  // m = d1 d2 ... dn, value = 0.d1d2...dn * 10^e. Plain notation for moderate exponents
  // (like %g), scientific otherwise; trailing zeros of the fraction are cut.
  while (m.size() > 1 && m.back() == '0') m.pop_back();
  const long n = static_cast<long>(m.size());
  std::string out = sign;
  if (e > -6 && e <= 21) {
    // Appended piece by piece (operator+ on temporaries trips GCC 12's -Wrestrict).
    if (e <= 0) {
      out += "0.";
      out.append(static_cast<size_t>(-e), '0');
      out += m;
    } else if (e < n) {
      out.append(m, 0, static_cast<size_t>(e));
      out += '.';
      out.append(m, static_cast<size_t>(e));
    } else {
      out += m;
      out.append(static_cast<size_t>(e - n), '0');
    }
  } else {
    out += m[0];
    if (n > 1) {
      out += '.';
      out.append(m, 1);
    }
    out += 'e';
    out += std::to_string(static_cast<long>(e - 1));
  }
  return out;
}

double ScalarTraits<double>::from_decimal(std::string_view text, long) {
  std::string s(text);
  char* end = nullptr;
  const double x = std::strtod(s.c_str(), &end);  // correctly rounded (glibc)
  if (s.empty() || *end != '\0') bad_decimal(text);
  return x;
}

std::string ScalarTraits<double>::to_string(const double& x) {
  char buf[kShortestChars];
  return std::string(buf, shortest_chars(buf, x));  // shortest string that round-trips
}

long double ScalarTraits<long double>::from_decimal(std::string_view text, long) {
  std::string s(text);
  char* end = nullptr;
  const long double x = std::strtold(s.c_str(), &end);
  if (s.empty() || *end != '\0') bad_decimal(text);
  return x;
}

std::string ScalarTraits<long double>::to_string(const long double& x) {
  char buf[96];
  auto r = std::to_chars(buf, buf + sizeof buf, x);
  return std::string(buf, r.ptr);
}

Quad ScalarTraits<Quad>::from_decimal(std::string_view text, long) {
  std::string s(text);
  char* end = nullptr;
  const __float128 x = strtoflt128(s.c_str(), &end);
  if (s.empty() || *end != '\0') bad_decimal(text);
  return Quad(x);
}

Quad ScalarTraits<Quad>::below(const Quad& x) {
  // -infinity: HUGE_VALQ is a GCC builtin that clang lacks (the fuzzing build, tests/fuzz/).
  return Quad(nextafterq(x.backend().value(), static_cast<__float128>(-std::numeric_limits<double>::infinity())));
}

int ScalarTraits<Quad>::exponent(const Quad& x) {
  int e = 0;
  frexpq(x.backend().value(), &e);
  return e;
}

Quad ScalarTraits<Quad>::pow_3_5(const Quad& x) {
  return Quad(powq(x.backend().value(), strtoflt128("0.6", nullptr)));
}

std::string ScalarTraits<Quad>::to_string(const Quad& x) {
  char buf[128];
  // 113-bit significand: 36 significant digits always round-trip.
  quadmath_snprintf(buf, sizeof buf, "%.35Qe", x.backend().value());
  return buf;
}

Mpfr ScalarTraits<Mpfr>::from_decimal(std::string_view text, long bits) {
  Mpfr x(bits);
  if (!x.set_decimal(text)) bad_decimal(text);
  return x;
}

Mpfr ScalarTraits<Mpfr>::pow_3_5(const Mpfr& x) {
  // (x^3)^(1/5): two correctly rounded operations, no inexact exponent 0.6.
  Mpfr r(x.bits());
  mpfr_pow_ui(r.get(), x.get(), 3, MPFR_RNDN);
  mpfr_rootn_ui(r.get(), r.get(), 5, MPFR_RNDN);
  return r;
}

Mpfi ScalarTraits<Mpfi>::from_decimal(std::string_view text, long bits) {
  Mpfi x(bits);
  if (!x.set_decimal(text)) bad_decimal(text);
  return x;
}

Truth ScalarTraits<Mpfi>::lt(const Mpfi& x, const Mpfi& y) {
  if (x.has_nan() || y.has_nan()) return Truth::invalid;
  if (mpfr_less_p(&x.get()->right, &y.get()->left)) return Truth::yes;
  if (mpfr_greaterequal_p(&x.get()->left, &y.get()->right)) return Truth::no;
  return Truth::unknown;
}

Truth ScalarTraits<Mpfi>::le(const Mpfi& x, const Mpfi& y) {
  if (x.has_nan() || y.has_nan()) return Truth::invalid;
  if (mpfr_lessequal_p(&x.get()->right, &y.get()->left)) return Truth::yes;
  if (mpfr_greater_p(&x.get()->left, &y.get()->right)) return Truth::no;
  return Truth::unknown;
}

Truth ScalarTraits<Mpfi>::is_zero(const Mpfi& x) {
  if (x.has_nan()) return Truth::invalid;
  if (mpfr_zero_p(&x.get()->left) && mpfr_zero_p(&x.get()->right)) return Truth::yes;
  if (!mpfi_has_zero(x.get())) return Truth::no;
  return Truth::unknown;
}

Mpfi ScalarTraits<Mpfi>::nonneg(const Mpfi& x) {
  if (mpfr_sgn(&x.get()->left) >= 0) return x;
  Mpfr zero(0, x.bits());
  Mpfr hi = x.upper();
  if (mpfr_sgn(hi.get()) < 0) hi = zero;  // cannot happen for a true non-negative value
  return Mpfi(zero, hi);
}

Mpfi ScalarTraits<Mpfi>::pow_3_5(const Mpfi& x) {
  // x^(3/5) = exp(3/5 * log x) for x > 0, with 3/5 itself enclosed; x = 0 gives 0.
  if (certainly(is_zero(x))) return x;
  Mpfi lo_part = nonneg(x);
  if (mpfr_zero_p(&lo_part.get()->left)) {
    // Monotone: enclose by the values at the ends, the lower end being 0.
    Mpfi up(lo_part.upper(), lo_part.upper());
    Mpfi r = exp(Mpfi(3, x.bits()) / 5 * log(up));
    return Mpfi(Mpfr(0, x.bits()), r.upper());
  }
  return exp(Mpfi(3, x.bits()) / 5 * log(lo_part));
}

std::string ScalarTraits<Mpfi>::lower_string(const Mpfi& x) { return mpfr_to_string(&x.get()->left, MPFR_RNDD); }
std::string ScalarTraits<Mpfi>::upper_string(const Mpfi& x) { return mpfr_to_string(&x.get()->right, MPFR_RNDU); }
std::string ScalarTraits<Mpfi>::to_string(const Mpfi& x) {
  std::string s = "[";  // appended piece by piece: "[" + temporary trips GCC 12's -Wrestrict
  s += lower_string(x);
  s += ", ";
  s += upper_string(x);
  s += ']';
  return s;
}

// ---- dd (scalar/double_double.hpp) ------------------------------------------------------

namespace {

dd_real to_qd(const DoubleDouble& x) { return dd_real(x.hi(), x.lo()); }
DoubleDouble from_qd(const dd_real& x) { return DoubleDouble::from_pair(x.x[0], x.x[1]); }

}  // namespace

DoubleDouble exp(const DoubleDouble& x) {
  if (x.is_nan()) return DoubleDouble::nan_value();
  return from_qd(exp(to_qd(x)));
}

DoubleDouble log(const DoubleDouble& x) {
  // Guarded here: QD prints a message on stderr for a non-positive argument.
  if (x.is_nan() || x.hi() < 0) return DoubleDouble::nan_value();
  if (x.hi() == 0) return DoubleDouble(-std::numeric_limits<double>::infinity());
  return from_qd(log(to_qd(x)));
}

DoubleDouble ScalarTraits<DoubleDouble>::from_decimal(std::string_view text, long) {
  const std::optional<Decimal> d = Decimal::parse(text);
  if (!d) bad_decimal(text);
  // hi = RN(d), lo = RN(d - hi): mpfr_set_q rounds an exact rational correctly.
  mpfr_t t;
  mpfr_init2(t, 53);
  mpfr_set_q(t, d->value().get_mpq_t(), MPFR_RNDN);
  const double hi = mpfr_get_d(t, MPFR_RNDN);  // exact (a 53-bit number)
  const mpq_class rest = d->value() - mpq_class(hi);
  mpfr_set_q(t, rest.get_mpq_t(), MPFR_RNDN);
  const double lo = mpfr_get_d(t, MPFR_RNDN);
  mpfr_clear(t);
  return DoubleDouble::from_pair(hi, lo);
}

DoubleDouble ScalarTraits<DoubleDouble>::pow_3_5(const DoubleDouble& x) {
  // (x^3)^(1/5), as for Mpfr: QD's nroot (measured up to 125 units of 2^-106 off), then one
  // Newton step r - (r^5 - y) / (5 r^4) in dd, which brings it to a few units.
  if (x.is_nan() || x.hi() < 0) return DoubleDouble::nan_value();
  if (x.hi() == 0) return DoubleDouble();
  const DoubleDouble y = x * x * x;
  const DoubleDouble r = from_qd(nroot(to_qd(y), 5));
  const DoubleDouble r2 = r * r, r4 = r2 * r2;
  return r - (r4 * r - y) / (5L * r4);
}

std::string ScalarTraits<DoubleDouble>::to_string(const DoubleDouble& x) {
  if (!x.is_finite() || x.hi() == 0) {
    mpfr_t t;
    mpfr_init2(t, 53);
    mpfr_set_d(t, x.hi(), MPFR_RNDN);
    std::string s = mpfr_to_string(t, MPFR_RNDN);
    mpfr_clear(t);
    return s;
  }
  // The exact value hi + lo, in as many bits as the pair spans.
  int eh = 0, el = 0;
  std::frexp(x.hi(), &eh);
  if (x.lo() != 0) std::frexp(x.lo(), &el);
  const mpfr_prec_t prec = x.lo() == 0 ? 53 : 53 + std::max(0, eh - el) + 1;
  mpfr_t v;
  mpfr_init2(v, prec);
  mpfr_set_d(v, x.hi(), MPFR_RNDN);
  mpfr_add_d(v, v, x.lo(), MPFR_RNDN);  // exact
  // Digits: those that read back to the same P-bit number (P = the bits the pair spans;
  // mpfr_get_str_ndigits), which then reads back to the same pair unless the value sits
  // within 2^-P of a tie of the double grid; up to four fewer are tried first (often enough)
  // and more after, doubling past 2P digits, where the string is the exact (dyadic, finite)
  // value: then hi = RN(value) and lo = value - hi, the same canonical pair.
  const size_t exact_at_p = mpfr_get_str_ndigits(10, prec);
  std::string s;
  for (size_t n = std::max<size_t>(17, exact_at_p - 4);; n = n < 2 * exact_at_p ? n + 1 : 2 * n) {
    s = mpfr_to_string_digits(v, MPFR_RNDN, n);
    if (from_decimal(s, 106) == x || n > 8192) break;
  }
  mpfr_clear(v);
  return s;
}

// ---- interval:double (scalar/interval_double.hpp) --------------------------------------

namespace {

std::string double_to_string(double x, mpfr_rnd_t rnd) {
  mpfr_t t;
  mpfr_init2(t, 53);
  mpfr_set_d(t, x, MPFR_RNDN);  // exact
  std::string s = mpfr_to_string(t, rnd);
  mpfr_clear(t);
  return s;
}

}  // namespace

// exp and log: scalar/interval_elementary.cpp (double arithmetic, MPFR as fallback).

DoubleInterval ScalarTraits<DoubleInterval>::from_decimal(std::string_view text, long) {
  std::string s(text);
  if (s.empty()) bad_decimal(text);
  mpfr_t lo, hi;
  mpfr_init2(lo, 53);
  mpfr_init2(hi, 53);
  char* end = nullptr;
  mpfr_strtofr(lo, s.c_str(), &end, 10, MPFR_RNDD);
  const bool ok = end && *end == '\0';
  mpfr_strtofr(hi, s.c_str(), &end, 10, MPFR_RNDU);
  const DoubleInterval r(mpfr_get_d(lo, MPFR_RNDD), mpfr_get_d(hi, MPFR_RNDU));
  mpfr_clear(lo);
  mpfr_clear(hi);
  if (!ok) bad_decimal(text);
  return r;
}

DoubleInterval ScalarTraits<DoubleInterval>::pow_3_5(const DoubleInterval& x) {
  // As for Mpfi: exp(3/5 log x) with 3/5 enclosed; an enclosure touching 0 gives
  // [0, upper^(3/5)] by monotonicity.
  if (certainly(is_zero(x))) return x;
  const DoubleInterval e = DoubleInterval(3L) / 5L;
  const DoubleInterval p = nonneg(x);
  if (p.lower() == 0) return {0.0, exp(e * log(DoubleInterval(p.upper(), p.upper()))).upper()};
  return exp(e * log(p));
}

std::string ScalarTraits<DoubleInterval>::lower_string(const DoubleInterval& x) { return double_to_string(x.lower(), MPFR_RNDD); }
std::string ScalarTraits<DoubleInterval>::upper_string(const DoubleInterval& x) { return double_to_string(x.upper(), MPFR_RNDU); }
std::string ScalarTraits<DoubleInterval>::to_string(const DoubleInterval& x) {
  std::string s = "[";
  s += lower_string(x);
  s += ", ";
  s += upper_string(x);
  s += ']';
  return s;
}

// ---- sin(2 pi x) and cos(2 pi x) (the sine wall) ----------------------------------------

namespace {

// [lo, hi] (in turns, exact MPFR ends) -> an enclosure [out_lo, out_hi] of sin(2 pi x)
// (cosine = false) or cos(2 pi x) over it, each end rounded outward at out's precision.
// MPFR's sinpi/cospi of 2x are correctly rounded and 2x is exact, so no rounded pi enters.
// Between the ends the function is monotone unless a maximum (x = 1/4 + k for the sine, k
// for the cosine) or a minimum (3/4 + k, 1/2 + k) lies in [lo, hi]; the extremum test rounds
// the candidate k down, which can only admit an extremum (a wider, still valid enclosure).
// Scratch variables of trig_2pi_enclosure, one set per thread, set up once (mpfr_set_prec
// reuses their limbs: a step calls the enclosure dozens of times).
struct TrigScratch {
  mpfr_t x2, at_lo, at_hi, k, c;
  TrigScratch() { mpfr_inits2(64, x2, at_lo, at_hi, k, c, (mpfr_ptr)nullptr); }
  ~TrigScratch() { mpfr_clears(x2, at_lo, at_hi, k, c, (mpfr_ptr)nullptr); }
  TrigScratch(const TrigScratch&) = delete;
  TrigScratch& operator=(const TrigScratch&) = delete;
};

// sin(2 pi x) or cos(2 pi x) over [lo, hi] into [out_lo, out_hi] (both of one precision):
// the directed roundings of the ends, widened to +-1 where the interval holds an extremum.
// Each end costs one correctly rounded MPFR call: its ternary value says on which side of
// the exact value the nearest rounding lies, so RD and RU are that rounding and its
// neighbour (or both it, when exact) -- the same bits as two directed calls.
void trig_2pi_enclosure(mpfr_srcptr lo, mpfr_srcptr hi, bool cosine, mpfr_ptr out_lo, mpfr_ptr out_hi) {
  if (mpfr_nan_p(lo) || mpfr_nan_p(hi) || !mpfr_number_p(lo) || !mpfr_number_p(hi)) {
    mpfr_set_nan(out_lo);
    mpfr_set_nan(out_hi);
    return;
  }
  thread_local TrigScratch t;
  const mpfr_prec_t p = std::max(mpfr_get_prec(lo), mpfr_get_prec(hi)) + 1, po = mpfr_get_prec(out_lo);
  mpfr_set_prec(t.x2, p);
  mpfr_set_prec(t.at_lo, po);
  mpfr_set_prec(t.at_hi, po);
  mpfr_sub(t.c, hi, lo, MPFR_RNDU);  // c at 64 bits: the width, rounded up
  if (mpfr_cmp_ui(t.c, 1) >= 0) {
    mpfr_set_si(out_lo, -1, MPFR_RNDD);
    mpfr_set_si(out_hi, 1, MPFR_RNDU);
    return;
  }
  // f(x) rounded to nearest at po bits in `out`; returns MPFR's ternary value.
  auto f = [&](mpfr_srcptr x, mpfr_ptr out) {
    mpfr_mul_2ui(t.x2, x, 1, MPFR_RNDN);  // exact (p > prec(x))
    return cosine ? mpfr_cospi(out, t.x2, MPFR_RNDN) : mpfr_sinpi(out, t.x2, MPFR_RNDN);
  };
  const int t_lo = f(lo, t.at_lo), t_hi = f(hi, t.at_hi);
  // RD(f(x)) is the nearest rounding, or the number below it when that lies above f(x)
  // (ternary > 0); RU(f(x)) likewise. The copies are exact (one precision).
  mpfr_set(out_hi, t.at_lo, MPFR_RNDN);
  if (t_lo < 0) mpfr_nextabove(out_hi);
  mpfr_set(out_lo, t.at_lo, MPFR_RNDN);
  if (t_lo > 0) mpfr_nextbelow(out_lo);
  mpfr_set(t.at_lo, t.at_hi, MPFR_RNDN);
  if (t_hi > 0) mpfr_nextbelow(t.at_lo);
  mpfr_min(out_lo, out_lo, t.at_lo, MPFR_RNDD);
  if (t_hi < 0) mpfr_nextabove(t.at_hi);
  mpfr_max(out_hi, out_hi, t.at_hi, MPFR_RNDU);
  // Is there an integer k with lo <= k + offset <= hi?
  auto contains = [&](double offset) {
    mpfr_sub_d(t.k, lo, offset, MPFR_RNDD);
    mpfr_ceil(t.k, t.k);
    mpfr_add_d(t.c, t.k, offset, MPFR_RNDN);  // exact: k is a modest integer at 64 bits
    return mpfr_lessequal_p(t.c, hi) != 0;
  };
  if (contains(cosine ? 0.0 : 0.25)) mpfr_set_si(out_hi, 1, MPFR_RNDU);
  if (contains(cosine ? 0.5 : 0.75)) mpfr_set_si(out_lo, -1, MPFR_RNDD);
}

Mpfi trig_mpfi(const Mpfi& x, bool cosine) {
  Mpfi r(x.bits());
  trig_2pi_enclosure(&x.get()->left, &x.get()->right, cosine, &r.get()->left, &r.get()->right);
  return r;
}

DoubleInterval trig_double_interval(const DoubleInterval& x, bool cosine) {
  struct Ends {  // the ends at 53 bits, one set per thread
    mpfr_t lo, hi, out_lo, out_hi;
    Ends() { mpfr_inits2(53, lo, hi, out_lo, out_hi, (mpfr_ptr)nullptr); }
    ~Ends() { mpfr_clears(lo, hi, out_lo, out_hi, (mpfr_ptr)nullptr); }
    Ends(const Ends&) = delete;
    Ends& operator=(const Ends&) = delete;
  };
  thread_local Ends e;
  mpfr_set_d(e.lo, x.lower(), MPFR_RNDN);  // exact
  mpfr_set_d(e.hi, x.upper(), MPFR_RNDN);
  trig_2pi_enclosure(e.lo, e.hi, cosine, e.out_lo, e.out_hi);
  return DoubleInterval(mpfr_get_d(e.out_lo, MPFR_RNDD), mpfr_get_d(e.out_hi, MPFR_RNDU));
}

Mpfr trig_mpfr(const Mpfr& x, bool cosine) {
  thread_local TrigScratch t;  // its x2
  mpfr_set_prec(t.x2, x.bits() + 1);
  Mpfr r(x.bits());
  mpfr_mul_2ui(t.x2, x.get(), 1, MPFR_RNDN);  // exact
  if (cosine) mpfr_cospi(r.get(), t.x2, MPFR_RNDN);
  else mpfr_sinpi(r.get(), t.x2, MPFR_RNDN);
  return r;
}

}  // namespace

Mpfr ScalarTraits<Mpfr>::two_pi(long bits) {
  Mpfr r(bits);
  mpfr_const_pi(r.get(), MPFR_RNDN);
  mpfr_mul_2ui(r.get(), r.get(), 1, MPFR_RNDN);
  return r;
}
Mpfr ScalarTraits<Mpfr>::sin_2pi(const Mpfr& x) { return trig_mpfr(x, false); }
Mpfr ScalarTraits<Mpfr>::cos_2pi(const Mpfr& x) { return trig_mpfr(x, true); }

Mpfi ScalarTraits<Mpfi>::two_pi(long bits) {
  Mpfi r(bits);
  mpfi_const_pi(r.get());
  mpfi_mul_2ui(r.get(), r.get(), 1);
  return r;
}
Mpfi ScalarTraits<Mpfi>::sin_2pi(const Mpfi& x) { return trig_mpfi(x, false); }
Mpfi ScalarTraits<Mpfi>::cos_2pi(const Mpfi& x) { return trig_mpfi(x, true); }

DoubleInterval ScalarTraits<DoubleInterval>::two_pi(long) {
  static const DoubleInterval r = [] {
    mpfr_t lo, hi;
    mpfr_inits2(53, lo, hi, (mpfr_ptr)nullptr);
    mpfr_const_pi(lo, MPFR_RNDD);
    mpfr_const_pi(hi, MPFR_RNDU);
    const DoubleInterval out(2 * mpfr_get_d(lo, MPFR_RNDD), 2 * mpfr_get_d(hi, MPFR_RNDU));  // x2 exact
    mpfr_clears(lo, hi, (mpfr_ptr)nullptr);
    return out;
  }();
  return r;
}
DoubleInterval ScalarTraits<DoubleInterval>::sin_2pi(const DoubleInterval& x) { return trig_double_interval(x, false); }
DoubleInterval ScalarTraits<DoubleInterval>::cos_2pi(const DoubleInterval& x) { return trig_double_interval(x, true); }

DoubleDouble ScalarTraits<DoubleDouble>::two_pi(long) { return from_qd(dd_real::_2pi); }
DoubleDouble ScalarTraits<DoubleDouble>::sin_2pi(const DoubleDouble& x) {
  if (!x.is_finite()) return DoubleDouble::nan_value();
  return from_qd(sin(dd_real::_2pi * to_qd(x - bouncer::floor(x))));
}
DoubleDouble ScalarTraits<DoubleDouble>::cos_2pi(const DoubleDouble& x) {
  if (!x.is_finite()) return DoubleDouble::nan_value();
  return from_qd(cos(dd_real::_2pi * to_qd(x - bouncer::floor(x))));
}

Quad ScalarTraits<Quad>::two_pi(long) { return Quad(2 * M_PIq); }
Quad ScalarTraits<Quad>::sin_2pi(const Quad& x) {
  const __float128 v = x.backend().value();
  return Quad(sinq(2 * M_PIq * (v - floorq(v))));
}
Quad ScalarTraits<Quad>::cos_2pi(const Quad& x) {
  const __float128 v = x.backend().value();
  return Quad(cosq(2 * M_PIq * (v - floorq(v))));
}

}  // namespace bouncer
