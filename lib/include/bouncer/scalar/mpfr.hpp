// Mpfr: a correctly rounded (round-to-nearest) MPFR number whose precision travels with
// the value, not with a process-wide default.
//
// Why not Boost's mpfr_float: in Boost 1.74 the default precision of variable-precision
// numbers is one process-wide static (unsafe for threads with different precisions), and
// every temporary costs a heap allocation (about 2.5x raw MPFR per step at 53-128 bits).
// Here a value of up to kInlineBits bits keeps its limbs inside the object (MPFR's
// "custom" interface), so temporaries cost no allocation; larger precisions fall back to
// mpfr_init2. Arithmetic builds small expression trees that are evaluated directly into
// the destination (see "Expressions" below), so the impact map is written with ordinary
// operators and costs about what hand-written mpfr_t code costs.
//
// Precision rules: the result of a binary operation has the larger precision of its
// operands; compound assignment keeps the precision of the left side; assignment copies
// value and precision. Every operation is rounded to nearest exactly once, as if each
// had its own temporary.
#pragma once

#include <mpfr.h>

#include <algorithm>
#include <concepts>
#include <cstring>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>

namespace bouncer {

// Every expression node derives from this tag, so that argument-dependent lookup finds
// the operators and functions of namespace bouncer for them.
struct MpfrExpression {};
template <class E>
concept is_mpfr_node = std::is_base_of_v<MpfrExpression, std::remove_cvref_t<E>>;

class Mpfr {
 public:
  static constexpr int kInlineLimbs = 16;
  static constexpr long kInlineBits = kInlineLimbs * GMP_NUMB_BITS;

  Mpfr() { init(53); }
  explicit Mpfr(mpfr_prec_t bits) { init(bits); }
  Mpfr(long n, mpfr_prec_t bits) { init(bits); mpfr_set_si(v_, n, MPFR_RNDN); }
  Mpfr(const Mpfr& o) { init(o.bits()); copy_value(o); }
  Mpfr(Mpfr&& o) noexcept {
    if (o.is_inline()) {
      init(o.bits());
      copy_limbs(o);
    } else {
      v_[0] = o.v_[0];  // steal the heap limbs
      o.init(MPFR_PREC_MIN);
    }
  }
  Mpfr& operator=(const Mpfr& o) {
    if (this != &o) {
      if (bits() != o.bits()) { release(); init(o.bits()); }
      copy_value(o);
    }
    return *this;
  }
  Mpfr& operator=(Mpfr&& o) noexcept {
    if (this == &o) return *this;
    if (!o.is_inline()) {
      release();
      v_[0] = o.v_[0];
      o.init(MPFR_PREC_MIN);
    } else {
      if (bits() != o.bits()) { release(); init(o.bits()); }
      copy_limbs(o);
    }
    return *this;
  }
  ~Mpfr() { release(); }

  mpfr_prec_t bits() const { return mpfr_get_prec(v_); }
  mpfr_ptr get() { return v_; }
  mpfr_srcptr get() const { return v_; }

  // Correctly rounded value of a decimal (or any MPFR-syntax) string; false on bad syntax.
  bool set_decimal(std::string_view text) {
    std::string s(text);
    char* end = nullptr;
    mpfr_strtofr(v_, s.c_str(), &end, 10, MPFR_RNDN);
    return !s.empty() && end && *end == '\0';
  }

  Mpfr& operator+=(const Mpfr& o) { mpfr_add(v_, v_, o.v_, MPFR_RNDN); return *this; }
  Mpfr& operator-=(const Mpfr& o) { mpfr_sub(v_, v_, o.v_, MPFR_RNDN); return *this; }
  Mpfr& operator*=(const Mpfr& o) { mpfr_mul(v_, v_, o.v_, MPFR_RNDN); return *this; }
  Mpfr& operator/=(const Mpfr& o) { mpfr_div(v_, v_, o.v_, MPFR_RNDN); return *this; }
  Mpfr& operator*=(long n) { mpfr_mul_si(v_, v_, n, MPFR_RNDN); return *this; }
  Mpfr& operator/=(long n) { mpfr_div_si(v_, v_, n, MPFR_RNDN); return *this; }

  // Compound assignment from an expression (see MpfrExpression below): the expression is
  // rounded to its own precision first, as if it had been a named Mpfr.
  template <class E> requires is_mpfr_node<E>
  Mpfr& operator+=(const E& e) { return *this += Mpfr(e); }
  template <class E> requires is_mpfr_node<E>
  Mpfr& operator-=(const E& e) { return *this -= Mpfr(e); }
  template <class E> requires is_mpfr_node<E>
  Mpfr& operator*=(const E& e) { return *this *= Mpfr(e); }
  template <class E> requires is_mpfr_node<E>
  Mpfr& operator/=(const E& e) { return *this /= Mpfr(e); }

