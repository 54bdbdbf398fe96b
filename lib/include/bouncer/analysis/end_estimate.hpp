// Honest digits of a located branch end (issue 23): how far a* computed in a point type can
// be trusted, and the digits of it that this backs.
//
// A branch end is located on whether the corrector's orbit keeps the branch's events (secant
// steps on a vanishing margin, else bisection: analysis/continuation.hpp). In a point type of
// p mantissa bits the margins that decide this carry rounding errors, amplified by 1 / (their
// slope in the parameter), so the bracket, 2^-44 relative wide in double, can lie beside a*:
// at the veldep c = 1000 unstable period-7 end by 2.6e-14, and, located by bisection alone,
// the stable period-7 ends were 1.9e-11 and 2.9e-11 away (about 2^12 ulps).
//
// The estimate (estimate_end_accuracy in continuation.hpp) re-locates the end with the same
// corrector and acceptance tests in Mpfr at p + 64 bits, from the exact model (its
// decimals, not T's roundings of them), starting next to T's bracket: its branch side is
// stepped back until the orbit keeps the branch's events there, its far side out until it
// does not, and the end is narrowed to 2^-(p + 24) relative (secant steps on the margin
// that reached 0 at a border; bisection otherwise). The same amplification A acts at
// p + 64 bits, so the re-located a* is off by about A 2^-(p+64), 2^-64 of T's error, and
// |refined - computed| is T's error itself up to that. The widened bracket is
//     computed a* -+ (4 max(|refined - computed|, half T's bracket) + the re-located
//                     bracket's half width + 2 ulps of T):
// a safety factor 4 on an estimate that is nearly exact, against what the argument above
// does not cover (an amplification that grows with the precision, an end whose cause is
// met differently at more bits). It is an estimate, not a proof: nothing is enclosed; the
// certified two-sided enclosure of a border collision is `continue --certify`
// (verify/border_collision.hpp). Cost: about a dozen corrector runs per end (0.5 s for the
// period-7 example in double).
#pragma once

#include <gmpxx.h>

#include <string>

namespace bouncer {

struct EndEstimate {
  enum class Kind {
    not_estimated,  // no estimate (not asked for, or the re-location failed: `note`)
    given,          // range end or --max-points: the parameter value where the branch stopped
    estimate,       // [lo, hi]: the widened bracket, an estimate
  };
  Kind kind = Kind::not_estimated;
  mpq_class center;       // the computed a* (the point type's bracket midpoint), exactly
  mpq_class lo, hi;       // estimate: center -+ radius
  double radius = 0;      // estimate: 4 max(|refined - center|, half the bracket)
  double error = 0;       // estimate: |refined - center|, the computed a*'s estimated error
  std::string refined;    // estimate: a* re-located at `bits` bits (round-trip text)
  long bits = 0;          // of the re-location
  std::string note;       // not_estimated: why
};

const char* name(EndEstimate::Kind);

// The digits a radius backs: center rounded to the decimal place of the radius's leading
// digit, and the radius rounded up to one significant digit there after adding the
// rounding of the center (so that value -+ plus_minus contains center -+ radius).
// E.g. center 27.720561305427014, radius 7.2e-11: "27.72056130543", "8e-11", 13 digits;
// lo/hi: center -+ radius rounded outward to the same decimal place.
struct BackedDigits {
  std::string value;       // "27.72056130543"
  std::string plus_minus;  // "8e-11"
  int digits = 0;          // significant digits of value (13)
  std::string lo, hi;      // "27.72056130535", "27.72056130551"
};
BackedDigits backed_digits(const mpq_class& center, double radius);

// The text of an end value for a sentence: "27.72056130543 ± 8e-11 (estimate)" for an
// estimate, the computed value for `given`, and "<computed> (accuracy not estimated)"
// otherwise (`computed`: the point type's round-trip text).
std::string end_value_text(const EndEstimate& e, const std::string& computed);

}  // namespace bouncer
