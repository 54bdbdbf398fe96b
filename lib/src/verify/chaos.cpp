// A horseshoe for the bouncer, found from the model and proved (verify/chaos.hpp says how).
#include "bouncer/verify/chaos.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <optional>
#include <sstream>

#include "bouncer/analysis/jacobian.hpp"
#include "bouncer/analysis/periodic.hpp"
#include "bouncer/base/build_info.hpp"
#include "bouncer/model/impact_map.hpp"
#include "bouncer/verify/covering_impact.hpp"

namespace bouncer {

namespace {

using M = Mpfr;

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// A vector of the (theta, v) plane: a displacement or a direction.
struct Vec {
  M x, y;
};

double dbl(const M& x) { return x.to_double(); }

bool neg(const M& x) { return mpfr_sgn(x.get()) < 0; }

M mabs(const M& x) { return M(abs(x)); }

M wrap_half(const M& d) {  // into [-1/2, 1/2): theta lives on the circle
  const M half = M(1, d.bits()) / 2;
  return M(d - floor(d + half));
}

M wrap_unit(const M& x) { return M(x - floor(x)); }

Vec diff(const State<M>& a, const State<M>& b) { return {wrap_half(M(a.theta - b.theta)), M(a.v - b.v)}; }

State<M> shifted(const State<M>& p, const Vec& d) { return {wrap_unit(M(p.theta + d.x)), M(p.v + d.y)}; }

M norm(const Vec& a) { return M(sqrt(M(a.x * a.x + a.y * a.y))); }

Vec scaled(const Vec& a, const M& f) { return {M(a.x * f), M(a.y * f)}; }

Vec plus(const Vec& a, const Vec& b) { return {M(a.x + b.x), M(a.y + b.y)}; }

Vec unit(const Vec& a) {
  const M n = norm(a);
  return {M(a.x / n), M(a.y / n)};
}

Vec apply(const Mat2<M>& J, const Vec& a) { return {M(J.a11 * a.x + J.a12 * a.y), M(J.a21 * a.x + J.a22 * a.y)}; }

Vec solve(const Mat2<M>& J, const Vec& b) {  // J^-1 b
  const M det = J.a11 * J.a22 - J.a12 * J.a21;
  return {M((J.a22 * b.x - J.a12 * b.y) / det), M((J.a11 * b.y - J.a21 * b.x) / det)};
}

// Coordinates (alpha, beta) of d in the basis (a, b): d = alpha a + beta b.
std::pair<M, M> coords(const Vec& d, const Vec& a, const Vec& b) {
  const M det = a.x * b.y - a.y * b.x;
  return {M((d.x * b.y - d.y * b.x) / det), M((a.x * d.y - a.y * d.x) / det)};
}

// The unit eigenvector of J for its real eigenvalue l.
Vec eigenvector(const Mat2<M>& J, const M& l) {
  Vec a{J.a12, M(l - J.a11)}, b{M(l - J.a22), J.a21};
  return unit(norm(a) > norm(b) ? a : b);
}

// An exact rational from x rounded to `digits` significant decimal digits.
mpq_class rational(const M& x, int digits) {
  if (mpfr_zero_p(x.get())) return 0;
  mpfr_exp_t e = 0;
  char* s = mpfr_get_str(nullptr, &e, 10, static_cast<size_t>(digits), x.get(), MPFR_RNDN);
  mpz_class mant(s);
  mpfr_free_str(s);
  // x = 0.d1...dn * 10^e = mant * 10^(e - n)
  const long shift = static_cast<long>(e) - digits;
  mpz_class ten;
  mpz_ui_pow_ui(ten.get_mpz_t(), 10, static_cast<unsigned long>(std::labs(shift)));
  mpq_class q = shift >= 0 ? mpq_class(mant * ten) : mpq_class(mant, ten);
  q.canonicalize();
  return q;
}

// The model's G = F^k at Mpfr: plain (points) and with its Jacobian.
struct Dynamics {
  long bits;
  int k;
  Model<M> model;
  ImpactMap<M> map;
  TangentMap<M> tangent;
  Dynamics(const ModelSpec& spec, long bits_, int k_)
      : bits(bits_), k(k_), model(make_model<M>(spec, bits_)), map(model), tangent(model) {}