  // Arithmetic operators (x + y, 2 * a, -x, ...) build expressions, defined below.
  // An expression becomes a number when it is assigned to or converted into an Mpfr:
  // then it is evaluated directly into that Mpfr's limbs.
  template <class E> requires is_mpfr_node<E>
  [[gnu::always_inline]] Mpfr(const E& e) {  // NOLINT(google-explicit-constructor): expressions are numbers
    init(e.prec());
    e.eval(*this);
  }
  template <class E> requires is_mpfr_node<E>
  [[gnu::always_inline]] Mpfr& operator=(const E& e) {
    if (bits() == e.prec()) [[likely]] e.eval(*this);
    else assign_other_precision(e);
    return *this;
  }

  // Point comparisons are exact, so plain bools are honest here (NaN compares false).
  friend bool operator<(const Mpfr& x, const Mpfr& y) { return mpfr_less_p(x.v_, y.v_); }
  friend bool operator<=(const Mpfr& x, const Mpfr& y) { return mpfr_lessequal_p(x.v_, y.v_); }
  friend bool operator>(const Mpfr& x, const Mpfr& y) { return mpfr_greater_p(x.v_, y.v_); }
  friend bool operator>=(const Mpfr& x, const Mpfr& y) { return mpfr_greaterequal_p(x.v_, y.v_); }
  friend bool operator==(const Mpfr& x, const Mpfr& y) { return mpfr_equal_p(x.v_, y.v_); }

  friend Mpfr pow(const Mpfr& x, const Mpfr& y) { Mpfr r(wider(x, y)); mpfr_pow(r.v_, x.v_, y.v_, MPFR_RNDN); return r; }

  double to_double() const { return mpfr_get_d(v_, MPFR_RNDN); }

 private:
  mpfr_t v_;
  mp_limb_t limbs_[kInlineLimbs];

  template <class E>
  [[gnu::noinline, gnu::cold]] void assign_other_precision(const E& e) {
    *this = Mpfr(e);  // the precision changes with the value; e may refer to *this
  }

  static mpfr_prec_t wider(const Mpfr& x, const Mpfr& y) { return std::max(x.bits(), y.bits()); }
  bool is_inline() const { return mpfr_custom_get_significand(v_) == static_cast<const void*>(limbs_); }
  void init(mpfr_prec_t bits) {
    static_assert(kInlineBits % GMP_NUMB_BITS == 0 && sizeof(limbs_) == kInlineLimbs * sizeof(mp_limb_t));
    if (bits <= kInlineBits) [[likely]] {
      mpfr_custom_init(limbs_, bits);
      mpfr_custom_init_set(v_, MPFR_NAN_KIND, 0, bits, limbs_);
    } else {
      mpfr_init2(v_, bits);
    }
  }
  void release() {
    if (!is_inline()) mpfr_clear(v_);
  }
  // Copy an inline value of the same precision: header fields and the used limbs.
  void copy_limbs(const Mpfr& o) {
    v_->_mpfr_sign = o.v_->_mpfr_sign;
    v_->_mpfr_exp = o.v_->_mpfr_exp;
    // NaN, infinities and zeros live in the exponent field; their limbs are never read.
    if (mpfr_regular_p(o.v_)) copy_limb_array(limbs_, o.limbs_, mpfr_custom_get_size(o.bits()) / sizeof(mp_limb_t));
  }
  // Copy a value of the same precision wherever its limbs live: what mpfr_set does for
  // equal precisions (special values live in the exponent field), without the call.
  void copy_value(const Mpfr& o) {
    v_->_mpfr_sign = o.v_->_mpfr_sign;
    v_->_mpfr_exp = o.v_->_mpfr_exp;
    if (!mpfr_regular_p(o.v_)) return;
    copy_limb_array(static_cast<mp_limb_t*>(mpfr_custom_get_significand(v_)),
                    static_cast<const mp_limb_t*>(mpfr_custom_get_significand(o.v_)),
                    mpfr_custom_get_size(o.bits()) / sizeof(mp_limb_t));
  }

