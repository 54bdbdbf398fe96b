#include "bouncer/run/orbit.hpp"

#include <optional>
#include <type_traits>

#include "bouncer/base/cancel.hpp"
#include "bouncer/scalar/scalar_set.hpp"

namespace bouncer {

template <class T>
OrbitOutcome follow_orbit(const ImpactMap<T>& map, const State<T>& start, const OrbitSteps& how, OrbitSink<T>& sink) {
  using Tr = ScalarTraits<T>;
  OrbitOutcome o;
  State<T> s = start;
  sink.start(s);
  std::optional<OrbitEnclosureOf<std::conditional_t<Tr::is_interval, T, Mpfi>>> lohner;
  if constexpr (Tr::is_interval) {
    if (how.method == EnclosureMethod::lohner) {
      lohner.emplace(map.model(), s, EnclosureMethod::lohner);
      o.fallbacks = 0;
    }
  }
  auto step = [&](const State<T>& from) -> StepResult<T> {
    if constexpr (Tr::is_interval) {
      if (lohner) {
        auto e = lohner->step();
        o.fallbacks = lohner->fallbacks();
        e.event.next = std::move(e.next);  // the Lohner box, tighter than the box image
        return std::move(e.event);
      }
    }
    return map.step(from);
  };
  for (long long n = 1; n <= how.steps; ++n) {
    throw_if_cancelled(n);
    try {
      StepResult<T> r = step(s);
      s = r.next;
      o.steps_done = n;
      if (o.phase_lost_at < 0 && r.phase_bits_lost >= Tr::bits(s.theta)) o.phase_lost_at = n;
      if (n % how.every == 0 || n == how.steps) sink.row(n, r);
      if ((n & 4095) == 0) sink.check();
    } catch (const Undecided& u) {
      o.undecided = true;
      o.reason = u.what();
      break;
    }
  }
  return o;
}

#define BOUNCER_X(T, kind) \
  template OrbitOutcome follow_orbit<T>(const ImpactMap<T>&, const State<T>&, const OrbitSteps&, OrbitSink<T>&);
BOUNCER_FOR_EACH_SCALAR(BOUNCER_X)
#undef BOUNCER_X

}  // namespace bouncer
