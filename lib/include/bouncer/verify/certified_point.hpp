// A certified long-run answer for one exact start (constant restitution, velocity-dependent
// restitution without collapse, or the elastic model): what every pixel of `basin --certify`
// states, with the double answer next to it (the artefact map).
//
// The start's orbit is followed in interval arithmetic (certify_sticking: interval:double,
// then MPFI at 64, 128, ... up to max_bits) for at most max_steps steps:
//   sticking k   certified: the orbit sticks (first at step `first_sticking`); after the
//                release it sticks again every k steps (the release orbit's own certificate,
//                computed once per release state and shared by every start that sticks);
//   fixed        certified: the orbit never sticks and lies, from step `certified_steps` on,
//   periodic p   in a set K with F^q(K) inside K around a period-p attractor (p = 1: fixed);
//                also when the orbit sticks and its release orbit is so trapped;
//   no_sticking  certified: no sticking in steps 1..certified_steps (= max_steps), and no
//                trapping set was found; or, after a first sticking, the release orbit is
//                certified free of sticking for free_steps >= max_steps steps;
//   not_trapped  velocity-dependent and elastic only (no orbit collapses there, so no
//                sticking class): the orbit is certified through all max_steps steps, and no
//                trapping set was found at its end (a chaotic orbit, or an attractor too slow
//                or too neutral for the proof); fixed and periodic p are as above. Elastic:
//                the map preserves area, so no trapping set exists and none is looked for;
//                not_trapped and undecided (with its certified_steps) are its only classes,
//                and they separate orbits certified for the whole run (in practice the
//                regular islands) from those whose enclosure outgrew the schedule (the
//                chaotic sea);
//   undecided    steps 1..certified_steps are certified free of sticking, the next step was
//                undecided at every precision of the schedule (`reason`).
// The release orbit, shared by every start that sticks, gets the full schedule (MPFI up to
// 4096 bits) and at least 20000 steps: its certificate decides whether double's sticking
// period is real (at eps = 0.5, a = 15 double's 3773 is not: certified free through 13672).
// Nothing here is guessed: a class other than undecided is a theorem about the exact orbit
// of the exact start (a double grid point is an exact dyadic number) and the exact decimal
// parameters.
#pragma once

#include <functional>
#include <map>
#include <mutex>
#include <optional>
#include <utility>
#include <string>
#include <string_view>

#include "bouncer/analysis/classify.hpp"
#include "bouncer/model/spec.hpp"
#include "bouncer/verify/sticking.hpp"

namespace bouncer {

// What a certificate states of one start (the header above); `outside` marks a grid start
// below the wall's velocity (no orbit, never returned by certify_point).
enum class CertifiedClass { sticking, fixed, periodic, no_sticking, not_trapped, undecided, outside };
inline constexpr int kCertifiedClassCount = static_cast<int>(CertifiedClass::outside) + 1;
const char* name(CertifiedClass c);  // "sticking", ..., "not_trapped", "undecided", "outside"
std::optional<CertifiedClass> certified_class_named(std::string_view text);

// A point answer against the certified one (compare_with_certified); `outside` as above.
enum class Agreement { agrees, differs, undecided, outside };
const char* name(Agreement a);  // "agrees", "differs", "undecided", "outside"
std::optional<Agreement> agreement_named(std::string_view text);

struct CertifiedPoint {
  CertifiedClass cls = CertifiedClass::undecided;
  long period = 0;                   // sticking: k; fixed / periodic: the attractor's period
  long long first_sticking = 0;      // sticking (and classes reached through a release): step
  long long certified_steps = 0;     // steps of the start's own run certified
  long long free_steps = 0;          // after a first sticking: release steps certified free of it
  std::string scalar;                // the tier that decided the start's run ("" if none)
  std::string reason;                // undecided: why
};

struct CertifyPointOptions {
  long long max_steps = 5500;        // steps followed from the start (and from a release)
  long max_bits = 256;               // the schedule's last MPFI precision
  long max_attractor_period = 64;    // longest attractor period looked for
  // a as the exact rational [lo, hi] instead of the model's decimal a (bifurcation columns:
  // the double parameter value itself, lo = hi).
  std::optional<std::pair<mpq_class, mpq_class>> a_range;
};

// Certificates of release states, computed once each and shared between threads.
class ReleaseCache {
 public:
  StickingCertificate get(const ModelSpec& model, const std::string& theta, const std::string& v,
                          const CertifyPointOptions& opt);
  // A smooth wall's release state (StickingQuestion::from_release).
  StickingCertificate get_release(const ModelSpec& model, const CertifyPointOptions& opt);

 private:
  std::mutex mutex_;
  std::map<std::string, StickingCertificate> done_;
};

// Certified grids (basin, scan, bifurcation --certify) exist for the models of
// why_no_certified_answers (verify/sticking.hpp) and for the elastic model (certified orbits,
// no attractor: not_trapped or undecided). Throws InputError("certify", ...) naming `command`,
// what is allowed and why, for any other model (velocity-dependent collapse).
void require_certified_model(const ModelSpec& m, const std::string& command);

// Certifies the orbit of the exact start (theta, v) (decimal text, exact). After a first
// sticking the orbit goes on from the release state: an exact knot of a piecewise wall, or a
// smooth wall's release enclosed by the interval model (ReleaseCache::get_release).
CertifiedPoint certify_point(const ModelSpec& model, const InitialCondition& start, const CertifyPointOptions& opt,
                             ReleaseCache& releases);

// Certifies the orbit of a smooth wall's release state (the start every sticking orbit passes
// through, as (1/2, 4) is the triangle's): its class, as certify_point's after a sticking.
CertifiedPoint certify_release_point(const ModelSpec& model, const CertifyPointOptions& opt, ReleaseCache& releases);

// Does a point answer agree with the certified one? agrees, differs (the point answer is an
// artefact of its precision) or undecided (no certified answer to compare with).
// double_class / double_period: bouncer::classify's class and period (a double run of the
// grid's transient + steps <= max_steps, so a double "sticking" stuck within max_steps).
Agreement compare_with_certified(const CertifiedPoint& c, OrbitClass double_class, long double_period);

}  // namespace bouncer