 public:
  // Up to 4 limbs (256 bits) by plain assignments: a call to memmove for two limbs cost
  // ~19% of a 113-bit step (measured with perf on tools/bench/bench_step).
  static void copy_limb_array(mp_limb_t* to, const mp_limb_t* from, size_t n) {
    switch (n) {
      case 4: to[3] = from[3]; [[fallthrough]];
      case 3: to[2] = from[2]; [[fallthrough]];
      case 2: to[1] = from[1]; [[fallthrough]];
      case 1: to[0] = from[0]; break;
      default: std::memcpy(to, from, n * sizeof(mp_limb_t));
    }
  }
};

// ---------------------------------------------------------------------------------------
// Expressions. `x + y`, `2 * a * G`, `(W + root) / a` are small trees of references to
// the named operands; assigning one to an Mpfr evaluates it there, node by node, with the
// same MPFR calls and the same roundings as one temporary per operation would give (each
// operation rounds to the larger precision of its operands), but without the temporaries:
// the impact map's MPFR step costs about what hand-written mpfr_t code costs
// (tools/bench/bench_step). A temporary is made only where two sub-expressions meet
// (a + b) * (c + d), where an operand would be overwritten before it is read, or where a
// sub-expression has a smaller precision than the whole.
//
// Operands that are temporaries themselves (sqrt(x) + y) are moved into the tree, so a
// tree never refers to a dead value. A tree does refer to named operands: evaluate it
// before they change or go out of scope (write `Mpfr d = x - y;` or `T d = ...`, never
// `auto d = x - y;`, and give lambdas that return arithmetic a `-> T` return type).
// ---------------------------------------------------------------------------------------
namespace mpfr_expr {

constexpr mpfr_rnd_t kRound = MPFR_RNDN;

template <class I>
concept small_int = std::integral<I> && !std::same_as<I, bool> &&
                    (std::is_signed_v<I> ? sizeof(I) <= sizeof(long) : sizeof(I) < sizeof(long));

// Leaves.
struct Ref {  // a named Mpfr
  const Mpfr* p;
  static constexpr bool node = false;
  mpfr_prec_t prec() const { return p->bits(); }
  mpfr_srcptr src() const { return p->get(); }
  bool is(const Mpfr& d) const { return p == &d; }
  bool same(mpfr_prec_t bits) const { return p->bits() == bits; }
};
struct Own {  // a temporary Mpfr, moved into the tree
  Mpfr v;
  static constexpr bool node = false;
  mpfr_prec_t prec() const { return v.bits(); }
  mpfr_srcptr src() const { return v.get(); }
  bool is(const Mpfr&) const { return false; }
  bool same(mpfr_prec_t bits) const { return v.bits() == bits; }
};
struct Int {  // an exact small integer (MPFR's _si functions: no rounding of the integer)
  long n;
  static constexpr bool node = false;
  mpfr_prec_t prec() const { return 0; }
  bool same(mpfr_prec_t) const { return true; }
};

// The four operations, on (number, number), (number, integer) and (integer, number).
struct Add {
  static void run(mpfr_ptr d, mpfr_srcptr x, mpfr_srcptr y) { mpfr_add(d, x, y, kRound); }
  static void run(mpfr_ptr d, mpfr_srcptr x, long n) { mpfr_add_si(d, x, n, kRound); }
  static void run(mpfr_ptr d, long n, mpfr_srcptr x) { mpfr_add_si(d, x, n, kRound); }
};
struct Sub {
  static void run(mpfr_ptr d, mpfr_srcptr x, mpfr_srcptr y) { mpfr_sub(d, x, y, kRound); }
  static void run(mpfr_ptr d, mpfr_srcptr x, long n) { mpfr_sub_si(d, x, n, kRound); }
  static void run(mpfr_ptr d, long n, mpfr_srcptr x) { mpfr_si_sub(d, n, x, kRound); }
};
struct Mul {
  static void run(mpfr_ptr d, mpfr_srcptr x, mpfr_srcptr y) { mpfr_mul(d, x, y, kRound); }
  static void run(mpfr_ptr d, mpfr_srcptr x, long n) { mpfr_mul_si(d, x, n, kRound); }
  static void run(mpfr_ptr d, long n, mpfr_srcptr x) { mpfr_mul_si(d, x, n, kRound); }
};
struct Div {
  static void run(mpfr_ptr d, mpfr_srcptr x, mpfr_srcptr y) { mpfr_div(d, x, y, kRound); }
  static void run(mpfr_ptr d, mpfr_srcptr x, long n) { mpfr_div_si(d, x, n, kRound); }
  static void run(mpfr_ptr d, long n, mpfr_srcptr x) { mpfr_si_div(d, n, x, kRound); }
};

template <class X>
mpfr_srcptr src_of(const X& x) { return x.src(); }
inline long src_of(const Int& x) { return x.n; }
template <class X>
bool is_leaf_equal(const X& x, const Mpfr& d) {
  if constexpr (X::node || std::is_same_v<X, Int>) return false;
  else return x.is(d);
}

#define BOUNCER_INLINE [[gnu::always_inline]] inline
#define BOUNCER_COLD [[gnu::noinline, gnu::cold]]

// Evaluate sub-expression x into d, which has at least x's precision. A sub-expression
// of smaller precision is rounded to its own precision first (as its temporary would be).
template <class X>
void eval_child(const X& x, Mpfr& d) {
  if (x.prec() == d.bits()) {
    x.eval(d);
  } else {
    Mpfr t(x);
    mpfr_set(d.get(), t.get(), kRound);  // exact: d is wider
  }
}

// Evaluation into d, where d.bits() == prec(). The hot path (every operand has d's
// precision) is inlined into the caller and makes exactly the MPFR calls of hand-written
// code; mixed precisions and operands that d would overwrite take the cold general path.
template <class Op, class L, class R>
struct Bin : MpfrExpression {
  L l;
  R r;
  static constexpr bool node = true;
  mpfr_prec_t prec() const { return std::max(l.prec(), r.prec()); }
  bool same(mpfr_prec_t p) const { return l.same(p) && r.same(p); }
  double to_double() const { return Mpfr(*this).to_double(); }