  // G(x), or nullopt when a step is undecided or not an impact.
  std::optional<State<M>> G(State<M> x) const {
    try {
      for (int i = 0; i < k; ++i) {
        StepResult<M> r = map.step(x);
        if (r.kind != EventKind::impact) return std::nullopt;
        x = r.next;
      }
      if (!std::isfinite(dbl(x.theta)) || !std::isfinite(dbl(x.v))) return std::nullopt;
      return x;
    } catch (const Undecided&) {
      return std::nullopt;
    }
  }
  std::optional<State<M>> Gn(State<M> x, int n) const {
    for (int i = 0; i < n; ++i) {
      auto y = G(x);
      if (!y) return std::nullopt;
      x = *y;
    }
    return x;
  }
  // DG at x.
  std::optional<Mat2<M>> DG(const State<M>& x) const {
    try {
      LinearOrbit<M> o = tangent.steps(x, k);
      for (EventKind kind : o.kinds)
        if (kind != EventKind::impact) return std::nullopt;
      return o.J;
    } catch (const Undecided&) {
      return std::nullopt;
    }
  }
};

// The saddle: p, its multipliers and unit eigenvectors.
struct Saddle {
  int period = 0;
  State<M> p;
  M lu, ls;
  Vec eu, es;
};

std::optional<Saddle> find_saddle(const ModelSpec& spec, const ChaosSearchOptions& o, std::string& why) {
  const Model<M> model = make_model<M>(spec, o.search_bits);
  std::ostringstream seen;
  for (int k = 1; k <= o.max_period; ++k) {
    const PeriodicOrbit<M> orbit = search_periodic<M>(model, k);
    if (!orbit.converged || orbit.minimal_period != k) continue;
    bool impacts = true;
    for (EventKind kind : orbit.kinds) impacts = impacts && kind == EventKind::impact;
    const double m0 = orbit.multipliers.modulus(0), m1 = orbit.multipliers.modulus(1);
    seen << " period " << k << ": multipliers of modulus " << m0 << ", " << m1
         << (orbit.multipliers.complex ? " (complex)" : "") << (impacts ? "" : " (not all impacts)") << ";";
    if (!impacts || orbit.multipliers.complex || !(m0 > 1 && m1 < 1)) continue;
    Saddle s;
    s.period = k;
    s.p = orbit.points[0];
    s.lu = orbit.multipliers.re[0];
    s.ls = orbit.multipliers.re[1];
    s.eu = eigenvector(orbit.J, s.lu);
    s.es = eigenvector(orbit.J, s.ls);
    return s;
  }
  why = "no saddle periodic orbit found (Newton from a grid of guesses, periods 1.." + std::to_string(o.max_period) +
        "):" + (seen.str().empty() ? std::string(" none converged") : seen.str());
  return std::nullopt;
}

// A homoclinic candidate: t with G^n(p + t e_u) on p's stable line, deep (|s_n| small).
struct Homoclinic {
  M t;
  int n = 0;
  M s;  // e_s coordinate of G^n(q0) relative to p
};

struct Search {
  const Dynamics& dyn;
  const Saddle& sd;
  const ChaosSearchOptions& o;

  State<M> start(const M& t) const { return shifted(sd.p, scaled(sd.eu, t)); }
  std::pair<M, M> local(const State<M>& x) const { return coords(diff(x, sd.p), sd.eu, sd.es); }
  // (u, s) of G^n(p + t e_u) in (e_u, e_s) coordinates at p.
  std::optional<std::pair<M, M>> at(const M& t, int n) const {
    auto x = dyn.Gn(start(t), n);
    if (!x) return std::nullopt;
    return local(*x);
  }

  // Bisection of u_n on [a, b] (opposite signs of u_n at the ends).
  std::optional<M> bisect(M a, M b, int n) const {
    auto fa = at(a, n);
    if (!fa) return std::nullopt;
    const bool neg_a = neg(fa->first);
    for (int it = 0; it < 2 * o.search_bits; ++it) {
      M mid = (a + b) / 2;
      if (mid == a || mid == b) break;
      auto fm = at(mid, n);
      if (!fm) return std::nullopt;
      if (neg(fm->first) == neg_a) a = mid; else b = mid;
    }
    return M((a + b) / 2);
  }

