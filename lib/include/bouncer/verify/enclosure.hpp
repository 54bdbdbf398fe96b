// Certified orbit enclosures: a set that provably contains the exact orbit of the exact
// decimal inputs, step by step, in MPFI interval arithmetic.
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

// Model<Mpfi> with every decimal enclosed at `bits`; with a_range, a is the interval
// [lo, hi] (exact rationals enclosed outward) instead of the spec's a.
Model<Mpfi> interval_model(const ModelSpec& spec, long bits,
                           const std::optional<std::pair<mpq_class, mpq_class>>& a_range = std::nullopt);
// The interval [lo, hi] of two exact rationals, rounded outward at `bits`.
Mpfi enclose(const mpq_class& lo, const mpq_class& hi, long bits);

struct EnclosedStep {
  // The interval step over the box before the step (both methods compute it): its kind and
  // event fields (tau, periods, sticking, ...) enclose those of every state in the set, and
  // event.next is the box image.
  StepResult<Mpfi> event;
  State<Mpfi> next;          // box enclosing the exact state after the step (lohner: tighter)
  bool fallback = false;     // lohner only: this step used the naive box image
};

// The set c + B r (c a point, B an invertible matrix, r an interval vector).
struct Parallelogram {
  Mpfr c[2];
  Mpfr B[2][2];
  Mpfi r[2];
};

class OrbitEnclosure {
 public:
  OrbitEnclosure(const Model<Mpfi>& model, const State<Mpfi>& start, EnclosureMethod method);
  // Lohner, starting from the set c + B r (B need not be orthogonal).
  OrbitEnclosure(const Model<Mpfi>& model, const Parallelogram& start);
  ~OrbitEnclosure();
  OrbitEnclosure(OrbitEnclosure&&) noexcept;
  OrbitEnclosure& operator=(OrbitEnclosure&&) noexcept;

  // One certified step. Throws Undecided when a branch is undecided for the set.
  EnclosedStep step();
  const State<Mpfi>& box() const;  // current enclosure (a box)
  Parallelogram set() const;       // current enclosure (Lohner: c + B r; naive: the box)
  long long steps() const;
  long long fallbacks() const;
  EnclosureMethod method() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// Approximate Jacobian of F^q at the midpoint of x (the product of the step Jacobians at
// the midpoints along its orbit; for building frames, not a rigorous enclosure); false if a
// step is undecided or a derivative is not finite.
bool jacobian_of_iterate(const Model<Mpfi>& model, const State<Mpfi>& x, long q, double J[2][2]);

// Largest width of the box's two components, as a double (for reports).
double box_width(const State<Mpfi>& s);

// Steps certified from `start` at `bits` before the first undecided step (at most
// max_steps); the reason when it stopped early.
struct Horizon {
  long long steps = 0;
  bool reached_max = false;
  std::string reason;
  double seconds = 0;
};
Horizon certified_horizon(const ModelSpec& spec, const InitialCondition& start, long bits, EnclosureMethod method,
                          long long max_steps);

}  // namespace bouncer
