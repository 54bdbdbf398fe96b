// The impact map (theta_n, v_n) -> (theta_{n+1}, v_{n+1}) of the piecewise linear bouncer,
// derived from first principles (see README "The model") and written once for every
// scalar type. The paper's explicit map (eqs. 3-4) is used only as a cross-check in tests.
#pragma once

#include <vector>

#include "bouncer/model/model.hpp"
#include "bouncer/scalar/scalar_set.hpp"

namespace bouncer {

enum class EventKind : unsigned char {
  impact,    // a flight ending in a collision
  sticking,  // a collision below the sticking threshold: collapse, ride, release
  ride,      // started with zero relative velocity: rode the wall to a corner
};
const char* name(EventKind);

template <class T>
struct StepResult {
  State<T> next;
  T tau;                      // time from the start state to `next`
  long long periods = 0;      // whole wall periods begun during the step (theta wraps)
  int segment = 0;            // wall segment of the last contact (impact or ride)
  EventKind kind = EventKind::impact;
  bool corner = false;        // the last impact was exactly at a wall corner
  Truth indirect = Truth::no; // the particle left the collision zone (rose above the top)
  // Sticking only: the collision that started the collapse, its segment, and whether the
  // ride passed an upward turn (where the downward-sticking convention applies).
  int stick_segment = -1;
  bool passed_upward_turn = false;
  T stuck_theta, stuck_v;
  // Bits of theta consumed by the whole part of theta_n + tau in a long flight: theta
  // keeps (bits - phase_bits_lost) correct bits at best. 0 for flights within a period.
  int phase_bits_lost = 0;
};

template <class T>
class ImpactMap {
  static_assert(Scalar<T>, "the impact map needs a scalar type meeting the contract of scalar/contract.hpp");

 public:
  explicit ImpactMap(Model<T> model) : m_(std::move(model)), zero_(m_.zero()) {}
  const Model<T>& model() const { return m_; }

  // One step. Throws Undecided when a branch cannot be decided (intervals, NaN).
  StepResult<T> step(const State<T>& s) const;

  // K steps of K independent orbits: out[k] is step(s[k]) bit for bit, every field; where
  // step(s[k]) is undecided, bit k of the returned mask is set, why[k] is its reason and
  // out[k] is unspecified. The step of one orbit is a chain of dependent operations whose
  // latency, not the arithmetic, sets its speed; here the common case of the step, written
  // without calls, is stamped out once per lane in one function, so that the processor
  // overlaps the K independent chains, and a lane whose step is not of that case takes
  // step() itself. The common case computes every value with step()'s own helpers (the
  // flight's root, the corner's gap, the jump), so the results are the same bit for bit.
  // Instantiated for double (kStepLanes lanes), the point type of grids; other types and
  // lane counts need impact_map_impl.hpp.
  template <int K>
  unsigned step_n(const State<T>* s, StepResult<T>* out, Reason* why) const;

  // The collision law (paper eq. 2) in the wall's frame: the relative speed after a
  // collision of relative speed `speed` (constant: eps speed; veldep: exp(-(speed/c)^(3/5))
  // speed; elastic: speed). Each bounce of a chatter is one such collision.
  T rebound(const T& speed) const;

  // A collapse on the wall (README "Sticking"): a chatter of relative launch speed w that
  // begins `offset` after the collision that stuck.
  struct Collapse {
    T offset;
    T w;
  };
  // The rest of a sticking step r of step() after its collision that stuck (r.stick_segment,
  // r.stuck_theta, r.stuck_v), walked as step() walks it: the ride on the wall to the release
  // (or to an upward-turn collision that launches the particle). Appends the collapse at the
  // stuck collision (offset 0, w = stuck_v - u_j) and one for every upward-turn collision
  // that sticks again (--downward-sticking impact); returns the walk's duration, so that the
  // stuck collision was r.tau minus it after the step's start.
  T after_sticking(const StepResult<T>& r, std::vector<Collapse>& collapses) const;

 private:
  Model<T> m_;
  T zero_;  // 0 at the model's precision, built once
  // The step into r (default-constructed), inlined into step().
  [[gnu::always_inline]] inline void step_into(const State<T>& s, StepResult<T>& r) const;
  // The common case of step_into for a point type, with no call and fewer branches: a flight
  // of a few pieces (with at most one jump over the top) ending in an impact that does not
  // stick. Writes step()'s result into r (default-constructed) and returns true, or returns
  // false (r unspecified) where the step is not of that case. Each lane of step_n().
  [[gnu::always_inline]] inline bool common_step(const State<T>& s, StepResult<T>& r) const;
  // `collapses`: where after_sticking records the collapses of the walk (step(): none).
  void collide(StepResult<T>& r, int j, T theta, const T& speed, int knot = -1,
               std::vector<Collapse>* collapses = nullptr) const;
  void ride(StepResult<T>& r, int j, const T& from, std::vector<Collapse>* collapses = nullptr) const;
  bool veldep_collapse_certain(const T& out, const T& time_left) const;
  // The sine wall's step (docs/model.md "The sine wall"): the first root of the gap after the
  // launch, a collision, and the sticking and riding rules of the smooth wall.
  void sine_step(const State<T>& s, StepResult<T>& r) const;
  void sine_collide(StepResult<T>& r, T theta, const T& speed) const;
  // The effective gravity a + f''(theta) in the sine wall's frame (impact_map_impl.hpp).
  T sine_gravity(const T& theta) const;
  // Rides the sine wall from phase `from` to the release phase (the next one after it).
  void sine_ride(StepResult<T>& r, const T& from) const;
  Truth left_zone(const State<T>& s, int j0, const T& u, const T& q) const;
};

// Explicitly instantiated in lib/src/model/map_instances.cpp for every type of the scalar set
// (scalar/scalar_set.hpp), one type per translation unit; for the duals over it, see
// analysis/jacobian.hpp and verify/interval_dual.hpp.
#define BOUNCER_X(T, kind)                  \
  extern template class ImpactMap<T>;       \
  extern template Model<T> make_model<T>(const ModelSpec&, long);
BOUNCER_FOR_EACH_SCALAR(BOUNCER_X)
#undef BOUNCER_X

// Lanes of the batched double step (step_n): of 2, 4 and 8, 4 was the fastest on the
// development machine (x86-64, SSE2 flags; bench_grid's "side by side" row measures it).
inline constexpr int kStepLanes = 4;
extern template unsigned ImpactMap<double>::step_n<kStepLanes>(const State<double>*, StepResult<double>*, Reason*) const;

}  // namespace bouncer
