// Certified sticking periods: escalation over interval enclosures of the orbit, the
// trapping-box proof of "never sticks", and adaptive bisection of a parameter interval.
#include "bouncer/verify/sticking.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <deque>
#include <functional>
#include <sstream>
#include <type_traits>

#include "bouncer/base/cancel.hpp"
#include "bouncer/model/impact_map.hpp"
#include "bouncer/scalar/scalar_set.hpp"

namespace bouncer {

const char* name(StickingOutcome o) {
  switch (o) {
    case StickingOutcome::sticks: return "sticks";
    case StickingOutcome::never_sticks: return "never_sticks";
    case StickingOutcome::no_sticking_within_max_steps: return "no_sticking_within_max_steps";
    case StickingOutcome::undecided: return "undecided";
  }
  return "?";
}

namespace {

struct RunResult {
  StickingOutcome outcome = StickingOutcome::no_sticking_within_max_steps;
  std::optional<long long> period;
  long long steps = 0;
  long long fallbacks = 0;
  std::optional<AttractorProof> attractor;
  std::string release_theta, release_v;  // sticks: the exact release state, when thin
};

// Coordinates u = E^-1 (x - z) of a candidate trapping set K = z + E [-rho, rho]^2, in the
// interval type S of the run (Mpfi or DoubleInterval) with points P (Mpfr or double).
template <class S>
struct Frame {
  using P = PointOfT<S>;
  P z[2];
  P E[2][2];
  S Einv[2][2];
};

template <class S>
S thin(const PointOfT<S>& x) { return S(x, x); }

// A point of P from a double (exact: P has at least 53 bits).
template <class P>
P point_from(double x, long bits) {
  if constexpr (std::is_same_v<P, Mpfr>) {
    Mpfr r(bits);
    mpfr_set_d(r.get(), x, MPFR_RNDN);
    return r;
  } else {
    return x;
  }
}

template <class P>
std::string point_text(const P& x) {
  if constexpr (std::is_same_v<P, Mpfr>) return ScalarTraits<Mpfr>::to_string(x);
  else return ScalarTraits<double>::to_string(x);
}

// E = the eigenvectors of J (when real and distinct), else the identity.
template <class S>
Frame<S> make_frame(const PointOfT<S> z[2], const double J[2][2], bool eigen, long bits) {
  Frame<S> f;
  f.z[0] = z[0];
  f.z[1] = z[1];
  double e[2][2] = {{1, 0}, {0, 1}};
  if (eigen) {
    const double tr = J[0][0] + J[1][1], det = J[0][0] * J[1][1] - J[0][1] * J[1][0];
    const double disc = tr * tr - 4 * det;
    if (disc > 0 && std::isfinite(disc)) {
      const double root = std::sqrt(disc);
      const double lam[2] = {tr >= 0 ? (tr + root) / 2 : (tr - root) / 2, 0};
      const double lam1 = lam[0] != 0 ? det / lam[0] : (tr - root) / 2;
      for (int k = 0; k < 2; ++k) {
        const double l = k == 0 ? lam[0] : lam1;
        double x, y;
        if (std::fabs(J[0][1]) > std::fabs(J[1][0])) { x = J[0][1]; y = l - J[0][0]; }
        else { x = l - J[1][1]; y = J[1][0]; }
        const double n = std::hypot(x, y);
        if (!(n > 0)) { x = k == 0; y = k == 1; }
        else { x /= n; y /= n; }
        e[0][k] = x;
        e[1][k] = y;
      }
      if (!(std::fabs(e[0][0] * e[1][1] - e[0][1] * e[1][0]) > 1e-9)) e[0][0] = e[1][1] = 1, e[0][1] = e[1][0] = 0;
    }
  }
  for (int i = 0; i < 2; ++i)
    for (int k = 0; k < 2; ++k) f.E[i][k] = point_from<PointOfT<S>>(e[i][k], bits);
  const S det = thin<S>(f.E[0][0]) * thin<S>(f.E[1][1]) - thin<S>(f.E[0][1]) * thin<S>(f.E[1][0]);
  f.Einv[0][0] = thin<S>(f.E[1][1]) / det;
  f.Einv[0][1] = -thin<S>(f.E[0][1]) / det;
  f.Einv[1][0] = -thin<S>(f.E[1][0]) / det;
  f.Einv[1][1] = thin<S>(f.E[0][0]) / det;
  return f;
}

// Is the set c + B r inside K = z + E [-rho, rho]^2? (interval arithmetic, rigorous)
template <class S>
bool inside(const Frame<S>& f, const ParallelogramOf<S>& s, const S& rho) {
  for (int i = 0; i < 2; ++i) {
    S u = f.Einv[i][0] * (thin<S>(s.c[0]) - thin<S>(f.z[0])) + f.Einv[i][1] * (thin<S>(s.c[1]) - thin<S>(f.z[1]));
    for (int k = 0; k < 2; ++k) u += (f.Einv[i][0] * thin<S>(s.B[0][k]) + f.Einv[i][1] * thin<S>(s.B[1][k])) * s.r[k];
    if (!ScalarTraits<S>::is_finite(u) || !rho.contains(u)) return false;
  }
  return true;
}

// Try to prove that the orbit, whose enclosure after `steps` steps is `now`, never sticks:
// find the period p of the attractor from the recent box centers, then a parallelogram
// K = z + E [-rho, rho]^2 around `now` (E: eigenvectors of DF^p, which makes K map into
// itself even where DF^p is far from normal; the axes as a fallback) with F^(m p)(K)
// inside K for some m <= 8, every step of the way certainly not sticking.
template <class S>
std::optional<AttractorProof> prove_trapped(const Model<S>& m, const ParallelogramOf<S>& now, const State<S>& box,
                                            const std::deque<std::pair<double, double>>& recent, long long steps,
                                            long bits) {
  if (recent.size() < 2) return std::nullopt;
  const auto& last = recent.back();
  long p = 0;
  double dp = 0;
  for (size_t k = 1; k < recent.size(); ++k) {
    const auto& x = recent[recent.size() - 1 - k];
    const double d = std::fabs(x.first - last.first) + std::fabs(x.second - last.second);
    if (d < 1e-6) {
      p = static_cast<long>(k);
      dp = d;
      break;
    }
  }
  if (p == 0) return std::nullopt;
  using P = PointOfT<S>;
  const P z[2] = {box.theta.mid(), box.v.mid()};
  double J[2][2];
  const bool have_j = jacobian_of_iterate(m, State<S>{thin<S>(z[0]), thin<S>(z[1])}, p, J);
  const double base = std::max({dp, box_width(box), std::ldexp(1.0, -static_cast<int>(bits) + 16)});
  for (bool eigen : {true, false}) {
    if (eigen && !have_j) continue;
    const Frame<S> f = make_frame<S>(z, J, eigen, bits);
    for (double factor : {16.0, 256.0, 4096.0, 65536.0, 1048576.0}) {
      const double rho = base * factor;
      if (rho > 1e-3) break;
      const P r = point_from<P>(rho, bits);
      const S pm(-r, r);
      if (!inside(f, now, pm)) continue;
      ParallelogramOf<S> K;
      for (int i = 0; i < 2; ++i) {
        K.c[i] = z[i];
        K.r[i] = pm;
        for (int k = 0; k < 2; ++k) K.B[i][k] = f.E[i][k];
      }
      OrbitEnclosureOf<S> trap(m, K);
      try {
        for (long i = 1; i <= 8 * p; ++i) {
          const EnclosedStepOf<S> s = trap.step();
          if (s.event.kind == EventKind::sticking) break;
          if (i % p == 0 && inside(f, trap.set(), pm)) {
            AttractorProof proof;
            proof.period = p;
            proof.iterate = i;
            proof.entered_at = steps;
            std::ostringstream t;
            t << "z + E [-rho, rho]^2 with z = (" << point_text(z[0]) << ", " << point_text(z[1])
              << "), rho = " << point_text(r) << ", E = [[" << point_text(f.E[0][0]) << ", " << point_text(f.E[0][1])
              << "], [" << point_text(f.E[1][0]) << ", " << point_text(f.E[1][1]) << "]] ("
              << (eigen ? "eigenvectors of DF^p" : "axes") << "), inside the box "
              << ScalarTraits<S>::to_string(trap.box().theta) << " x " << ScalarTraits<S>::to_string(trap.box().v);
            proof.box = t.str();
            return proof;
          }
        }
      } catch (const Undecided&) {
      }
    }
  }
  return std::nullopt;
}

template <class S>
RunResult run_once(const StickingQuestion& q, long bits, Progress& progress) {
  const Model<S> m = interval_model_of<S>(q.model, bits, q.a_range);
  OrbitEnclosureOf<S> orbit(m, q.from_release ? release_state(m) : make_state<S>(q.start, bits), q.method);
  const size_t keep = q.prove_attractor ? static_cast<size_t>(q.max_attractor_period) + 1 : 0;
  std::deque<std::pair<double, double>> recent;
  RunResult r;
  for (long long n = 1; n <= q.max_steps; ++n) {
    throw_if_cancelled(n);
    const EnclosedStepOf<S> s = orbit.step();  // throws Undecided
    progress.steps = n;
    if (s.event.kind == EventKind::sticking) {
      r.outcome = StickingOutcome::sticks;
      r.period = n;
      r.steps = n;
      r.fallbacks = orbit.fallbacks();
      using Tr = ScalarTraits<S>;
      const State<S>& rel = s.event.next;  // the release: a wall corner, exact when thin
      if (Tr::lower_string(rel.theta) == Tr::upper_string(rel.theta) && Tr::lower_string(rel.v) == Tr::upper_string(rel.v)) {
        r.release_theta = Tr::lower_string(rel.theta);
        r.release_v = Tr::lower_string(rel.v);
      }
      return r;
    }
    if (keep) {
      recent.emplace_back(ScalarTraits<S>::to_double(s.next.theta), ScalarTraits<S>::to_double(s.next.v));
      if (recent.size() > keep) recent.pop_front();
    }
  }
  r.steps = q.max_steps;
  r.fallbacks = orbit.fallbacks();
  if (q.prove_attractor) {
    r.attractor = prove_trapped(m, orbit.set(), orbit.box(), recent, q.max_steps, bits);
    if (r.attractor) r.outcome = StickingOutcome::never_sticks;
  }
  return r;
}

}  // namespace

std::string why_no_certified_answers(const ModelSpec& model) {
  if (model.law == Law::elastic)
    return "the elastic map preserves area, so no set maps strictly into itself and no attractor can be certified "
           "by a trapping set";
  if (model.law == Law::veldep && model.veldep_collapse) return "velocity-dependent collapse has no certified test";
  return "";
}

namespace {

StickingCertificate certify_run(const StickingQuestion& q) {
  auto e = escalate<RunResult>(q.schedule, [&](const Tier& t, Progress& p) {
    return t.double_interval ? run_once<DoubleInterval>(q, t.bits, p) : run_once<Mpfi>(q, t.bits, p);
  });
  StickingCertificate c;
  c.attempts = e.attempts;
  c.seconds = e.seconds;
  if (e.result) {
    const RunResult& r = *e.result;
    c.outcome = r.outcome;
    c.certified = true;
    c.period = r.period;
    c.bits = e.bits;
    c.scalar = e.scalar;
    c.steps_checked = r.outcome == StickingOutcome::sticks ? *r.period - 1 : r.steps;
    c.fallbacks = r.fallbacks;
    c.attractor = r.attractor;
    c.release_theta = r.release_theta;
    c.release_v = r.release_v;
  } else {
    c.outcome = StickingOutcome::undecided;
    c.certified = false;
    c.bits = e.best_bits;
    c.steps_checked = e.best_steps;
    c.reason = e.gave_up;
  }
  return c;
}

}  // namespace

std::string start_text(const StickingQuestion& q) {
  if (q.from_release) return "the release state (theta_r, 2 pi cos(2 pi theta_r)), theta_r = asin(a/(4 pi^2))/(2 pi)";
  return "(theta, v) = (" + q.start.theta.text() + ", " + q.start.v.text() + ")";
}

StickingCertificate certify_sticking(const StickingQuestion& q) {
  if (q.from_release && q.model.wall.shape != WallShape::sine)
    throw InputError("wall", "a start at the release state is for smooth walls (a piecewise wall's release is an exact knot: give it as theta, v)");
  if (const std::string why = why_no_certified_answers(q.model); !why.empty())
    throw InputError("model", "certified long-run answers need --model constant, or --model veldep without "
                              "--veldep-collapse: " + why);
  return certify_run(q);
}

StickingCertificate certify_orbit_steps(const StickingQuestion& q) {
  if (q.model.law == Law::veldep && q.model.veldep_collapse)
    throw InputError("model", "a certified orbit needs --veldep-collapse off: velocity-dependent collapse has no certified test");
  StickingQuestion plain = q;
  plain.prove_attractor = false;
  return certify_run(plain);
}

template <class T>
PlainSticking plain_sticking_period(const ModelSpec& model, const InitialCondition& start, long bits,
                                    long long max_steps, bool from_release) {
  PlainSticking out;
  const Model<T> m = make_model<T>(model, bits);
  const ImpactMap<T> map(m);
  State<T> s = from_release ? release_state(m) : make_state<T>(start, bits);
  for (long long n = 1; n <= max_steps; ++n) {
    throw_if_cancelled(n);
    try {
      StepResult<T> r = map.step(s);
      out.steps_run = n;
      if (r.kind == EventKind::sticking) {
        out.period = n;
        return out;
      }
      s = std::move(r.next);
    } catch (const Undecided&) {
      out.failed = true;
      return out;
    }
  }
  return out;
}

#define BOUNCER_X(T, kind) \
  template PlainSticking plain_sticking_period<T>(const ModelSpec&, const InitialCondition&, long, long long, bool);
BOUNCER_FOR_EACH_POINT_SCALAR(BOUNCER_X)
#undef BOUNCER_X

std::string describe(const StickingCertificate& c, long long max_steps) {
  std::ostringstream s;
  switch (c.outcome) {
    case StickingOutcome::sticks:
      s << "sticks: the first sticking is at step " << *c.period << " (sticking period " << *c.period << ")";
      break;
    case StickingOutcome::never_sticks:
      s << "never sticks: after step " << c.attractor->entered_at << " the orbit is in a set K with F^"
        << c.attractor->iterate << "(K) inside K (attractor of period " << c.attractor->period
        << "), and no step from K sticks";
      break;
    case StickingOutcome::no_sticking_within_max_steps:
      s << "no sticking within " << max_steps << " steps";
      break;
    case StickingOutcome::undecided:
      s << "undecided: no sticking in steps 1.." << c.steps_checked << " (certified); " << c.reason;
      break;
  }
  return s.str();
}

namespace {

std::string piece_key(const StickingCertificate& c) {
  switch (c.outcome) {
    case StickingOutcome::sticks: return std::to_string(*c.period);
    case StickingOutcome::never_sticks: return "never";
    case StickingOutcome::no_sticking_within_max_steps: return "none";
    case StickingOutcome::undecided: return "undecided";
  }
  return "?";
}

}  // namespace

RangeReport certify_sticking_range(const StickingQuestion& q, const RangeOptions& opt) {
  if (!q.a_range) throw InputError("a-range", "is required");
  const auto t0 = std::chrono::steady_clock::now();
  RangeReport rep;
  rep.lo = q.a_range->first;
  rep.hi = q.a_range->second;
  int runs = 0;
  std::function<void(const mpq_class&, const mpq_class&, int)> rec = [&](const mpq_class& lo, const mpq_class& hi,
                                                                         int depth) {
    StickingQuestion sub = q;
    sub.a_range = std::make_pair(lo, hi);
    sub.schedule.stop_when_stalled = true;
    StickingCertificate c = certify_sticking(sub);
    ++runs;
    if (c.outcome == StickingOutcome::undecided && depth < opt.max_depth && runs + 2 <= opt.max_pieces) {
      const mpq_class mid = (lo + hi) / 2;
      rec(lo, mid, depth + 1);
      rec(mid, hi, depth + 1);
      return;
    }
    rep.pieces.push_back({lo, hi, std::move(c)});
  };
  rec(rep.lo, rep.hi, 0);
  rep.uncertified_length = 0;
  for (const RangePiece& p : rep.pieces)
    if (!p.cert.certified) rep.uncertified_length += p.hi - p.lo;

  // The theorem: adjacent pieces with the same answer merged.
  std::vector<std::pair<std::string, std::vector<std::pair<mpq_class, mpq_class>>>> groups;
  std::string prev;
  for (const RangePiece& p : rep.pieces) {
    const std::string key = piece_key(p.cert);
    auto it = std::find_if(groups.begin(), groups.end(), [&](const auto& g) { return g.first == key; });
    if (it == groups.end()) {
      groups.push_back({key, {}});
      it = groups.end() - 1;
    }
    if (key == prev && !it->second.empty() && it->second.back().second == p.lo) it->second.back().second = p.hi;
    else it->second.emplace_back(p.lo, p.hi);
    prev = key;
  }
  std::ostringstream t;
  t << "For every a in [" << exact_decimal(rep.lo) << ", " << exact_decimal(rep.hi)
    << "] except a set of total length L = " << exact_decimal(rep.uncertified_length)
    << ", the sticking period of the orbit from " << start_text(q)
    << " (eps = " << q.model.eps.text() << ", " << q.model.wall.text << " wall, " << name(q.model.downward)
    << " downward-sticking convention) is:";
  bool first = true;
  for (const auto& [key, ivs] : groups) {
    if (key == "undecided") continue;
    t << (first ? " " : "; ");
    first = false;
    if (key == "never") t << "infinite (the orbit never sticks: trapped near a periodic attractor)";
    else if (key == "none") t << "greater than " << q.max_steps << " (no sticking within " << q.max_steps << " steps)";
    else t << key;
    t << " for a in ";
    for (size_t i = 0; i < ivs.size(); ++i)
      t << (i ? " u " : "") << "[" << exact_decimal(ivs[i].first) << ", " << exact_decimal(ivs[i].second) << "]";
  }
  if (first) t << " (nothing certified)";
  t << ".";
  for (const auto& [key, ivs] : groups) {
    if (key != "undecided") continue;
    t << " The exceptional set is ";
    for (size_t i = 0; i < ivs.size(); ++i)
      t << (i ? " u " : "") << "[" << exact_decimal(ivs[i].first) << ", " << exact_decimal(ivs[i].second) << "]";
    t << " (undecided at the precisions allowed).";
  }
  rep.theorem = t.str();
  rep.seconds = detail::seconds_since(t0);
  return rep;
}

bool plain_agrees(const StickingCertificate& c, const PlainSticking& d) {
  switch (c.outcome) {
    case StickingOutcome::sticks: return d.period && *d.period == *c.period;
    case StickingOutcome::never_sticks:
    case StickingOutcome::no_sticking_within_max_steps: return !d.period && !d.failed;
    case StickingOutcome::undecided: return !d.period || *d.period > c.steps_checked;
  }
  return false;
}

std::vector<PlainSticking> double_sticking_at_midpoints(const StickingQuestion& q, const RangeReport& rep) {
  std::vector<PlainSticking> runs;
  for (const RangePiece& piece : rep.pieces) {
    ModelSpec at = q.model;
    at.a = *Decimal::parse(exact_decimal((piece.lo + piece.hi) / 2));
    runs.push_back(plain_sticking_period<double>(at, q.start, 53, q.max_steps, q.from_release));
  }
  return runs;
}

}  // namespace bouncer
