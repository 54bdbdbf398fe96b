// Helpers shared by the proofs: exact-rational enclosures, triangle-wall models whose
// parameters are intervals (when a parameter is not a finite decimal), box covers of an
// interval with adaptive bisection, and printing.
#pragma once

#include <functional>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <gmpxx.h>

#include "bouncer/model/impact_map.hpp"
#include "bouncer/scalar/traits.hpp"

namespace proofs {

using bouncer::Mpfi;
using bouncer::Mpfr;
using Tr = bouncer::ScalarTraits<Mpfi>;

// The tightest enclosure of num/den at `bits` (both exact integers: one rounding each way).
inline Mpfi q(long num, long den, long bits) { return Mpfi(num, bits) / Mpfi(den, bits); }
// Enclosure of an exact rational (mpfi_set_q rounds outward).
inline Mpfi qi(const mpq_class& x, long bits) {
  Mpfi r(bits);
  mpfi_set_q(r.get(), x.get_mpq_t());
  return r;
}
// Nearest Mpfr of an exact rational (for box ends, which need not be exact).
inline Mpfr qr(const mpq_class& x, long bits) {
  Mpfr r(bits);
  mpfr_set_q(r.get(), x.get_mpq_t(), MPFR_RNDN);
  return r;
}
inline std::string qs(const mpq_class& x) { return x.get_str(); }
inline Mpfi dec(const char* text, long bits) { return Tr::from_decimal(text, bits); }
inline Mpfi point(const Mpfr& x) { return Mpfi(x, x); }
inline std::string s(const Mpfi& x) { return Tr::to_string(x); }
inline std::string s(const Mpfr& x) { return bouncer::mpfr_to_string(x.get(), MPFR_RNDN); }
inline double d(const Mpfi& x) { return x.mid().to_double(); }
// Certainly x < y / x <= y (every point).
inline bool lt(const Mpfi& x, const Mpfi& y) { return Tr::lt(x, y) == bouncer::Truth::yes; }
inline bool le(const Mpfi& x, const Mpfi& y) { return Tr::le(x, y) == bouncer::Truth::yes; }
// Certainly disjoint.
inline bool disjoint(const Mpfi& x, const Mpfi& y) { return lt(x, y) || lt(y, x); }
// x^r for x > 0 and an interval exponent r (exp(r log x), outward rounded).
inline Mpfi powi(const Mpfi& x, const Mpfi& r) { return exp(r * log(x)); }

// The symmetric triangle wall (f = 4 theta - 1 on [0,1/2), 3 - 4 theta on [1/2,1)) with the
// given law and parameters as intervals. The wall comes from the library's make_model
// (exact knots); a, eps, c and the sticking constant a(1-eps)/2 are then set from the
// interval parameters, which is all make_model does with them.
//
// `top_override`: Wall::top is only used by the step as "a height the wall never exceeds"
// (the particle above it cannot meet the wall; the jump to the moment it falls back to
// `top`; the indirect flag). Any value >= max f = 1 gives the same exact map (the indirect
// flag aside). A large value disables the jump shortcut, so the step walks every segment;
// the Jacobian evaluations use that to differentiate one formula path. (The step itself
// already walks where the jump's phase is undecided.)
inline bouncer::Model<Mpfi> triangle_model(bouncer::Law law, const Mpfi& a, const Mpfi& eps,
                                           const Mpfi& c, long bits,
                                           std::optional<long> top_override = std::nullopt) {
  bouncer::ModelSpec spec;
  spec.law = law;
  spec.wall = bouncer::parse_wall("wall", "triangle");
  spec.a = bouncer::Decimal::from_int(1);
  spec.eps = bouncer::Decimal::from_int(1);
  spec.c = bouncer::Decimal::from_int(1);
  bouncer::Model<Mpfi> m = bouncer::make_model<Mpfi>(spec, bits);
  m.a = a;
  m.eps = law == bouncer::Law::constant ? eps : Mpfi(1, bits);
  m.c = c;
  m.collapse = m.a * (1 - m.eps) / 2;
  if (top_override) m.wall.top = Mpfi(*top_override, bits);
  return m;
}

// How finely a proof covers an open interval: [lo + delta, hi - delta] with delta = 2^-delta_exp,
// `initial` boxes bisected at most `depth` times; the default mode or the finer --full one.
struct CoverPlan {
  int delta_exp;
  int depth;
  long initial;
  mpq_class delta;
  std::string text() const {
    return "delta = 2^-" + std::to_string(delta_exp) + ", " + std::to_string(initial) +
           " initial boxes, bisection depth <= " + std::to_string(depth);
  }
};
inline CoverPlan cover_plan(bool full, int delta_exp, int depth, int delta_exp_full, int depth_full) {
  const int e = full ? delta_exp_full : delta_exp;
  return {e, full ? depth_full : depth, full ? 256L : 16L, mpq_class(mpz_class(1), mpz_class(1) << e)};
}

// Result of a cover of [lo, hi] by boxes with adaptive bisection.
struct Cover {
  long certified = 0;        // boxes on which the check succeeded
  long failed = 0;           // boxes still failing at the depth limit
  long evaluations = 0;
  int deepest = 0;
  Mpfr failed_measure{0, 64};
  std::map<std::string, long> reasons;  // why boxes failed (last attempt)
  std::vector<std::pair<Mpfr, Mpfr>> failed_boxes;
  bool complete() const { return failed == 0; }
};

// The check returns an empty string on success, else the reason it failed (Undecided
// message, or "image test failed"): the box is then bisected, up to max_depth levels.
using BoxCheck = std::function<std::string(const Mpfi& box)>;

inline void cover(const Mpfr& lo, const Mpfr& hi, long initial, int max_depth, const BoxCheck& f,
                  Cover& out) {
  const long bits = std::max(lo.bits(), hi.bits()) + 64;  // room for exact dyadic splits
  struct Item { Mpfr l, r; int depth; };
  std::vector<Item> stack;
  Mpfr width(bits);
  mpfr_sub(width.get(), hi.get(), lo.get(), MPFR_RNDN);
  for (long i = initial - 1; i >= 0; --i) {
    Mpfr l(bits), r(bits);
    // l = lo + width*i/initial, rounded; the boxes share endpoints, so they cover [lo, hi].
    mpfr_mul_si(l.get(), width.get(), i, MPFR_RNDN);
    mpfr_div_si(l.get(), l.get(), initial, MPFR_RNDN);
    mpfr_add(l.get(), l.get(), lo.get(), MPFR_RNDN);
    mpfr_mul_si(r.get(), width.get(), i + 1, MPFR_RNDN);
    mpfr_div_si(r.get(), r.get(), initial, MPFR_RNDN);
    mpfr_add(r.get(), r.get(), lo.get(), MPFR_RNDN);
    if (i == 0) mpfr_set(l.get(), lo.get(), MPFR_RNDN);
    if (i == initial - 1) mpfr_set(r.get(), hi.get(), MPFR_RNDN);
    stack.push_back({l, r, 0});
  }
  while (!stack.empty()) {
    Item it = std::move(stack.back());
    stack.pop_back();
    ++out.evaluations;
    out.deepest = std::max(out.deepest, it.depth);
    const std::string why = f(Mpfi(it.l, it.r));
    if (why.empty()) { ++out.certified; continue; }
    if (it.depth >= max_depth) {
      ++out.failed;
      ++out.reasons[why];
      Mpfr w(64);
      mpfr_sub(w.get(), it.r.get(), it.l.get(), MPFR_RNDU);
      mpfr_add(out.failed_measure.get(), out.failed_measure.get(), w.get(), MPFR_RNDU);
      if (out.failed_boxes.size() < 8) out.failed_boxes.push_back({it.l, it.r});
      continue;
    }
    Mpfr m(bits);
    mpfr_add(m.get(), it.l.get(), it.r.get(), MPFR_RNDN);
    mpfr_div_2ui(m.get(), m.get(), 1, MPFR_RNDN);  // exact at this precision
    stack.push_back({m, it.r, it.depth + 1});
    stack.push_back({it.l, m, it.depth + 1});
  }
}

inline std::string describe(const Cover& c) {
  std::string r = std::to_string(c.certified) + " boxes certified (" +
                  std::to_string(c.evaluations) + " evaluations, bisection depth <= " +
                  std::to_string(c.deepest) + ")";
  if (c.failed) {
    r += "; " + std::to_string(c.failed) + " boxes NOT certified, total width " +
         s(c.failed_measure) + ":";
    for (const auto& [why, n] : c.reasons) r += " [" + why + "] x" + std::to_string(n);
  }
  return r;
}

// Mpfr point of a decimal or rational at `bits` (rounded to nearest; used for box ends,
// which need not be exact: a cover of [lo, hi] is what it is).
inline Mpfr mq(long num, long den, long bits) {
  Mpfr r(num, bits);
  mpfr_div_si(r.get(), r.get(), den, MPFR_RNDN);
  return r;
}

// One step, returning the Undecided message on failure.
template <class T>
inline std::string try_step(const bouncer::ImpactMap<T>& map, const bouncer::State<T>& st,
                            bouncer::StepResult<T>& out) {
  try {
    out = map.step(st);
    return "";
  } catch (const bouncer::Undecided& u) {
    return std::string("undecided: ") + u.what();
  }
}

}  // namespace proofs
