// Per-scalar knowledge in one place: parsing decimals, printing, precision, and the
// three-valued predicates that are the impact map's only branch points.
//
// The contract these specialisations meet is the concept Scalar<T> (and PointScalar<T>,
// IntervalScalar<T>) of scalar/contract.hpp; the set of supported types is
// scalar/scalar_set.hpp.
#pragma once

#include <boost/multiprecision/float128.hpp>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <ostream>
#include <string>
#include <string_view>

#include "bouncer/scalar/contract.hpp"
#include "bouncer/scalar/double_double.hpp"
#include "bouncer/scalar/interval_double.hpp"
#include "bouncer/scalar/mpfi.hpp"
#include "bouncer/scalar/mpfr.hpp"
#include "bouncer/scalar/truth.hpp"

namespace bouncer {

using Quad = boost::multiprecision::float128;

// Decimal text of an MPFR number with enough digits to round-trip at its precision,
// rounded in the given direction (RNDN for points; RNDD/RNDU for interval ends).
std::string mpfr_to_string(mpfr_srcptr x, mpfr_rnd_t rnd);
// The same with a given number of significant digits.
std::string mpfr_to_string_digits(mpfr_srcptr x, mpfr_rnd_t rnd, size_t digits);

namespace detail {

// The rounding guards of every point type, from its below() and floor().
template <class T>
struct PointGuards {
  static T clamp(const T& x, const T& lo, const T& hi) {
    if (x < lo) return lo;
    if (!(x < hi)) return ScalarTraits<T>::below(hi);
    return x;
  }
  static Truth floor_certain(const T& x, T& out) {
    if (!ScalarTraits<T>::is_finite(x)) return Truth::invalid;
    out = ScalarTraits<T>::floor(x);
    return Truth::yes;
  }
};

// Shared by the IEEE-style point types (double, long double, Quad).
template <class T>
struct PointTraits : PointGuards<T> {
  static constexpr bool is_interval = false;
  static constexpr long fixed_bits = std::numeric_limits<T>::digits;
  // NaN fails both comparisons, so it is recognised without a separate isnan test.
  static Truth lt(const T& x, const T& y) { return x < y ? Truth::yes : x >= y ? Truth::no : Truth::invalid; }
  static Truth le(const T& x, const T& y) { return x <= y ? Truth::yes : x > y ? Truth::no : Truth::invalid; }
  static Truth is_zero(const T& x) { return x == 0 ? Truth::yes : x != 0 && x == x ? Truth::no : Truth::invalid; }
  static bool likely_negative(const T& x) { return x < 0; }
  static T nonneg(const T& x) { return x < 0 ? T(0) : x; }
  static bool is_finite(const T& x) { using std::isfinite; using boost::multiprecision::isfinite; return isfinite(x); }
  static double to_double(const T& x) { return static_cast<double>(x); }
  static bool nan(const T& x, const T& y) { using std::isnan; using boost::multiprecision::isnan; return isnan(x) || isnan(y); }
};

}  // namespace detail

template <>
struct ScalarTraits<double> : detail::PointTraits<double> {
  static constexpr const char* family = "double";
  static double from_decimal(std::string_view text, long bits);
  static double from_int(long n, long) { return static_cast<double>(n); }
  static long bits(const double&) { return std::numeric_limits<double>::digits; }
  static double below(const double& x) { return std::nextafter(x, -std::numeric_limits<double>::infinity()); }
  // frexp's exponent; read from the bits for a normal x (the jump of the impact map takes it
  // at every step, and the call to frexp would cost a tenth of the step).
  static int exponent(const double& x) {
    std::uint64_t u;
    std::memcpy(&u, &x, sizeof u);
    const int biased = static_cast<int>(u >> 52 & 0x7ff);
    if (biased != 0 && biased != 0x7ff) return biased - 1022;
    int e;
    std::frexp(x, &e);
    return e;
  }
  static double floor(const double& x) { return std::floor(x); }
  static double pow_3_5(const double& x) { return std::pow(x, 0.6); }
  // sin(2 pi x), cos(2 pi x) and 2 pi (the sine wall, model/model.hpp): x reduced to [0, 1)
  // first (exact), so a long flight's phase costs no more than its own rounding.
  static double two_pi(long) { return 6.283185307179586; }
  static double sin_2pi(const double& x) { return std::sin(two_pi(0) * (x - std::floor(x))); }
  static double cos_2pi(const double& x) { return std::cos(two_pi(0) * (x - std::floor(x))); }
  static std::string to_string(const double& x);
};

template <>
struct ScalarTraits<long double> : detail::PointTraits<long double> {
  static constexpr const char* family = "long";
  static long double from_decimal(std::string_view text, long bits);
  static long double from_int(long n, long) { return static_cast<long double>(n); }
  static long bits(const long double&) { return std::numeric_limits<long double>::digits; }
  static long double below(const long double& x) { return std::nextafter(x, -std::numeric_limits<long double>::infinity()); }
  static int exponent(const long double& x) { int e; std::frexp(x, &e); return e; }
  static long double floor(const long double& x) { return std::floor(x); }
  static long double pow_3_5(const long double& x) { return std::pow(x, 0.6L); }
  static long double two_pi(long) { return 6.283185307179586476925286766559005768L; }
  static long double sin_2pi(const long double& x) { return std::sin(two_pi(0) * (x - std::floor(x))); }
  static long double cos_2pi(const long double& x) { return std::cos(two_pi(0) * (x - std::floor(x))); }
  static std::string to_string(const long double& x);
};

// dd: double-word arithmetic (scalar/double_double.hpp: the algorithms and their error
// bounds). 106 bits: hi and lo carry 53 each (|lo| <= ulp(hi)/2, so one more bit is implicit
// in lo's sign; 106 is the precision its operations are tested to).
template <>
struct ScalarTraits<DoubleDouble> : detail::PointGuards<DoubleDouble> {
  using D = DoubleDouble;
  static constexpr bool is_interval = false;
  static constexpr const char* family = "dd";
  static constexpr long fixed_bits = 106;
  static D from_decimal(std::string_view text, long bits);  // hi = RN(d), lo = RN(d - hi)
  static D from_int(long n, long) { return D(n); }
  static long bits(const D&) { return fixed_bits; }
  static Truth lt(const D& x, const D& y) { return x < y ? Truth::yes : x >= y ? Truth::no : Truth::invalid; }
  static Truth le(const D& x, const D& y) { return x <= y ? Truth::yes : x > y ? Truth::no : Truth::invalid; }
  static Truth is_zero(const D& x) { return x.is_nan() ? Truth::invalid : truth(x.hi() == 0); }
  static bool likely_negative(const D& x) { return x.hi() < 0; }
  static D nonneg(const D& x) { return x.hi() < 0 ? D() : x; }
  static bool is_finite(const D& x) { return x.is_finite(); }
  static double to_double(const D& x) { return x.hi(); }  // canonical: hi = RN(value)
  // The largest dd below x: lo moved one double down (hi + lo' < hi + lo exactly).
  static D below(const D& x) { return D::from_pair(x.hi(), std::nextafter(x.lo(), -std::numeric_limits<double>::infinity())); }
  static int exponent(const D& x) {
    if (x.hi() == 0) return 0;
    int e = 0;
    const double m = std::frexp(x.hi(), &e);
    // hi = RN(value) may have rounded up to a power of two: the value is then below it.
    if (std::fabs(m) == 0.5 && x.lo() != 0 && (x.lo() < 0) != (x.hi() < 0)) --e;
    return e;
  }
  static D floor(const D& x) { return bouncer::floor(x); }
  static D pow_3_5(const D& x);
  static std::string to_string(const D& x);
  static bool nan(const D& x, const D& y) { return x.is_nan() || y.is_nan(); }
  static D two_pi(long);
  static D sin_2pi(const D& x);  // QD's sin and cos of 2 pi (x - floor x)
  static D cos_2pi(const D& x);
};

template <>
struct ScalarTraits<Quad> : detail::PointTraits<Quad> {
  static constexpr const char* family = "quad";
  static Quad from_decimal(std::string_view text, long bits);
  static Quad from_int(long n, long) { return Quad(n); }
  static long bits(const Quad&) { return 113; }
  static Quad below(const Quad& x);
  static int exponent(const Quad& x);
  static Quad floor(const Quad& x) { return boost::multiprecision::floor(x); }
  static Quad pow_3_5(const Quad& x);
  static Quad two_pi(long);
  static Quad sin_2pi(const Quad& x);
  static Quad cos_2pi(const Quad& x);
  static std::string to_string(const Quad& x);
};

template <>
struct ScalarTraits<Mpfr> : detail::PointGuards<Mpfr> {
  static constexpr bool is_interval = false;
  static constexpr const char* family = "mpfr";
  static constexpr long fixed_bits = 0;
  static Mpfr from_decimal(std::string_view text, long bits);
  static Mpfr from_int(long n, long bits) { return Mpfr(n, bits); }
  static long bits(const Mpfr& x) { return x.bits(); }
  static Truth lt(const Mpfr& x, const Mpfr& y) { return nan(x, y) ? Truth::invalid : truth(x < y); }
  static Truth le(const Mpfr& x, const Mpfr& y) { return nan(x, y) ? Truth::invalid : truth(x <= y); }
  static Truth is_zero(const Mpfr& x) { return mpfr_nan_p(x.get()) ? Truth::invalid : truth(mpfr_zero_p(x.get()) != 0); }
  static bool likely_negative(const Mpfr& x) { return mpfr_sgn(x.get()) < 0; }
  static Mpfr nonneg(const Mpfr& x) { return mpfr_sgn(x.get()) < 0 ? Mpfr(0, x.bits()) : x; }
  static bool is_finite(const Mpfr& x) { return mpfr_number_p(x.get()) != 0; }
  static double to_double(const Mpfr& x) { return x.to_double(); }
  static Mpfr below(const Mpfr& x) { Mpfr r = x; mpfr_nextbelow(r.get()); return r; }
  static int exponent(const Mpfr& x) { return mpfr_zero_p(x.get()) ? 0 : static_cast<int>(mpfr_get_exp(x.get())); }
  static Mpfr floor(const Mpfr& x) { return bouncer::floor(x); }
  static Mpfr pow_3_5(const Mpfr& x);
  static Mpfr two_pi(long bits);
  static Mpfr sin_2pi(const Mpfr& x);  // mpfr_sinpi(2x): correctly rounded, no rounded pi
  static Mpfr cos_2pi(const Mpfr& x);
  static std::string to_string(const Mpfr& x) { return mpfr_to_string(x.get(), MPFR_RNDN); }
  static bool nan(const Mpfr& x, const Mpfr& y) { return mpfr_nan_p(x.get()) || mpfr_nan_p(y.get()); }
};

template <>
struct ScalarTraits<Mpfi> {
  static constexpr bool is_interval = true;
  static constexpr const char* family = "interval";
  static constexpr long fixed_bits = 0;
  static Mpfi from_decimal(std::string_view text, long bits);
  static Mpfi from_int(long n, long bits) { return Mpfi(n, bits); }
  static long bits(const Mpfi& x) { return x.bits(); }
  // Certainly x < y when every point of x is below every point of y.
  static Truth lt(const Mpfi& x, const Mpfi& y);
  static Truth le(const Mpfi& x, const Mpfi& y);
  static Truth is_zero(const Mpfi& x);
  // Only chooses between two algebraically equal formulas; never a model branch.
  static bool likely_negative(const Mpfi& x) { return mpfr_sgn(x.mid().get()) < 0; }
  // Intersection with [0, inf): the caller knows the exact value is non-negative.
  static Mpfi nonneg(const Mpfi& x);
  // The caller knows the exact value lies in [lo, hi): the enclosure is cut to it.
  static Mpfi clamp(const Mpfi& x, const Mpfi& lo, const Mpfi& hi) { return intersect(x, hull(lo, hi)); }
  // Certain only when both ends have the same integer part.
  static Truth floor_certain(const Mpfi& x, Mpfi& out) {
    Mpfr lo = bouncer::floor(x.lower()), hi = bouncer::floor(x.upper());
    if (!(lo == hi)) return Truth::unknown;
    out = Mpfi(lo, lo);
    return Truth::yes;
  }
  static bool is_finite(const Mpfi& x) { return !x.has_nan() && x.bounded(); }
  static double to_double(const Mpfi& x) { return x.mid().to_double(); }
  static Mpfi pow_3_5(const Mpfi& x);
  // Enclosures: MPFR's sinpi/cospi of 2x (exact) at each end, rounded outward, with the
  // extrema inside [x] (scalar.cpp, trig_2pi_enclosure).
  static Mpfi two_pi(long bits);
  static Mpfi sin_2pi(const Mpfi& x);
  static Mpfi cos_2pi(const Mpfi& x);
  static int exponent(const Mpfi& x) { Mpfr u = abs(x).upper(); return mpfr_zero_p(u.get()) ? 0 : static_cast<int>(mpfr_get_exp(u.get())); }
  static std::string to_string(const Mpfi& x);  // "[lo, hi]"
  static std::string lower_string(const Mpfi& x);  // rounded down
  static std::string upper_string(const Mpfi& x);  // rounded up
};

// interval:double, the fast certified scalar (scalar/interval_double.hpp: the rounding
// argument). Its branch predicates are those of Mpfi on the two double ends.
template <>
struct ScalarTraits<DoubleInterval> {
  using D = DoubleInterval;
  static constexpr bool is_interval = true;
  static constexpr const char* family = "interval:double";
  static constexpr long fixed_bits = std::numeric_limits<double>::digits;
  static D from_decimal(std::string_view text, long bits);  // the tightest enclosure
  static D from_int(long n, long) { return D(n); }
  static long bits(const D&) { return fixed_bits; }
  static Truth lt(const D& x, const D& y) {
    if (x.has_nan() || y.has_nan()) return Truth::invalid;
    return x.upper() < y.lower() ? Truth::yes : x.lower() >= y.upper() ? Truth::no : Truth::unknown;
  }
  static Truth le(const D& x, const D& y) {
    if (x.has_nan() || y.has_nan()) return Truth::invalid;
    return x.upper() <= y.lower() ? Truth::yes : x.lower() > y.upper() ? Truth::no : Truth::unknown;
  }
  static Truth is_zero(const D& x) {
    if (x.has_nan()) return Truth::invalid;
    if (x.lower() == 0 && x.upper() == 0) return Truth::yes;
    return x.lower() > 0 || x.upper() < 0 ? Truth::no : Truth::unknown;
  }
  static bool likely_negative(const D& x) { return x.mid() < 0; }
  static D nonneg(const D& x) { return x.lower() >= 0 ? x : D(0.0, std::max(x.upper(), 0.0)); }
  static D clamp(const D& x, const D& lo, const D& hi) { return intersect(x, hull(lo, hi)); }
  static Truth floor_certain(const D& x, D& out) {
    if (!is_finite(x)) return Truth::invalid;
    const double lo = std::floor(x.lower()), hi = std::floor(x.upper());
    if (lo != hi) return Truth::unknown;
    out = D(lo, lo);
    return Truth::yes;
  }
  static bool is_finite(const D& x) { return x.bounded(); }
  static double to_double(const D& x) { return x.mid(); }
  static int exponent(const D& x) {
    const double m = std::max(std::fabs(x.lower()), std::fabs(x.upper()));
    int e = 0;
    std::frexp(m, &e);
    return m == 0 ? 0 : e;
  }
  static D pow_3_5(const D& x);
  static std::string to_string(const D& x);     // "[lo, hi]"
  static D two_pi(long);
  static D sin_2pi(const D& x);  // as for Mpfi, at 53 bits with directed roundings
  static D cos_2pi(const D& x);
  static std::string lower_string(const D& x);  // rounded down
  static std::string upper_string(const D& x);  // rounded up
};

// A value to be assigned before it is read, with the precision `bits` where the type has
// one (an Mpfr of the right precision lets later assignments evaluate in place).
template <class T>
T blank(long bits) {
  if constexpr (std::is_same_v<T, Mpfr>) return Mpfr(bits);
  else if constexpr (requires { T::blank(bits); }) return T::blank(bits);  // Dual<S>: its parts' blanks
  else return T();
}

// In-place forms of ScalarTraits::nonneg and ScalarTraits::clamp, for the hot path of the
// impact map: the same results without a copy for the multiple-precision point type.
template <class T>
void make_nonneg(T& x) { x = ScalarTraits<T>::nonneg(x); }
inline void make_nonneg(Mpfr& x) {
  if (mpfr_sgn(x.get()) < 0) mpfr_set_zero(x.get(), 1);
}
template <class T>
void clamp_into_segment(T& x, const T& lo, const T& hi) { x = ScalarTraits<T>::clamp(x, lo, hi); }
inline void clamp_into_segment(Mpfr& x, const Mpfr& lo, const Mpfr& hi) {
  if (x < lo) {
    x = lo;
  } else if (!(x < hi)) {
    x = hi;
    mpfr_nextbelow(x.get());
  }
}

// Printing: an Mpfr with enough digits to read back the same number at its precision; an
// Mpfi as "[lo, hi]" with the lower end rounded down and the upper end rounded up, so the
// printed interval still encloses the value.
inline std::ostream& operator<<(std::ostream& os, const Mpfr& x) { return os << ScalarTraits<Mpfr>::to_string(x); }
inline std::ostream& operator<<(std::ostream& os, const Mpfi& x) { return os << ScalarTraits<Mpfi>::to_string(x); }

}  // namespace bouncer
