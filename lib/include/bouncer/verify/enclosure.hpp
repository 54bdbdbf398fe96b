// Certified orbit enclosures: a set that provably contains the exact orbit of the exact
// decimal inputs, step by step, in interval arithmetic (MPFI at any precision, or the fast
// DoubleInterval of scalar/interval_double.hpp).
//
// Two methods:
//   naive   iterate the interval box with ImpactMap<Mpfi>. Simple, but a 2-D box that the
//           map rotates and shears is re-boxed every step (the wrapping effect), so the
//           enclosure grows faster than the dynamics requires.
//   lohner  mean-value form with a moving orthogonal frame (Lohner's QR method): the set is
//           c + B r (c a point, B an orthogonal 2x2 matrix, r an interval vector). One step:
//             X~ = hull(c + B r);  J  = interval Jacobian of the step over X~
//             (ImpactMap<Dual<Mpfi>>: forward-mode derivatives in interval arithmetic);
//             y  = interval image of the point c (ImpactMap<Mpfi>);
//             c' = mid(y);  B' = Q of the QR factorization of mid(J B);
//             r' = (B'^-1 J B) r + B'^-1 (y - c')   (B'^-1 enclosed rigorously).
//           Valid because every branch of the step is decided for the whole of X~, so the
//           step is one smooth formula there and the mean value theorem applies. The
//           enclosure then grows at the rate of the true linearized dynamics.
//           If the Jacobian enclosure is not finite (e.g. a square root of an interval
//           touching 0), the step falls back to the naive box image (counted).
// Both methods decide every branch for the whole set (Undecided otherwise), so the event
// kind of each step (impact, sticking, ride) is certain. The model may carry interval
// parameters (e.g. a = [A0, A1]): the result then holds for every parameter in them.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <utility>

#include "bouncer/model/impact_map.hpp"
#include "bouncer/scalar/decimal.hpp"
#include "bouncer/verify/escalation.hpp"

namespace bouncer {

enum class EnclosureMethod { naive, lohner };
const char* name(EnclosureMethod m);
EnclosureMethod parse_enclosure_method(const std::string& field, const std::string& text);

// The point type of an interval type's ends and midpoints: Mpfr for Mpfi, double for
// DoubleInterval. Frames (c, B) are points; only the interval parts carry the rigour.
template <class S>
struct PointOf;
template <>
struct PointOf<Mpfi> {
  using type = Mpfr;
};
template <>
struct PointOf<DoubleInterval> {
  using type = double;
};
template <class S>
using PointOfT = typename PointOf<S>::type;

// Model<S> with every decimal enclosed (at `bits` for Mpfi; DoubleInterval has 53); with
// a_range, a is the interval [lo, hi] (exact rationals enclosed outward) instead of the
// spec's a.
template <class S>
Model<S> interval_model_of(const ModelSpec& spec, long bits,
                           const std::optional<std::pair<mpq_class, mpq_class>>& a_range = std::nullopt);
inline Model<Mpfi> interval_model(const ModelSpec& spec, long bits,
                                  const std::optional<std::pair<mpq_class, mpq_class>>& a_range = std::nullopt) {
  return interval_model_of<Mpfi>(spec, bits, a_range);
}
// The interval [lo, hi] of two exact rationals, rounded outward at `bits`.
Mpfi enclose(const mpq_class& lo, const mpq_class& hi, long bits);
template <class S>
S enclose_as(const mpq_class& lo, const mpq_class& hi, long bits);

template <class S>
struct EnclosedStepOf {
  // The interval step over the box before the step (both methods compute it): its kind and
  // event fields (tau, periods, sticking, ...) enclose those of every state in the set, and
  // event.next is the box image.
  StepResult<S> event;
  State<S> next;             // box enclosing the exact state after the step (lohner: tighter)
  bool fallback = false;     // lohner only: this step used the naive box image
};
using EnclosedStep = EnclosedStepOf<Mpfi>;

// The set c + B r (c a point, B an invertible matrix, r an interval vector).
template <class S>
struct ParallelogramOf {
  PointOfT<S> c[2];
  PointOfT<S> B[2][2];
  S r[2];
};
using Parallelogram = ParallelogramOf<Mpfi>;

// Instantiated for the enclosure scalars (scalar/scalar_set.hpp): Mpfi and DoubleInterval.
template <class S>
class OrbitEnclosureOf {
 public:
  OrbitEnclosureOf(const Model<S>& model, const State<S>& start, EnclosureMethod method);
  // Lohner, starting from the set c + B r (B need not be orthogonal).
  OrbitEnclosureOf(const Model<S>& model, const ParallelogramOf<S>& start);
  ~OrbitEnclosureOf();
  OrbitEnclosureOf(OrbitEnclosureOf&&) noexcept;
  OrbitEnclosureOf& operator=(OrbitEnclosureOf&&) noexcept;

  // One certified step. Throws Undecided when a branch is undecided for the set.
  EnclosedStepOf<S> step();
  const State<S>& box() const;     // current enclosure (a box)
  ParallelogramOf<S> set() const;  // current enclosure (Lohner: c + B r; naive: the box)
  long long steps() const;
  long long fallbacks() const;
  EnclosureMethod method() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};
using OrbitEnclosure = OrbitEnclosureOf<Mpfi>;

// Approximate Jacobian of F^q at the midpoint of x (the product of the step Jacobians at
// the midpoints along its orbit; for building frames, not a rigorous enclosure); false if a
// step is undecided or a derivative is not finite.
template <class S>
bool jacobian_of_iterate(const Model<S>& model, const State<S>& x, long q, double J[2][2]);

// Largest width of the box's two components, as a double (for reports).
template <class S>
double box_width(const State<S>& s);

// Steps certified from `start` at `bits` before the first undecided step (at most
// max_steps); the reason when it stopped early.
struct Horizon {
  long long steps = 0;
  bool reached_max = false;
  std::string reason;
  double seconds = 0;
};
template <class S = Mpfi>
Horizon certified_horizon(const ModelSpec& spec, const InitialCondition& start, long bits, EnclosureMethod method,
                          long long max_steps);

}  // namespace bouncer
