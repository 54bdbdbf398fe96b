// Each periodic chain of an attractors sweep handed to `continue` (run/attractors_sweep.hpp
// continue_chains): the branch, its certified ends, and which of its events explains each
// appearance and disappearance of the chain.
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <exception>
#include <limits>
#include <thread>

#include "bouncer/run/workers.hpp"
#include "bouncer/analysis/continuation.hpp"
#include "bouncer/run/attractors_sweep.hpp"
#include "bouncer/verify/border_collision.hpp"

namespace bouncer {

namespace {

template <class T>
std::string text_of(const T& x) {
  return ScalarTraits<T>::to_string(x);
}

// The chain's orbit at a value, as the run's scalar: its points read back from their digits.
template <class T>
std::vector<State<T>> orbit_of(const FoundAttractor& a, long bits) {
  using Tr = ScalarTraits<T>;
  std::vector<State<T>> s;
  for (const AttractorPoint& p : a.points) s.push_back({Tr::from_decimal(p.theta.digits, bits), Tr::from_decimal(p.v.digits, bits)});
  return s;
}

// The Hausdorff distance of two point sets, in the metric of attractor_distance.
template <class T>
double orbit_distance(const std::vector<State<T>>& x, const FoundAttractor& y) {
  FoundAttractor a;
  for (const State<T>& p : x)
    a.points.push_back({number_of(p.theta), number_of(p.v)});
  return attractor_distance(a, y);
}

template <class T>
BranchEventInfo end_info(const BranchEnd<T>& e, bool high) {
  BranchEventInfo i;
  i.end = true;
  i.high = high;
  i.kind = name(e.reason);
  i.param = ScalarTraits<T>::to_double(e.param);
  i.param_text = text_of(e.param);
  i.bracket_lo = text_of(e.bracket_lo);
  i.bracket_hi = text_of(e.bracket_hi);
  i.detail = e.detail;
  return i;
}

void take_certificate(BranchEventInfo& i, const std::optional<CertifiedBranchEnd>& c) {
  if (!c) return;
  i.tried = true;
  i.certified = c->two_sided.certified;
  if (i.certified)
    i.enclosure = c->two_sided.parameter;
  else
    i.reason = c->two_sided.reason.empty() ? c->two_sided.statement : c->two_sided.reason;
}

template <class T>
ContinuedBranch continue_one(const AttractorsSweepResult& r, const Model<T>& m, size_t at_value, const FoundAttractor& a, Branch<T>& b) {
  using Tr = ScalarTraits<T>;
  const AttractorsSweepRequest& s = r.request;
  const long bits = s.point.precision.bits;
  ContinuedBranch cb;
  cb.kind = a.kind;
  cb.period = a.period;
  cb.from_value = at_value;
  const T lo = Tr::from_decimal(s.lo.text(), bits), hi = Tr::from_decimal(s.hi.text(), bits);
  ContinuationOptions opt;
  opt.classify_beyond = false;  // what lies beyond is the sweep's to say
  b = continue_branch(m, s.vary, a.period, orbit_of<T>(a, bits).front(), lo, hi, opt);
  cb.started = b.started;
  cb.note = b.note;
  cb.corrector_runs = b.corrector_runs;
  if (!b.started) return cb;
  cb.low_param = text_of(b.points.front().param);
  cb.high_param = text_of(b.points.back().param);
  cb.low = Tr::to_double(b.points.front().param);
  cb.high = Tr::to_double(b.points.back().param);
  cb.events_text = event_text(b.points[b.start].events);
  cb.events.push_back(end_info(b.low, false));
  for (const Bifurcation<T>& f : b.bifurcations) {
    BranchEventInfo i;
    i.kind = name(f.kind);
    i.param = Tr::to_double(f.param);
    i.param_text = text_of(f.param);
    i.bracket_lo = text_of(f.bracket_lo);
    i.bracket_hi = text_of(f.bracket_hi);
    cb.events.push_back(i);
  }
  cb.events.push_back(end_info(b.high, true));
  return cb;
}

// Krawczyk on every event of a branch, tied to a chain's transition or not (a branch ends
// where it ends whether or not a basin at the sampled values shows it: the period 3 goes on
// to a* = 25.40222, where its basin is below one start in 1024): border ends
// (certify_branch_ends, both sides of a*), period doublings (certify_period_doubling) and
// folds, ends or on the branch (certify_fold). Range ends and unexplained ends have no proof.
template <class T>
void certify_events(const AttractorsSweepRequest& s, const Branch<T>& b, ContinuedBranch& cb) {
  const long bits = s.point.precision.bits;
  if (!b.started) return;
  const CertifiedBranchEnds c = certify_branch_ends(s.point.model, s.vary, cb.period, b, bits, /*one_sided=*/false);
  take_certificate(cb.events.front(), c.low);
  take_certificate(cb.events.back(), c.high);
  for (size_t e = 0; e < cb.events.size(); ++e) {
    BranchEventInfo& i = cb.events[e];
    std::optional<PeriodDoublingCertificate> smooth;
    if (i.end) {
      smooth = certify_smooth_end(s.point.model, s.vary, cb.period, b, i.high ? b.high : b.low, bits);
    } else if (i.kind == name(SmoothKind::period_doubling) || i.kind == name(SmoothKind::fold)) {
      const PeriodDoublingQuestion q = smooth_event_question(s.point.model, s.vary, cb.period, b, i.param, i.bracket_lo, i.bracket_hi, bits);
      smooth = i.kind == name(SmoothKind::fold) ? certify_fold(q) : certify_period_doubling(q);
    }
    if (!smooth) continue;
    const PeriodDoublingCertificate& c = *smooth;
    i.tried = true;
    i.certified = c.certified;
    if (c.certified)
      i.enclosure = c.parameter;
    else
      i.reason = c.reason.empty() ? c.statement : c.reason;
  }
}

// Is the chain's attractor `a` at parameter value p on branch b? Newton at p from the
// branch's orbit nearest in the parameter converges onto a's orbit.
template <class T>
bool on_branch(const Model<T>& m_at_p, double p, const Branch<T>& b, const FoundAttractor& a) {
  using Tr = ScalarTraits<T>;
  if (!b.started || b.period != a.period || b.points.empty()) return false;
  if (p < Tr::to_double(b.points.front().param) || p > Tr::to_double(b.points.back().param)) return false;
  const BranchPoint<T>* near = &b.points.front();
  for (const BranchPoint<T>& x : b.points)
    if (std::fabs(Tr::to_double(x.param) - p) < std::fabs(Tr::to_double(near->param) - p)) near = &x;
  // Every point of the nearest orbit as a guess: the orbit may have moved, not its order.
  for (const State<T>& guess : near->orbit.points) {
    const PeriodicOrbit<T> o = find_periodic(m_at_p, a.period, guess, NewtonOptions{30, 1e-9, 8});
    if (o.converged && o.minimal_period == a.period && orbit_distance(o.points, a) < 1e-6) return true;
  }
  return false;
}

template <class T>
ChainBranches continue_typed(const AttractorsSweepResult& r, bool certify, int threads) {
  const auto t0 = std::chrono::steady_clock::now();
  const AttractorsSweepRequest& s = r.request;
  const long bits = s.point.precision.bits;
  ChainBranches out;
  out.chain_branch.assign(r.chains.size(), -1);
  out.transitions.resize(r.chains.size());
  std::vector<Branch<T>> branches;
  for (size_t c = 0; c < r.chains.size(); ++c) {
    const AttractorChain& ch = r.chains[c];
    // Appearances and disappearances inside the range.
    for (size_t k = 0; k + 1 < ch.index.size(); ++k) {
      const bool now = ch.index[k] >= 0, next = ch.index[k + 1] >= 0;
      if (now != next) out.transitions[c].push_back({!now, k, k + 1, -1, -1});
    }
    if (ch.kind != AttractorKind::periodic && ch.kind != AttractorKind::sticking) continue;
    if (ch.period > kMaxBranchPeriod) continue;  // as `continue --period`
    // Started at the value of the chain's largest share.
    size_t best = 0;
    double share = -1;
    for (size_t k = 0; k < ch.index.size(); ++k)
      if (ch.index[k] >= 0 && r.at[k].attractors[static_cast<size_t>(ch.index[k])].fraction > share) {
        share = r.at[k].attractors[static_cast<size_t>(ch.index[k])].fraction;
        best = k;
      }
    const FoundAttractor& a = r.at[best].attractors[static_cast<size_t>(ch.index[best])];
    if (a.points.empty()) continue;
    const Model<T> m = make_model<T>(with_parameter(s.point.model, s.vary, r.values[best]), bits);
    int found = -1;
    for (size_t b = 0; b < branches.size() && found < 0; ++b)
      if (out.branches[b].kind == ch.kind && on_branch(m, r.values[best].approx(), branches[b], a)) found = static_cast<int>(b);
    if (found < 0) {
      branches.emplace_back();
      out.branches.push_back(continue_one(r, m, best, a, branches.back()));
      found = static_cast<int>(branches.size() - 1);
    }
    out.chain_branch[c] = found;
    out.branches[static_cast<size_t>(found)].chains.push_back(static_cast<int>(c));
  }
  // Tie each transition to the branch event between its two values: an end on the side
  // where the chain is absent (a high end for a disappearance, a low end for an appearance),
  // or a bifurcation (the orbit's stability changes there). Ends first, then the nearest.
  for (size_t c = 0; c < r.chains.size(); ++c) {
    const int b = out.chain_branch[c];
    if (b < 0) continue;
    const ContinuedBranch& cb = out.branches[static_cast<size_t>(b)];
    for (ChainTransition& t : out.transitions[c]) {
      const double x = r.values[t.before].approx(), y = r.values[t.after].approx();
      int pick = -1;
      for (size_t e = 0; e < cb.events.size(); ++e) {
        const BranchEventInfo& ev = cb.events[e];
        // The continuation locates a* to about 2^-44 relative: an a* on a value itself
        // (a = 32 at a sweep value 32) may fall just outside; 1e-9 relative is far below any
        // spacing of values and far above that error.
        const double tol = 1e-9 * std::max(1.0, std::fabs(ev.param));
        if (!(ev.param >= x - tol && ev.param <= y + tol)) continue;
        if (ev.end && (ev.kind == "range_end" || ev.kind == "max_points")) continue;
        if (ev.end && ev.high == t.appears) continue;  // the branch exists on the wrong side
        if (pick < 0 || (ev.end && !cb.events[static_cast<size_t>(pick)].end)) pick = static_cast<int>(e);
      }
      if (pick >= 0) {
        t.branch = b;
        t.event = pick;
      }
    }
  }
  if (certify) {
    // The branches' proofs are independent: `threads` workers take them in turn (each writes
    // only its branch, so the result does not depend on the number of threads).
    std::atomic<size_t> next{0};
    std::atomic<bool> failed{false};
    std::exception_ptr error;
    auto work = [&] {
      for (size_t b; (b = next++) < out.branches.size() && !failed;) {
        try {
          certify_events(s, branches[b], out.branches[b]);
        } catch (...) {
          if (!failed.exchange(true)) error = std::current_exception();
        }
      }
    };
    run_workers(static_cast<unsigned>(std::min<size_t>(static_cast<size_t>(std::max(1, threads)), out.branches.size())), work);
    if (error) std::rethrow_exception(error);
  }
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return out;
}

}  // namespace

ChainBranches continue_chains(const AttractorsSweepResult& r, bool certify, int threads) {
  return with_point_scalar(r.request.point.precision,
                           [&](auto tag) { return continue_typed<typename decltype(tag)::type>(r, certify, threads); });
}

}  // namespace bouncer
