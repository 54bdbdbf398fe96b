// The attractors across a parameter range, matched value to value (run/attractors_sweep.hpp).
#include "bouncer/run/attractors_sweep.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "bouncer/base/error.hpp"
#include "bouncer/run/cells.hpp"

namespace bouncer {

namespace {

double point_distance(const AttractorPoint& p, const AttractorPoint& q) {
  double dt = std::fabs(p.theta.value - q.theta.value);
  dt -= std::floor(dt);
  dt = std::min(dt, 1 - dt);
  return std::max(dt, std::fabs(p.v.value - q.v.value) / std::max(1.0, std::fabs(p.v.value)));
}

// One directed half of the Hausdorff distance: the farthest point of x from y.
double farthest(const std::vector<AttractorPoint>& x, const std::vector<AttractorPoint>& y) {
  double worst = 0;
  for (const AttractorPoint& p : x) {
    double best = std::numeric_limits<double>::infinity();
    for (const AttractorPoint& q : y) best = std::min(best, point_distance(p, q));
    worst = std::max(worst, best);
  }
  return worst;
}

// lo + (hi - lo) k / (n - 1), rounded to 20 decimals (exact at the ends).
Decimal value_at(const Decimal& lo, const Decimal& hi, long k, long n) {
  if (k == 0) return lo;
  if (k == n - 1) return hi;
  const mpq_class x = lo.value() + (hi.value() - lo.value()) * k / (n - 1);
  const mpz_class scale("100000000000000000000");
  mpq_class scaled = x * scale + mpq_class(1, 2);
  mpz_class fl;
  mpz_fdiv_q(fl.get_mpz_t(), scaled.get_num_mpz_t(), scaled.get_den_mpz_t());
  return *Decimal::parse(exact_decimal(mpq_class(fl, scale)));
}

}  // namespace

double attractor_distance(const FoundAttractor& x, const FoundAttractor& y) {
  if (x.points.empty() || y.points.empty()) return std::numeric_limits<double>::infinity();
  return std::max(farthest(x.points, y.points), farthest(y.points, x.points));
}

void merge_split_chains(AttractorsSweepResult& r) {
  if (!r.branches) return;
  ChainBranches& cb = *r.branches;
  auto unexplained = [&](size_t c, bool appears, size_t before) {
    for (const ChainTransition& t : cb.transitions[c])
      if (t.appears == appears && t.before == before && t.event < 0) return true;
    return false;
  };
  auto spans = [&](const ContinuedBranch& b, size_t before, size_t after) {
    if (!b.started) return false;
    const double x = r.values[before].approx(), y = r.values[after].approx();
    for (const BranchEventInfo& e : b.events)
      if (!e.end && e.param >= x && e.param <= y) return false;  // a bifurcation in between
    return b.low <= x && y <= b.high;
  };
  for (bool merged = true; merged;) {
    merged = false;
    for (size_t x = 0; x < r.chains.size() && !merged; ++x) {
      const int b = cb.chain_branch[x];
      if (b < 0) continue;
      for (const ChainTransition& t : cb.transitions[x]) {
        if (t.appears || t.event >= 0 || !spans(cb.branches[static_cast<size_t>(b)], t.before, t.after)) continue;
        for (const int yi : cb.branches[static_cast<size_t>(b)].chains) {
          const size_t y = static_cast<size_t>(yi);
          if (y == x || r.chains[y].index[t.after] < 0 || !unexplained(y, true, t.before)) continue;
          bool overlap = false;
          for (size_t k = 0; k < r.chains[x].index.size(); ++k) overlap |= r.chains[x].index[k] >= 0 && r.chains[y].index[k] >= 0;
          if (overlap) continue;
          // y joins x.
          const size_t at = t.before;
          AttractorChain& cx = r.chains[x];
          for (size_t k = 0; k < cx.index.size(); ++k)
            if (r.chains[y].index[k] >= 0) cx.index[k] = r.chains[y].index[k];
          cx.joined.push_back(at);
          cx.joined.insert(cx.joined.end(), r.chains[y].joined.begin(), r.chains[y].joined.end());
          std::sort(cx.joined.begin(), cx.joined.end());
          std::vector<ChainTransition> ts;
          for (const ChainTransition& u : cb.transitions[x])
            if (!(!u.appears && u.before == at)) ts.push_back(u);
          for (const ChainTransition& u : cb.transitions[y])
            if (!(u.appears && u.before == at)) ts.push_back(u);
          std::sort(ts.begin(), ts.end(), [](const ChainTransition& p, const ChainTransition& q) { return p.before < q.before; });
          cb.transitions[x] = std::move(ts);
          // Remove y; renumber.
          r.chains.erase(r.chains.begin() + static_cast<std::ptrdiff_t>(y));
          cb.transitions.erase(cb.transitions.begin() + static_cast<std::ptrdiff_t>(y));
          cb.chain_branch.erase(cb.chain_branch.begin() + static_cast<std::ptrdiff_t>(y));
          for (ContinuedBranch& br : cb.branches) {
            std::vector<int> keep;
            for (const int c : br.chains)
              if (c != yi) keep.push_back(c > yi ? c - 1 : c);
            br.chains = std::move(keep);
          }
          merged = true;
          break;
        }
        if (merged) break;
      }
    }
  }
  for (size_t c = 0; c < r.chains.size(); ++c) r.chains[c].id = static_cast<int>(c);
}

AttractorsSweepResult sweep_attractors(const AttractorsSweepRequest& r, const GridOptions& run) {
  if (r.values < 2 || r.values > 10000)
    throw InputError("values", "must be an integer in [2, 10000] (got " + std::to_string(r.values) + ")");
  check_varied_range(r.point.model, r.vary, r.lo, r.hi);
  AttractorsSweepResult res;
  res.request = r;
  for (long k = 0; k < r.values; ++k) {
    res.values.push_back(value_at(r.lo, r.hi, k, r.values));
    AttractorsRequest q = r.point;
    q.model = with_parameter(r.point.model, r.vary, res.values.back());
    res.at.push_back(find_attractors(q, run));
    const std::vector<FoundAttractor>& now = res.at.back().attractors;
    // Match this value's attractors with the chains alive at the previous value: closest
    // pairs first (same kind and period, within match_distance); the rest start chains.
    struct Pair {
      double d;
      size_t chain, att;
    };
    std::vector<Pair> pairs;
    for (size_t c = 0; c < res.chains.size(); ++c) {
      if (k == 0 || res.chains[c].index[static_cast<size_t>(k - 1)] < 0) continue;
      const FoundAttractor& before = res.at[static_cast<size_t>(k - 1)].attractors[static_cast<size_t>(res.chains[c].index[static_cast<size_t>(k - 1)])];
      for (size_t a = 0; a < now.size(); ++a) {
        if (now[a].kind != before.kind || now[a].period != before.period) continue;
        const double d = attractor_distance(before, now[a]);
        if (d <= r.match_distance) pairs.push_back({d, c, a});
      }
    }
    std::stable_sort(pairs.begin(), pairs.end(), [](const Pair& x, const Pair& y) { return x.d < y.d; });
    for (AttractorChain& c : res.chains) c.index.push_back(-1);
    std::vector<bool> taken(now.size(), false);
    for (const Pair& p : pairs) {
      if (taken[p.att] || res.chains[p.chain].index[static_cast<size_t>(k)] >= 0) continue;
      taken[p.att] = true;
      res.chains[p.chain].index[static_cast<size_t>(k)] = static_cast<int>(p.att);
    }
    for (size_t a = 0; a < now.size(); ++a) {
      if (taken[a]) continue;
      AttractorChain c;
      c.id = static_cast<int>(res.chains.size());
      c.kind = now[a].kind;
      c.period = now[a].period;
      c.index.assign(static_cast<size_t>(k), -1);
      c.index.push_back(static_cast<int>(a));
      res.chains.push_back(std::move(c));
    }
  }
  if (r.continue_branches) {
    res.branches = continue_chains(res, r.certify_ends, static_cast<int>(worker_threads(run.threads)));
    merge_split_chains(res);
  }
  return res;
}

}  // namespace bouncer
