#include "bouncer/analysis/lyapunov.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "bouncer/analysis/jacobian.hpp"
#include "bouncer/base/cancel.hpp"

namespace bouncer {

double growth_exponent(const std::vector<std::pair<double, double>>& pts) {
  if (pts.size() < 2) return 0;
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  int n = 0;
  for (const auto& [x, y] : pts) {
    if (!(x > 0) || !(y > 0)) continue;
    const double lx = std::log(x), ly = std::log(y);
    sx += lx; sy += ly; sxx += lx * lx; sxy += lx * ly; ++n;
  }
  if (n < 2) return 0;
  const double den = n * sxx - sx * sx;
  return den > 0 ? (n * sxy - sx * sy) / den : 0;
}

namespace {

// Log-spaced samples (n, running max of v) and the growth verdict.
struct Growth {
  std::vector<std::pair<double, double>> samples;
  double next = 1;
  double runmax = 0;
  void add(long n, double v) {
    runmax = std::max(runmax, v);
    if (n >= next) {
      samples.emplace_back(static_cast<double>(n), runmax);
      while (next <= n) next = std::ceil(next * 1.25);
    }
  }
  // Fit over the last part of the run: [N/16, N].
  double alpha(long N) const {
    std::vector<std::pair<double, double>> tail;
    for (const auto& p : samples)
      if (p.first >= N / 16.0) tail.push_back(p);
    return growth_exponent(tail);
  }
  double max_at(double n) const {
    double m = 0;
    for (const auto& p : samples)
      if (p.first <= n) m = p.second;
    return m;
  }
  bool unbounded(long N) const {
    if (N < 64) return false;
    const double a = alpha(N);
    const double early = max_at(N / 16.0);
    return a > 0.2 && runmax > 1.5 * early;
  }
};

template <class S>
double log_of(const S& x) {
  using std::log;
  return ScalarTraits<S>::to_double(log(x));
}

}  // namespace

template <class T>
LyapunovResult lyapunov(const Model<T>& model, State<T> s, const LyapunovOptions& opt, State<T>* end) {
  using Tr = ScalarTraits<T>;
  using std::sqrt;
  LyapunovResult r;
  const long bits = model.bits;
  const long M = std::max(1L, opt.steps);
  long B = std::max(1L, std::min(opt.blocks, M / 10));
  const long per_block = M / B;
  B = M / per_block;
  Growth g;
  long n = 0;
  try {
    ImpactMap<T> map(model);
    for (; n < opt.transient; ++n) {
      throw_if_cancelled(n);
      s = map.step(s).next;
      g.add(n + 1, Tr::to_double(s.v));
    }
    TangentMap<T> tm(model);
    T w0 = Tr::from_int(1, bits), w1 = Tr::from_int(1, bits);
    {
      const T nrm = sqrt(w0 * w0 + w1 * w1);
      w0 = w0 / nrm;
      w1 = w1 / nrm;
    }
    std::vector<double> block_sum(B, 0.0);
    double total = 0;
    for (long i = 0; i < B * per_block; ++i, ++n) {
      throw_if_cancelled(n);
      LinearStep<T> st = tm.step(s);
      g.add(n + 1, Tr::to_double(st.next.v));
      r.v_max = std::max(r.v_max, Tr::to_double(st.next.v));
      T x0 = st.J.a11 * w0 + st.J.a12 * w1;
      T x1 = st.J.a21 * w0 + st.J.a22 * w1;
      const T nrm = sqrt(x0 * x0 + x1 * x1);
      if (st.contracted || Tr::is_zero(nrm) == Truth::yes) {
        r.contracted = true;
        r.lambda = -std::numeric_limits<double>::infinity();
        r.stderr_ = 0;
        r.steps = i + 1;
        std::ostringstream os;
        os << name(st.kind) << " at step " << n + 1
           << ": the release state does not depend on the input (J = 0), the map contracts to a point";
        r.note = os.str();
        if (end) *end = std::move(st.next);
        return r;
      }
      if (!Tr::is_finite(nrm)) throw Undecided(Reason::nonfinite);
      const double l = log_of(nrm);
      block_sum[i / per_block] += l;
      total += l;
      w0 = x0 / nrm;
      w1 = x1 / nrm;
      s = std::move(st.next);
    }
    r.steps = B * per_block;
    r.blocks = B;
    r.lambda = total / static_cast<double>(r.steps);
    if (B >= 2) {
      double mean = 0, var = 0;
      for (double b : block_sum) mean += b / per_block;
      mean /= B;
      for (double b : block_sum) var += (b / per_block - mean) * (b / per_block - mean);
      var /= (B - 1);
      r.stderr_ = std::sqrt(var / B);
    } else {
      r.stderr_ = std::numeric_limits<double>::quiet_NaN();
    }
  } catch (const Undecided& e) {
    r.undecided = true;
    r.steps = std::max(0L, n - opt.transient);
    r.lambda = std::numeric_limits<double>::quiet_NaN();
    r.stderr_ = std::numeric_limits<double>::quiet_NaN();
    r.note = std::string("step ") + std::to_string(n + 1) + " undecided: " + e.what();
    if (end) *end = s;
    return r;
  }
  if (end) *end = s;
  r.alpha = g.alpha(n);
  r.unbounded = g.unbounded(n);
  if (r.unbounded) {
    std::ostringstream os;
    os << "velocity grows without bound: running max of v ~ n^" << r.alpha
       << " (Fermi acceleration); lambda is a finite-time value";
    r.note = os.str();
  }
  return r;
}

#define BOUNCER_X(T, kind) \
  template LyapunovResult lyapunov<T>(const Model<T>&, State<T>, const LyapunovOptions&, State<T>*);
BOUNCER_FOR_EACH_ANALYSIS_SCALAR(BOUNCER_X)
#undef BOUNCER_X

}  // namespace bouncer