  // From a crossing at level n in [a, b]: the homoclinic point, made deep.
  std::optional<Homoclinic> refine(const M& a, const M& b, int n, double depth) const {
    auto t = bisect(a, b, n);
    if (!t) return std::nullopt;
    Homoclinic h{*t, n, M(0, o.search_bits)};
    auto f = at(h.t, n);
    if (!f) return std::nullopt;
    h.s = f->second;
    while (std::fabs(dbl(h.s)) > depth) {
      if (h.n >= 3 * o.max_return) return std::nullopt;
      const int next = h.n + 1;
      // A bracket of u_next around t, widened until it changes sign.
      M w = h.t;
      mpfr_mul_2si(w.get(), w.get(), -(o.search_bits - 16), MPFR_RNDN);
      w = mabs(w);
      bool found = false;
      for (int it = 0; it < 4 * o.search_bits && !found && mpfr_cmp_d(w.get(), 1e-2 * std::fabs(dbl(h.t))) < 0; ++it) {
        auto lo = at(M(h.t - w), next), hi = at(M(h.t + w), next);
        if (lo && hi && std::fabs(dbl(lo->first)) < o.neighbourhood && std::fabs(dbl(hi->first)) < o.neighbourhood &&
            neg(lo->first) != neg(hi->first)) {
          auto t2 = bisect(M(h.t - w), M(h.t + w), next);
          if (!t2) return std::nullopt;
          auto f2 = at(*t2, next);
          if (!f2) return std::nullopt;
          h = {*t2, next, f2->second};
          found = true;
        }
        w *= 2;
      }
      if (!found) return std::nullopt;
    }
    return h;
  }
};

struct Vertex {
  M t;
  State<M> x;
  bool ok = true;
  bool broken_before = false;  // the segment from the previous vertex crosses a discontinuity
};

// The homoclinic candidates (shortest returns first), or a sentence why none.
std::vector<Homoclinic> find_homoclinic(const Dynamics& dyn, const Saddle& sd, const ChaosSearchOptions& o,
                                        std::string& why) {
  Search search{dyn, sd, o};
  const long bits = o.search_bits;
  const M lu_abs = mabs(sd.lu);
  M t0(bits);
  mpfr_set_d(t0.get(), o.unstable_start, MPFR_RNDN);
  // Depth of the return: about N_0's size (the chain's last h-set sits at 2.5 S_0 from p).
  const double depth = 2.5 * 0.6 * dbl(lu_abs) * o.unstable_start;
  std::vector<Vertex> poly;
  const int k0 = 32;
  for (int j = 0; j <= k0; ++j) {
    Vertex v;
    M e(bits);
    mpfr_set_si(e.get(), j, MPFR_RNDN);
    e /= k0;
    v.t = t0 * exp(M(log(lu_abs) * e));
    v.x = search.start(v.t);
    poly.push_back(v);
  }
  auto dist_p = [&](const State<M>& x) { return dbl(norm(diff(x, sd.p))); };
  std::vector<Homoclinic> out;
  long total = 0;
  for (int n = 1; n <= o.max_return && out.empty(); ++n) {
    for (Vertex& v : poly) {
      if (!v.ok) continue;
      auto y = dyn.G(v.x);
      if (y) v.x = *y; else v.ok = false;
    }
    // Refine: split segments whose ends drift apart.
    std::vector<Vertex> next;
    next.push_back(poly[0]);
    std::function<void(const Vertex&, const Vertex&, int)> split = [&](const Vertex& a, const Vertex& b, int depth_) {
      if (!a.ok || !b.ok || b.broken_before) {
        next.push_back(b);
        return;
      }
      const double d = dbl(norm(diff(b.x, a.x)));
      const double want = std::clamp(0.25 * std::min(dist_p(a.x), dist_p(b.x)), 1e-9, o.spacing);
      if (d <= want) {
        next.push_back(b);
        return;
      }
      if (depth_ > 80 || static_cast<long>(next.size() + poly.size()) > o.max_vertices) {
        Vertex c = b;
        c.broken_before = true;
        next.push_back(c);
        return;
      }
      Vertex mid;
      mid.t = (a.t + b.t) / 2;
      auto x = dyn.Gn(search.start(mid.t), n);
      ++total;
      if (!x) {
        mid.ok = false;
        mid.x = a.x;
      } else {
        mid.x = *x;
      }
      split(a, mid, depth_ + 1);
      split(next.back(), b, depth_ + 1);
    };
    for (size_t i = 1; i < poly.size(); ++i) split(next.back(), poly[i], 0);
    poly.swap(next);
    if (static_cast<long>(poly.size()) > o.max_vertices) {
      why = "no homoclinic return found: the unstable manifold's polyline needs more than " +
            std::to_string(o.max_vertices) + " vertices by iterate " + std::to_string(n);
      return out;
    }
    // Crossings of the stable line near p.
    for (size_t i = 1; i < poly.size() && static_cast<int>(out.size()) < o.max_candidates; ++i) {
      const Vertex &a = poly[i - 1], &b = poly[i];
      if (!a.ok || !b.ok || b.broken_before) continue;
      const auto [ua, sa] = search.local(a.x);
      const auto [ub, sb] = search.local(b.x);
      const double R = o.neighbourhood;
      if (std::fabs(dbl(ua)) > R || std::fabs(dbl(ub)) > R || std::fabs(dbl(sa)) > R || std::fabs(dbl(sb)) > R) continue;
      if (neg(ua) == neg(ub)) continue;
      auto h = search.refine(a.t, b.t, n, depth);
      if (h) out.push_back(*h);
    }
  }
  if (out.empty() && why.empty())
    why = "no homoclinic return found: the unstable manifold of the saddle (" + std::to_string(poly.size()) +
          " vertices) does not cross its stable line within " + std::to_string(o.neighbourhood) + " of it in " +
          std::to_string(o.max_return) + " iterates of G";
  return out;
}

// The h-sets along a homoclinic orbit (verify/chaos.hpp), or a sentence why not.
struct Chain {
  std::vector<HSet2> sets;
  int m = 0;
  double return_distance = 0;
  std::string why;
};

Chain build_chain(const Dynamics& dyn, const Saddle& sd, const Homoclinic& h, const ChaosSearchOptions& o) {
  Chain c;
  const long bits = o.search_bits;
  const int m = h.n;
  c.m = m;
  c.return_distance = std::fabs(dbl(h.s));
  const M one(1, bits);
  M delta(bits);
  mpfr_set_d(delta.get(), o.margin, MPFR_RNDN);
  const M grow = one + delta;
  M sdelta(bits);
  mpfr_set_d(sdelta.get(), o.stable_margin, MPFR_RNDN);
  const M sgrow = one + sdelta;
  M cap(bits);
  mpfr_set_d(cap.get(), o.cap, MPFR_RNDN);
  // The orbit q_0..q_{m+1} and DG along it.
  std::vector<State<M>> q(m + 2);
  std::vector<Mat2<M>> J(m + 1);
  q[0] = shifted(sd.p, scaled(sd.eu, h.t));
  for (int i = 0; i <= m; ++i) {
    auto y = dyn.G(q[i]);
    auto d = dyn.DG(q[i]);
    if (!y || !d) {
      c.why = "the homoclinic orbit is undecided at iterate " + std::to_string(i);
      return c;
    }
    q[i + 1] = *y;
    J[i] = *d;
  }
  // Directions: unstable forward, stable backward from e_s at q_{m+1}.
  std::vector<Vec> w(m + 1), z(m + 2);
  w[0] = sd.eu;
  w[1] = unit(apply(J[0], sd.eu));
  for (int i = 1; i < m; ++i) w[i + 1] = unit(apply(J[i], w[i]));
  z[m + 1] = sd.es;
  for (int i = m; i >= 1; --i) z[i] = unit(solve(J[i], z[i + 1]));
  z[0] = sd.es;
  const M sm = coords(diff(q[m], sd.p), sd.eu, sd.es).second;
  const M sm_abs = mabs(sm);
  const M u1 = coords(diff(q[1], sd.p), sd.eu, sd.es).first;
  const M D = mabs(u1);
  std::vector<M> L(m + 1, M(0, bits)), S(m + 1, M(0, bits));
  L[0] = M(D * 6 / 10);
  // The cap leaves the last h-set room to stretch across N_0 (|lambda_u| L_m > L_0).
  if (cap < L[0] * 2) cap = M(L[0] * 2);
  S[0] = M(sm_abs / 5 * 2);
  // Images of a grid of N_i (centre a, directions wa, za, radii la, sa) relative to b in the
  // basis (wb, zb): the smallest |alpha| on the edges x = +-1 (the reach of the image along
  // the next unstable direction), then, given the next unstable radius lb, the largest |beta|
  // where the image may be inside the next h-set's unstable strip (|alpha| <= 1.5 (1 + margin)
  // lb at a grid point or at one of its neighbours along x).
  constexpr int nx = 16;
  struct Spread {
    M edge;
    std::vector<std::array<M, 2>> image;  // (alpha, beta) per grid point, x fastest
    bool ok = true;
    M beta(const M& lb, const M& grow_) const {
      const M reach = M(lb * grow_ * 3 / 2);
      M out(0, lb.bits());
      for (int iy = 0; iy < 3; ++iy)
        for (int ix = 0; ix <= 2 * nx; ++ix) {
          bool near = false;
          for (int jx = std::max(0, ix - 1); jx <= std::min(2 * nx, ix + 1); ++jx)
            near = near || mabs(image[iy * (2 * nx + 1) + jx][0]) <= reach;
          const M bb = mabs(image[iy * (2 * nx + 1) + ix][1]);
          if (near && bb > out) out = bb;
        }
      return out;
    }
  };
  auto spread = [&](const State<M>& a, const Vec& wa, const Vec& za, const M& la, const M& sa, const State<M>& b,
                    const Vec& wb, const Vec& zb) {
    Spread r{M(0, bits), {}, true};
    bool first = true;
    for (int iy = -1; iy <= 1; ++iy)
      for (int ix = -nx; ix <= nx; ++ix) {
        const M x = M(M(ix, bits) / nx);
        const Vec d = plus(scaled(wa, M(la * x)), scaled(za, M(sa * iy)));
        auto y = dyn.G(shifted(a, d));
        if (!y) {
          r.ok = false;
          return r;
        }
        const auto [al, be] = coords(diff(*y, b), wb, zb);
        r.image.push_back({al, be});
        if ((ix == -nx || ix == nx) && (first || mabs(al) < r.edge)) {
          r.edge = mabs(al);
          first = false;
        }
      }
    return r;
  };
  for (int pass = 0; pass < 3; ++pass) {
    // N_1 from N_0.
    L[1] = M(D / 5);
    {
      const Spread r = spread(sd.p, sd.eu, sd.es, L[0], S[0], q[1], w[1], z[1]);
      if (!r.ok) {
        c.why = "an image of a point of N_0 is undecided";
        return c;
      }
      S[1] = M(r.beta(L[1], grow) * sgrow);
    }
    for (int i = 1; i < m; ++i) {
      // The unstable radius from the images of the edges, the stable one from the relevant part.
      Spread r = spread(q[i], w[i], z[i], L[i], S[i], q[i + 1], w[i + 1], z[i + 1]);
      if (!r.ok) {
        c.why = "an image of a point of N_" + std::to_string(i) + " is undecided (radius " + std::to_string(dbl(L[i])) + ")";
        return c;
      }
      L[i + 1] = M(r.edge / grow);
      if (L[i + 1] > cap) L[i + 1] = cap;
      S[i + 1] = M(r.beta(L[i + 1], grow) * sgrow);
    }
    // Closing N_m => N_0: S_0 between the image's stable spread and the gap to N_m.
    const Spread r = spread(q[m], w[m], z[m], L[m], S[m], sd.p, sd.eu, sd.es);
    if (!r.ok) {
      c.why = "an image of a point of N_m is undecided";
      return c;
    }
    const M lower = M(r.beta(L[0], grow) * grow), upper = M((sm_abs - S[m]) / grow);
    if (r.edge < L[0] * grow) {
      std::ostringstream s;
      s << "the last h-set's image does not stretch across N_0: its edges reach " << dbl(r.edge) << " along e_u, N_0 is "
        << dbl(L[0]) << " wide (the unstable radii were capped at " << dbl(cap) << ")";
      c.why = s.str();
      return c;
    }
    if (!(lower < upper)) {
      std::ostringstream s;
      s << "no stable radius of N_0 fits: the last h-set's image spreads " << dbl(lower) << " along e_s, the gap to it is "
        << dbl(upper) << " (return distance " << dbl(sm_abs) << ", its stable radius " << dbl(S[m]) << ")";
      c.why = s.str();
      return c;
    }
    S[0] = M(sqrt(M(lower * upper)));
  }
  auto hset = [&](const State<M>& centre, const Vec& wa, const Vec& za, const M& la, const M& sa) {
    HSet2 n;
    n.c = {rational(centre.theta, o.digits), rational(centre.v, o.digits)};
    n.B[0][0] = rational(M(wa.x * la), o.digits);
    n.B[1][0] = rational(M(wa.y * la), o.digits);
    n.B[0][1] = rational(M(za.x * sa), o.digits);
    n.B[1][1] = rational(M(za.y * sa), o.digits);
    return n;
  };
  c.sets.push_back(hset(sd.p, sd.eu, sd.es, L[0], S[0]));
  for (int i = 1; i <= m; ++i) c.sets.push_back(hset(q[i], w[i], z[i], L[i], S[i]));
  // Every h-set inside 0 < theta < 1: the strip where the plane's (theta, v) are the
  // cylinder's, so that disjointness in the plane is disjointness on the cylinder and no
  // h-set is cut by the wrap of theta.
  for (int i = 0; i <= m; ++i) {
    const HSet2& n = c.sets[i];
    const mpq_class half = abs(n.B[0][0]) + abs(n.B[0][1]);
    if (n.c[0] - half <= 0 || n.c[0] + half >= 1) {
      c.why = "N_" + std::to_string(i) + " crosses theta = 0 (the wrap of the phase)";
      c.sets.clear();
      return c;
    }
  }
  return c;
}

// Builds and checks the chain of each candidate until one is proved; fills `out` with the
// last one tried, and `failures` with why the others were not proved.
void try_candidates(const ModelSpec& spec, const Dynamics& dyn, const Saddle& saddle_, const std::vector<Homoclinic>& candidates,
                    const ChaosSearchOptions& o, const std::string& saddle_text, const std::string& at, ChaosSearchResult& out,
                    std::vector<std::string>& failures) {
  const Saddle* saddle = &saddle_;
  for (const Homoclinic& h : candidates) {
    out.orbit.t = dbl(h.t);
    out.orbit.m = h.n;
    out.orbit.return_distance = std::fabs(dbl(h.s));
    Chain chain = build_chain(dyn, *saddle, h, o);
    if (chain.sets.empty()) {
      failures.push_back(at + "return after " + std::to_string(h.n) + " iterates: " + chain.why);
      continue;
    }
    const int m = chain.m;
    const int count = m + 1;
    // One map per h-set: G on the branch at its centre.
    std::vector<SetMap2> maps;
    std::vector<std::string> branches;
    std::string undecided;
    for (int i = 0; i < count; ++i) {
      const auto branch = impact_branch(spec, saddle->period, o.bits, chain.sets[i].c[0], chain.sets[i].c[1]);
      if (branch.empty() && undecided.empty()) undecided = "the branch at the centre of N_" + std::to_string(i) + " is undecided";
      branches.push_back(branch_text(branch));
      maps.push_back(impact_set_map(spec, branch, o.bits));
    }
    if (!undecided.empty()) {
      failures.push_back(at + "return after " + std::to_string(h.n) + " iterates: " + undecided);
      continue;
    }
    std::vector<CoveringEdge> edges{{0, 0}, {0, 1}};
    for (int i = 1; i < m; ++i) edges.push_back({i, i + 1});
    edges.push_back({m, 0});
    const CoveringOptions copt{o.bits, o.max_pieces};
    HorseshoeResult hs = check_horseshoe(maps, chain.sets, edges, saddle->period, copt);
    // The return strip across further h-sets along W^u: N_m => N_1, N_2, ... while proved.
    for (int j = 1; j < m; ++j) {
      CoveringResult extra = check_covering(maps[m], chain.sets[m], chain.sets[j], {o.bits, std::min(16, o.max_pieces)});
      if (!extra.proved) break;
      hs.coverings[m][j] = extra;
      hs.matrix[m][j] = 1;
      edges.push_back({m, j});
    }
    if (hs.disjoint) hs.entropy = entropy_lower_bound(hs.matrix, saddle->period, o.bits);
    out.coverings.clear();
    std::string first_failure;
    for (const CoveringEdge& e : edges) {
      const CoveringResult& r = hs.coverings[e.from][e.to];
      out.coverings.push_back({e.from, e.to, r});
      if (!r.proved && first_failure.empty())
        first_failure = "N_" + std::to_string(e.from) + " => N_" + std::to_string(e.to) + " (" + name(r.failure) + "): " + r.message;
    }
    out.disjoint = hs.disjoint;
    out.entropy = hs.entropy;
    out.certificate.sets = chain.sets;
    out.certificate.coverings.clear();
    for (const CoveringEdge& e : edges) {
      const CoveringResult& r = hs.coverings[e.from][e.to];
      if (r.proved) out.certificate.coverings.push_back({e.from, e.to, r.sign, r.pieces, branches[e.from]});
    }
    out.certificate.entropy_bound = hs.entropy.bound;
    out.certificate.quotient = hs.entropy.quotient;
    if (hs.disjoint && hs.entropy.horseshoe) {
      out.proved = true;
      std::ostringstream s;
      s << "proved: h_top >= " << hs.entropy.bound << " per collision (" << saddle_text << "; homoclinic return after "
        << m << " iterates of F^" << saddle->period << ", " << count << " disjoint h-sets, "
        << out.certificate.coverings.size() << " coverings at " << o.bits << " bits)";
      out.message = s.str();
      break;
    }
    std::string f = at + "return after " + std::to_string(m) + " iterates: ";
    if (!hs.disjoint) {
      for (int i = 0; i < count; ++i)
        for (int j = i + 1; j < count; ++j)
          if (!hsets_disjoint(chain.sets[i], chain.sets[j]) && f.find("overlap") == std::string::npos)
            f += "N_" + std::to_string(i) + " and N_" + std::to_string(j) + " overlap; ";
    }
    if (!first_failure.empty()) f += "covering " + first_failure;
    failures.push_back(f);
  }
}

}  // namespace

ChaosSearchResult certify_chaos(const ModelSpec& spec, const ChaosSearchOptions& o) {
  ChaosSearchResult out;
  const auto t_start = std::chrono::steady_clock::now();
  out.certificate.map = ChaosMap::impact;
  out.certificate.model = spec;
  out.certificate.bits = o.bits;
  out.certificate.made_by = "certify_chaos (bouncer " + build_info().version + ", commit " + build_info().commit + ")";
  // With --veldep-collapse on, a point sticks where the collapse bound is at most the time
  // left, but an interval step over a box where that is undecided goes on bouncing: the
  // enclosures would be of another map than F at some points of an h-set. No proof then.
  if (spec.law == Law::veldep && spec.veldep_collapse) {
    out.message = "not attempted with --veldep-collapse on: the interval step does not decide the collapse test "
                  "over a box (it bounces where a point of the box may stick), so its enclosures are not of F";
    return out;
  }
  std::string why;
  const auto saddle = find_saddle(spec, o, why);
  if (!saddle) {
    out.message = why;
    out.search_seconds = seconds_since(t_start);
    return out;
  }
  out.orbit.period = saddle->period;
  out.orbit.theta = dbl(saddle->p.theta);
  out.orbit.v = dbl(saddle->p.v);
  out.orbit.lambda_u = dbl(saddle->lu);
  out.orbit.lambda_s = dbl(saddle->ls);
  out.certificate.k = saddle->period;
  const Dynamics dyn(spec, o.search_bits, saddle->period);
  std::ostringstream saddle_text;
  saddle_text << "saddle of period " << saddle->period << " at (" << out.orbit.theta << ", " << out.orbit.v
              << "), multipliers " << out.orbit.lambda_u << ", " << out.orbit.lambda_s;
  out.search_seconds = seconds_since(t_start);
  std::vector<std::string> failures;
  for (int attempt = 0; attempt < std::max(1, o.attempts) && !out.proved; ++attempt) {
    // Each further attempt starts 4 times closer to p with 4 times smaller h-sets.
    ChaosSearchOptions oa = o;
    // Near a strongly expanding saddle the first image of the fundamental domain is far from
    // p: t0 scaled by 3 / |lambda_u| when that is below 1.
    const double scale = std::min(1.0, 3.0 / std::fabs(out.orbit.lambda_u)) / std::pow(4.0, attempt);
    oa.unstable_start = o.unstable_start * scale;
    oa.cap = o.cap * scale;
    std::ostringstream at;
    at << "t0 = " << oa.unstable_start << ": ";
    const auto t_search = std::chrono::steady_clock::now();
    why.clear();
    const std::vector<Homoclinic> candidates = find_homoclinic(dyn, *saddle, oa, why);
    out.candidates += static_cast<int>(candidates.size());
    out.search_seconds += seconds_since(t_search);
    if (candidates.empty()) {
      failures.push_back(at.str() + why);
      continue;
    }
    const auto t_check = std::chrono::steady_clock::now();
    try_candidates(spec, dyn, *saddle, candidates, oa, saddle_text.str(), at.str(), out, failures);
    out.check_seconds += seconds_since(t_check);
  }
  if (!out.proved) {
    std::string s = "not proved (" + saddle_text.str() + "):";
    for (const std::string& f : failures) s += " " + f + ";";
    out.message = s;
  }
  return out;
}

}  // namespace bouncer
