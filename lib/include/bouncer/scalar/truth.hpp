// Three-valued decisions: the one place where the impact map branches.
//
// Every comparison the map makes returns a Truth, never a bool. For point types (double,
// MPFR, ...) it is `yes` or `no` (or `invalid` when a value is NaN). For interval types it
// is `unknown` when the enclosures overlap. `decide()` turns a Truth into a bool and ends
// the step with an `Undecided` exception otherwise, so an interval run never guesses and
// never crashes. `certainly()` is for optional shortcuts that are correct either way.
#pragma once

#include <stdexcept>
#include <string>

namespace bouncer {

enum class Truth : unsigned char { no, yes, unknown, invalid };

constexpr Truth truth(bool b) { return b ? Truth::yes : Truth::no; }
constexpr Truth operator!(Truth t) {
  return t == Truth::yes ? Truth::no : t == Truth::no ? Truth::yes : t;
}

// Why a step could not be completed.
enum class Reason : unsigned char {
  phase_at_corner,     // theta's enclosure straddles a wall corner
  impact_at_corner,    // the impact time straddles the end of a wall segment
  corner_approach,     // at a corner hit, approaching or separating is undecided
  sticking_threshold,  // the post-impact velocity straddles the sticking threshold
  riding,              // the relative velocity straddles zero (riding the wall or not)
  period_boundary,     // theta + flight time straddles an integer
  walk_limit,          // the flight crosses more wall segments than the walk allows
  grazing,             // smooth wall: the flight may touch the wall before its impact (first root)
  nonfinite,           // NaN or overflow
};

const char* describe(Reason r);

// Thrown by decide(); caught by every driver that runs steps.
struct Undecided : std::runtime_error {
  Reason reason;
  explicit Undecided(Reason r) : std::runtime_error(describe(r)), reason(r) {}
};

[[noreturn, gnu::cold, gnu::noinline]] void throw_undecided(Truth t, Reason where);

// The only way to turn a comparison into control flow in the model code. The yes/no path
// is inline; the throw lives out of line so that the hot path pays no call.
inline bool decide(Truth t, Reason where) {
  if (t == Truth::yes) return true;
  if (t != Truth::no) throw_undecided(t, where);
  return false;
}

// For shortcuts whose "no" branch is also correct (e.g. skipping a long flight).
constexpr bool certainly(Truth t) { return t == Truth::yes; }

}  // namespace bouncer
