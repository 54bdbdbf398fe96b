// Precision escalation: run a certified (interval) computation at B bits and, where a step
// is undecided, run it again at more bits, following a fixed, documented schedule.
//
// Schedule: with double_first, one run in DoubleInterval (interval:double, 53 bits, the fast
// certified scalar of scalar/interval_double.hpp) first; then MPFI at start_bits, doubling
// (64, 128, 256, 512, 1024, 2048, 4096, ...), the last entry clipped to max_bits. A rerun starts from the beginning (the computation is a pure
// function of the bits), so every certified answer is the answer of one run at one
// precision, which `bits` names.
//
// The computation is any callable `R run(const Tier& tier, Progress& p)` (or
// `R run(long bits, Progress& p)`, which runs the MPFI tiers only) that either returns its
// result or throws `Undecided` (scalar/truth.hpp); it records in `p.steps` how far it got,
// so that a give-up says where and why ("undecided at step 851 at 1024 bits: theta's
// enclosure straddles a wall corner").
#pragma once

#include <chrono>
#include <optional>
#include <string>
#include <type_traits>
#include <vector>

#include "bouncer/scalar/truth.hpp"

namespace bouncer {

// One run of the schedule: DoubleInterval, or MPFI at `bits`.
struct Tier {
  bool double_interval = false;
  long bits = 53;
  std::string text() const;  // "interval:double" or "interval:BITS"
};

struct EscalationSchedule {
  long start_bits = 64;
  long max_bits = 4096;
  // Stop early when a rerun at more bits certifies no more steps than the run before
  // (the enclosure is then limited by something bits cannot fix, e.g. a parameter
  // interval's width): used by adaptive bisection over parameter intervals.
  bool stop_when_stalled = false;
  // Run in DoubleInterval (interval:double) before the MPFI tiers.
  bool double_first = false;
  // start_bits, 2 start_bits, 4 start_bits, ... and max_bits last (if not already there).
  std::vector<long> bits() const;
  // The runs in order: interval:double (with double_first), then MPFI at bits().
  std::vector<Tier> tiers() const;
  // e.g. "interval:double, then 64, 128, 256, ... doubling up to 4096 bits"
  std::string text() const;
};

// What a run reports about its progress, also when it ends with Undecided.
struct Progress {
  long long steps = 0;  // steps certified so far in this run
};

struct Attempt {
  long bits = 0;
  bool double_interval = false;  // this run was the interval:double tier
  std::string scalar;        // "interval:double" or "interval:BITS" (Tier::text)
  bool decided = false;      // the run finished (its result is certified)
  long long steps = 0;       // steps certified in this run
  std::string reason;        // why it stopped, when undecided
  double seconds = 0;
};

template <class R>
struct Escalated {
  std::optional<R> result;       // from the first run that finished
  long bits = 0;                 // bits of that run (0 if none finished)
  std::string scalar;            // its Tier::text ("" if none finished)
  std::vector<Attempt> attempts; // in schedule order
  double seconds = 0;            // total wall time of all attempts
  // When no run finished: the best run (most steps) and why it stopped.
  long long best_steps = 0;
  long best_bits = 0;
  std::string gave_up;           // "" when a run finished
};

namespace detail {
double seconds_since(std::chrono::steady_clock::time_point t0);
std::string give_up_text(const Attempt& best, long max_bits);
}  // namespace detail

template <class R, class F>
Escalated<R> escalate(const EscalationSchedule& schedule, F&& run) {
  constexpr bool kTiers = std::is_invocable_v<F&, const Tier&, Progress&>;
  Escalated<R> out;
  const auto t_all = std::chrono::steady_clock::now();
  Attempt best;
  for (const Tier& tier : schedule.tiers()) {
    if (!kTiers && tier.double_interval) continue;  // a bits-only computation: MPFI tiers
    Attempt a;
    a.bits = tier.bits;
    a.double_interval = tier.double_interval;
    a.scalar = tier.text();
    Progress p;
    const auto t0 = std::chrono::steady_clock::now();
    try {
      if constexpr (kTiers) out.result.emplace(run(tier, p));
      else out.result.emplace(run(tier.bits, p));
      a.decided = true;
      a.steps = p.steps;
    } catch (const Undecided& u) {
      a.steps = p.steps;
      a.reason = u.what();
    }
    a.seconds = detail::seconds_since(t0);
    out.attempts.push_back(a);
    if (a.steps >= best.steps || best.bits == 0) best = a;
    if (a.decided) {
      out.bits = tier.bits;
      out.scalar = a.scalar;
      break;
    }
    // A stall is judged between two MPFI runs (the double tier is a cheap first try).
    const Attempt* before = out.attempts.size() >= 2 ? &out.attempts[out.attempts.size() - 2] : nullptr;
    if (schedule.stop_when_stalled && before && !before->double_interval && !a.double_interval && a.steps <= before->steps)
      break;
  }
  out.best_steps = best.steps;
  out.best_bits = best.bits;
  if (!out.result) out.gave_up = detail::give_up_text(best, schedule.max_bits);
  out.seconds = detail::seconds_since(t_all);
  return out;
}

}  // namespace bouncer
