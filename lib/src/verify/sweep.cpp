// Precision sweep against a certified reference (verify/sweep.hpp).
#include "bouncer/verify/sweep.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <deque>
#include <iomanip>
#include <sstream>

#include "bouncer/base/cancel.hpp"
#include "bouncer/model/impact_map.hpp"

namespace bouncer {

// Every point type of the scalar set: the fixed ones at their precision, the others at
// 64, 128, ..., 4096 bits.
std::vector<Precision> default_sweep_precisions() {
  std::vector<Precision> p;
  for_each_scalar<PointScalars>([&](auto tag) {
    using T = typename decltype(tag)::type;
    constexpr long fixed = ScalarTraits<T>::fixed_bits;
    if (fixed) p.push_back({precision_kind<T>(), fixed});
    else for (long b = 64; b <= 4096; b *= 2) p.push_back({precision_kind<T>(), b});
  });
  return p;
}

namespace {

// One certified step, kept as outward-rounded double bounds (memory: 33 bytes a step).
struct RefStep {
  double th_lo, th_hi, v_lo, v_hi;
  EventKind kind;
};

struct Reference {
  std::vector<RefStep> steps;
  long bits = 0;
};

RefStep ref_step(const EnclosedStep& s) {
  return {mpfr_get_d(&s.next.theta.get()->left, MPFR_RNDD), mpfr_get_d(&s.next.theta.get()->right, MPFR_RNDU),
          mpfr_get_d(&s.next.v.get()->left, MPFR_RNDD), mpfr_get_d(&s.next.v.get()->right, MPFR_RNDU), s.event.kind};
}

double outside(double x, double lo, double hi) { return std::max({0.0, lo - x, x - hi}); }
// Distance of a phase from [lo, hi] on the circle R/Z.
double phase_outside(double x, double lo, double hi) {
  return std::min({outside(x, lo, hi), outside(x + 1, lo, hi), outside(x - 1, lo, hi)});
}

std::optional<long> final_period(const std::deque<std::pair<double, double>>& tail) {
  if (tail.size() < 2) return std::nullopt;
  const auto& last = tail.back();
  for (size_t k = 1; k < tail.size(); ++k) {
    const auto& x = tail[tail.size() - 1 - k];
    const double scale = 1 + std::fabs(last.second);
    if (std::fabs(x.first - last.first) + std::fabs(x.second - last.second) < 1e-8 * scale)
      return static_cast<long>(k);
  }
  return std::nullopt;
}

std::string plain_answer(const SweepRow& r, const SweepQuestion& q, bool failed, long long failed_at) {
  const long long steps = q.steps;
  std::ostringstream s;
  if (r.sticking_period) s << "sticks at step " << *r.sticking_period << " (sticking period " << *r.sticking_period << ")";
  else if (failed) s << "step " << failed_at << " failed (NaN or overflow)";
  else if (r.attractor_period) s << "no sticking within " << steps << " steps; settles on a period-" << *r.attractor_period << " orbit";
  else s << "no sticking within " << steps << " steps; no period <= " << q.max_period << " in the final steps";
  if (const auto& c = r.classification) {
    s << "; over " << q.classify_steps << " more steps: " << name(c->cls);
    if (c->cls == OrbitClass::undecided) s << " (" << c->evidence << ")";
    else if (std::isfinite(c->lambda)) s << " (lambda " << std::setprecision(3) << c->lambda << " per collision)";
  }
  return s.str();
}

template <class T>
SweepRow run_plain(const SweepQuestion& q, const Precision& p, const Reference& ref) {
  using Tr = ScalarTraits<T>;
  SweepRow row;
  row.precision = p.text();
  row.bits = p.bits;
  const ImpactMap<T> map(make_model<T>(q.model, p.bits));
  State<T> s = make_state<T>(q.start, p.bits);
  std::deque<std::pair<double, double>> tail;
  const size_t keep = static_cast<size_t>(q.max_period) + 1;
  bool failed = false;
  long long failed_at = 0;
  for (long long n = 1; n <= q.steps; ++n) {
    throw_if_cancelled(n);
    StepResult<T> r;
    try {
      r = map.step(s);
    } catch (const Undecided& u) {
      failed = true;
      failed_at = n;
      if (!row.leaves_at && n <= static_cast<long long>(ref.steps.size())) {
        row.leaves_at = n;
        row.why = std::string("the step failed: ") + u.what();
      }
      break;
    }
    s = std::move(r.next);
    if (r.kind == EventKind::sticking && !row.sticking_period) row.sticking_period = n;
    if (!row.leaves_at && n <= static_cast<long long>(ref.steps.size())) {
      const RefStep& e = ref.steps[n - 1];
      if (r.kind != e.kind) {
        row.leaves_at = n;
        row.why = std::string("event ") + name(r.kind) + " where the certified event is " + name(e.kind);
      } else {
        const double dt = phase_outside(Tr::to_double(s.theta), e.th_lo, e.th_hi);
        const double dv = outside(Tr::to_double(s.v), e.v_lo, e.v_hi);
        if (std::max(dt, dv) > q.tolerance) {
          row.leaves_at = n;
          std::ostringstream w;
          w << (dt >= dv ? "theta" : "v") << " is " << std::max(dt, dv) << " outside the enclosure";
          row.why = w.str();
        }
      }
    }
    tail.emplace_back(Tr::to_double(s.theta), Tr::to_double(s.v));
    if (tail.size() > keep) tail.pop_front();
  }
  if (!row.sticking_period && !failed) row.attractor_period = final_period(tail);
  if (!row.sticking_period && !failed && !row.attractor_period) {
    // What kind of orbit this precision sees: the attractor classification, continued
    // from the final state (the periods up to max_period are already excluded).
    ClassifyOptions co;
    co.transient = 0;
    co.steps = q.classify_steps;
    co.max_period = std::min(co.max_period, q.classify_steps / 2);
    row.classification = classify(map, s, co);
  }
  row.answer = plain_answer(row, q, failed, failed_at);
  return row;
}

}  // namespace

SweepReport precision_sweep(const SweepQuestion& q) {
  const auto t0 = std::chrono::steady_clock::now();
  SweepReport rep;
  // The reference, escalated until it covers all steps; the best run is kept otherwise.
  Reference best;
  auto e = escalate<Reference>(q.reference, [&](long bits, Progress& p) {
    Reference ref;
    ref.bits = bits;
    ref.steps.reserve(static_cast<size_t>(std::min<long long>(q.steps, 1 << 20)));
    OrbitEnclosure orbit(interval_model(q.model, bits), make_state<Mpfi>(q.start, bits), q.method);
    try {
      for (long long n = 1; n <= q.steps; ++n) {
        throw_if_cancelled(n);
        ref.steps.push_back(ref_step(orbit.step()));
        p.steps = n;
      }
    } catch (const Undecided&) {
      if (ref.steps.size() > best.steps.size() || best.bits == 0) best = std::move(ref);
      throw;
    }
    return ref;
  });
  const Reference& ref = e.result ? *e.result : best;
  rep.reference_bits = ref.bits;
  rep.reference_steps = static_cast<long long>(ref.steps.size());
  rep.reference_attempts = e.attempts;
  rep.reference_status = e.result ? "covers all " + std::to_string(q.steps) + " steps"
                                  : "covers steps 1.." + std::to_string(ref.steps.size()) + "; " + e.gave_up;
  {
    std::ostringstream a;
    long long stick = 0;
    for (size_t i = 0; i < ref.steps.size() && !stick; ++i)
      if (ref.steps[i].kind == EventKind::sticking) stick = static_cast<long long>(i) + 1;
    if (stick) a << "sticks at step " << stick << " (sticking period " << stick << "), certified";
    else a << "no sticking within " << ref.steps.size() << " steps, certified";
    rep.reference_answer = a.str();
  }

  const std::vector<Precision> precisions = q.precisions.empty() ? default_sweep_precisions() : q.precisions;
  for (const Precision& p : precisions) {
    if (p.is_interval()) continue;
    rep.rows.push_back(with_scalar(p, [&](auto tag) {
      using T = typename decltype(tag)::type;
      if constexpr (ScalarTraits<T>::is_interval) return SweepRow{};
      else return run_plain<T>(q, p, ref);
    }));
  }

  // Least-squares slope of leaves_at against bits.
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  int n = 0;
  long first_bits = -1;
  bool distinct = false;
  for (const SweepRow& r : rep.rows) {
    if (!r.leaves_at) continue;
    const double x = static_cast<double>(r.bits), y = static_cast<double>(*r.leaves_at);
    sx += x; sy += y; sxx += x * x; sxy += x * y; ++n;
    if (first_bits < 0) first_bits = r.bits;
    else if (r.bits != first_bits) distinct = true;
  }
  if (n >= 2 && distinct) {
    const double slope = (n * sxy - sx * sy) / (n * sxx - sx * sx);
    rep.slope = slope;
    if (slope > 0) rep.implied_lyapunov = std::log(2.0) / slope;
  }
  rep.seconds = detail::seconds_since(t0);
  return rep;
}

}  // namespace bouncer