  BOUNCER_INLINE void eval(Mpfr& d) const {
    if (same(d.bits()) && !overwrites_operand(d)) [[likely]] fast(d);
    else general(d);
  }
  // An operand read after d has been overwritten by the other side.
  bool overwrites_operand(const Mpfr& d) const {
    bool hit = false;
    if constexpr (L::node && !R::node) hit = is_leaf_equal(r, d);
    if constexpr (!L::node && R::node) hit = is_leaf_equal(l, d);
    if constexpr (L::node) hit = hit || l.overwrites_operand(d);
    if constexpr (R::node && !L::node) hit = hit || r.overwrites_operand(d);
    return hit;
  }
  BOUNCER_INLINE void fast(Mpfr& d) const {
    if constexpr (!L::node && !R::node) {
      Op::run(d.get(), src_of(l), src_of(r));  // MPFR allows d to be an operand
    } else if constexpr (L::node && !R::node) {
      l.fast(d);
      Op::run(d.get(), d.get(), src_of(r));
    } else if constexpr (!L::node && R::node) {
      r.fast(d);
      Op::run(d.get(), src_of(l), d.get());
    } else {
      Mpfr t(d.bits());
      r.fast(t);  // evaluated before l overwrites d
      l.fast(d);
      Op::run(d.get(), d.get(), t.get());
    }
  }
  BOUNCER_COLD void general(Mpfr& d) const {
    if constexpr (!L::node && !R::node) {
      Op::run(d.get(), src_of(l), src_of(r));
    } else if constexpr (L::node && !R::node) {
      if (is_leaf_equal(r, d)) return via_temporary(d);  // r would be overwritten first
      eval_child(l, d);
      Op::run(d.get(), d.get(), src_of(r));
    } else if constexpr (!L::node && R::node) {
      if (is_leaf_equal(l, d)) return via_temporary(d);
      eval_child(r, d);
      Op::run(d.get(), src_of(l), d.get());
    } else {
      const Mpfr t(r);  // evaluated before l overwrites d
      eval_child(l, d);
      Op::run(d.get(), d.get(), t.get());
    }
  }
  void via_temporary(Mpfr& d) const {
    Mpfr t(*this);
    d = std::move(t);
  }
};

// Functions of one operand, evaluated in place (MPFR allows d == x).
struct Neg {
  static void run(mpfr_ptr d, mpfr_srcptr x) { mpfr_neg(d, x, kRound); }
};
struct Sqrt {
  static void run(mpfr_ptr d, mpfr_srcptr x) { mpfr_sqrt(d, x, kRound); }
};
struct Exp {
  static void run(mpfr_ptr d, mpfr_srcptr x) { mpfr_exp(d, x, kRound); }
};
struct Log {
  static void run(mpfr_ptr d, mpfr_srcptr x) { mpfr_log(d, x, kRound); }
};
struct Abs {
  static void run(mpfr_ptr d, mpfr_srcptr x) { mpfr_abs(d, x, kRound); }
};
struct Floor {  // the integer part, correctly rounded to the operand's precision
  static void run(mpfr_ptr d, mpfr_srcptr x) { mpfr_floor(d, x); }
};

template <class Fn, class E>
struct Unary : MpfrExpression {
  E e;
  static constexpr bool node = true;
  mpfr_prec_t prec() const { return e.prec(); }
  bool same(mpfr_prec_t p) const { return e.same(p); }
  double to_double() const { return Mpfr(*this).to_double(); }
  bool overwrites_operand(const Mpfr& d) const {
    if constexpr (E::node) return e.overwrites_operand(d);
    else return false;
  }
  BOUNCER_INLINE void eval(Mpfr& d) const {
    if constexpr (E::node) {
      e.eval(d);
      Fn::run(d.get(), d.get());
    } else {
      Fn::run(d.get(), e.src());
    }
  }
  BOUNCER_INLINE void fast(Mpfr& d) const { eval(d); }
};

template <class X>
concept operand = std::same_as<std::remove_cvref_t<X>, Mpfr> || is_mpfr_node<X>;

// The tree's handle on an operand: a reference to a named Mpfr, ownership of a temporary
// Mpfr, or the sub-expression itself (moved).
template <class X>
auto leaf(X&& x) {
  using V = std::remove_cvref_t<X>;
  if constexpr (std::is_same_v<V, Mpfr>) {
    if constexpr (std::is_lvalue_reference_v<X>) return Ref{&x};
    else return Own{std::move(x)};
  } else {
    return V(std::forward<X>(x));
  }
}
template <class Op, class X, class Y>
auto bin(X&& x, Y&& y) {
  return Bin<Op, decltype(leaf(std::forward<X>(x))), decltype(leaf(std::forward<Y>(y)))>{
      {}, leaf(std::forward<X>(x)), leaf(std::forward<Y>(y))};
}
template <class Op, class X>
auto bin_int(X&& x, long n) {
  return Bin<Op, decltype(leaf(std::forward<X>(x))), Int>{{}, leaf(std::forward<X>(x)), Int{n}};
}
template <class Op, class X>
auto int_bin(long n, X&& x) {
  return Bin<Op, Int, decltype(leaf(std::forward<X>(x)))>{{}, Int{n}, leaf(std::forward<X>(x))};
}
template <class Fn, class X>
auto unary(X&& x) {
  return Unary<Fn, decltype(leaf(std::forward<X>(x)))>{{}, leaf(std::forward<X>(x))};
}

}  // namespace mpfr_expr

#define BOUNCER_MPFR_OPERATOR(sym, Op)                                                          \
  template <class X, class Y> requires mpfr_expr::operand<X> && mpfr_expr::operand<Y>          \
  auto operator sym(X&& x, Y&& y) { return mpfr_expr::bin<mpfr_expr::Op>(std::forward<X>(x), std::forward<Y>(y)); } \
  template <class X, mpfr_expr::small_int I> requires mpfr_expr::operand<X>                     \
  auto operator sym(X&& x, I n) { return mpfr_expr::bin_int<mpfr_expr::Op>(std::forward<X>(x), static_cast<long>(n)); } \
  template <mpfr_expr::small_int I, class X> requires mpfr_expr::operand<X>                     \
  auto operator sym(I n, X&& x) { return mpfr_expr::int_bin<mpfr_expr::Op>(static_cast<long>(n), std::forward<X>(x)); }
BOUNCER_MPFR_OPERATOR(+, Add)
BOUNCER_MPFR_OPERATOR(-, Sub)
BOUNCER_MPFR_OPERATOR(*, Mul)
BOUNCER_MPFR_OPERATOR(/, Div)
#undef BOUNCER_MPFR_OPERATOR
#undef BOUNCER_INLINE
#undef BOUNCER_COLD

#define BOUNCER_MPFR_FUNCTION(name, Fn)                          \
  template <class X> requires mpfr_expr::operand<X>               \
  auto name(X&& x) { return mpfr_expr::unary<mpfr_expr::Fn>(std::forward<X>(x)); }
BOUNCER_MPFR_FUNCTION(operator-, Neg)
BOUNCER_MPFR_FUNCTION(sqrt, Sqrt)
BOUNCER_MPFR_FUNCTION(exp, Exp)
BOUNCER_MPFR_FUNCTION(log, Log)
BOUNCER_MPFR_FUNCTION(abs, Abs)
BOUNCER_MPFR_FUNCTION(floor, Floor)
#undef BOUNCER_MPFR_FUNCTION

// Namespace-scope declarations of the friends, so that bouncer::pow(x, y) etc. also work.
Mpfr pow(const Mpfr& x, const Mpfr& y);
bool operator<(const Mpfr& x, const Mpfr& y);  // also for expressions, once evaluated
bool operator<=(const Mpfr& x, const Mpfr& y);
bool operator>(const Mpfr& x, const Mpfr& y);
bool operator>=(const Mpfr& x, const Mpfr& y);
bool operator==(const Mpfr& x, const Mpfr& y);

}  // namespace bouncer
