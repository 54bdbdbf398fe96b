// Certified border collisions, both sides (verify/border_collision.hpp).
#include "bouncer/verify/border_collision.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <functional>
#include <cmath>
#include <limits>
#include <memory>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "bouncer/analysis/jacobian.hpp"
#include "bouncer/verify/enclosure.hpp"
#include "bouncer/model/impact_map_impl.hpp"
#include "bouncer/verify/interval_dual.hpp"
#include "sparse_krawczyk.hpp"

namespace bouncer {

namespace {

using Tr = ScalarTraits<Mpfi>;

// Why the proof stopped (caught once, in certify_border_collision).
struct Fail : std::runtime_error {
  using std::runtime_error::runtime_error;
};

Mpfi thin(const Mpfr& x) { return Mpfi(x, x); }

mpq_class to_q(const Mpfr& x) {
  mpq_class r;
  mpfr_get_q(r.get_mpq_t(), x.get());
  return r;
}

Enclosure enclosure(const Mpfi& x) {
  const std::string hi = Tr::upper_string(x);
  return {Tr::lower_string(x), hi == "-0" ? "0" : hi, x.mid().to_double(), x.width().to_double()};
}

bool strictly_inside(const Mpfi& x, const Mpfi& y) { return mpfi_is_strictly_inside(x.get(), y.get()) > 0; }

std::string text(const Mpfr& x) { return Tr::lower_string(thin(x)); }

// One step of the branch side's piece: departure segment, impact segment and the whole wall
// periods from the departure's period to the impact's, whether the impact sticks (then the
// step ends at the release state of the ride: knot and velocity from the wall).
struct Piece {
  int from_segment = 0;
  int segment = 0;
  long periods = 0;
  bool sticks = false;
  int release_knot = -1;
};

// Margin kinds: continuation.hpp's Margin, and the departure speed v - u (> 0: the particle
// leaves the wall), which the step decides too.
constexpr int kDeparture = kMargins;

struct MarginId {
  int kind = 0;
  long step = 0;
  int knot = -1;
  bool end = false;  // knot margins: to the end of the impact's segment (else to its start)
};

std::string margin_words(const MarginId& id) {
  std::ostringstream s;
  s << "step " << id.step << ": ";
  switch (id.kind) {
    case static_cast<int>(Margin::knot): s << "the impact's distance to the knot " << id.knot; break;
    case static_cast<int>(Margin::clearance): s << "the flight's clearance at the knot " << id.knot; break;
    case static_cast<int>(Margin::speed): s << "the impact speed (squared)"; break;
    case static_cast<int>(Margin::sticking): s << "the sticking test"; break;
    default: s << "the departure speed"; break;
  }
  return s.str();
}

// The branch side's piece of one step, in closed form, for any scalar T of the step (Mpfi,
// Dual<Mpfi>): never decides a branch. Gap to the line of the impact segment j in wall
// period K (relative to the departure's period), t the time since departure:
//   gap(t) = g0 + W t - a t^2/2,  W = v - u_j,  g0 = f(theta) - h_j - u_j (theta - K - s_j),
// its larger root t* = (W + q)/a = 2 g0/(q - W), q = sqrt(W^2 + 2 a g0) the relative impact
// speed; theta' = theta + t* - K, v' = u_j + rebound(q). On the branch side this is the step
// (the walk of impact_map_impl.hpp finds the same root of the same quadratic); across the
// border it is that formula's analytic extension. Appends the step's margins (raw signs).
template <class T>
State<T> piece_step(const ImpactMap<T>& map, const State<T>& s, const Piece& pc, long step, std::vector<T>* mv,
                    std::vector<MarginId>* ids) {
  using TT = ScalarTraits<T>;
  using std::sqrt;
  const Model<T>& m = map.model();
  const Wall<T>& w = m.wall;
  auto push = [&](int kind, int knot, T x, bool end = false) {
    if (mv) mv->push_back(std::move(x));
    if (ids) ids->push_back({kind, step, knot, end});
  };
  const bool margins = mv || ids;
  const int j0 = pc.from_segment, j = pc.segment;
  const T K = TT::from_int(pc.periods, m.bits);
  const T f0 = w.height_at(j0, s.theta);
  if (margins) {
    push(kDeparture, -1, T(s.v - w.velocity[j0]));
    // Clearance at every knot passed strictly inside the flight (the gap is concave on each
    // segment, so positive at the knots means positive in between).
    int jj = j0;
    long mm = 0, count = 0;
    while (!(jj == j && mm == pc.periods)) {
      jj = w.next(jj);
      if (jj == 0) ++mm;
      if (++count > 100000) throw Fail("a flight passes more than 1e5 wall knots");
      const T tk = w.start[jj] + TT::from_int(mm, m.bits) - s.theta;
      push(static_cast<int>(Margin::clearance), jj, T(f0 + s.v * tk - m.a * tk * tk / 2 - w.height[jj]));
    }
  }
  const T& u = w.velocity[j];
  const T g0 = f0 - w.height[j] - u * (s.theta - K - w.start[j]);
  const T W = s.v - u;
  const T D = W * W + 2 * m.a * g0;
  if (margins) push(static_cast<int>(Margin::speed), -1, D);
  const T q = sqrt(D);
  const T t = TT::likely_negative(W) && !TT::likely_negative(g0) ? T(2 * g0 / (q - W)) : T((W + q) / m.a);
  State<T> next;
  next.theta = s.theta + t - K;
  if (margins) {
    push(static_cast<int>(Margin::knot), j, T(next.theta - w.start[j]));
    push(static_cast<int>(Margin::knot), w.next(j), T(w.end[j] - next.theta), true);
  }
  const T out = map.rebound(q);
  if (margins && m.law == Law::constant)
    push(static_cast<int>(Margin::sticking), -1, T(out - m.collapse * (w.end[j] - next.theta)));
  if (pc.sticks) {
    next = release_state(m, pc.release_knot);
  } else {
    next.v = u + out;
  }
  return next;
}

template <class T>
State<T> piece_orbit(const ImpactMap<T>& map, State<T> s, const std::vector<Piece>& pieces, std::vector<T>* mv,
                     std::vector<MarginId>* ids = nullptr, std::vector<State<T>>* points = nullptr) {
  for (size_t i = 0; i < pieces.size(); ++i) {
    if (points) points->push_back(s);
    s = piece_step(map, s, pieces[i], static_cast<long>(i), mv, ids);
  }
  return s;
}

struct Jet;

// Everything fixed by the branch side.
struct Setup {
  Parameter par = Parameter::a;
  long bits = 128;
  bool high = true;            // the branch lies below a* (a high end)
  Model<Mpfi> base;            // the model in intervals (its parameter replaced per evaluation)
  std::vector<Piece> pieces;
  std::vector<StepEvent> events;
  std::vector<MarginId> ids;   // the margins, in evaluation order
  std::vector<int> sign;       // +1: positive on the branch side
  int border = -1;             // index of the margin that vanishes
  bool release = false;        // an orbit through a sticking step: the start R is exact
  State<Mpfi> R;
  // The orbit's unknowns: m points x_0 .. x_{m-1} (2m numbers theta_i, v_i), then the
  // parameter, index 2m. m = 1: the composed map, P_E^Q(x_0) = x_0 (the first point alone).
  // m = Q (multiple shooting, long periods): step i's piece maps x_i to x_{i+1 mod Q}, each
  // step evaluated over its own point's box. The composed map's interval evaluation widens a
  // box by the product of the Q steps' derivative norms (2^66 over a period-66 orbit);
  // shooting never composes, so its boxes stay as narrow as each point's own uncertainty.
  int m = 1;
  // Another system on the same unknowns (period doubling, m = 1): its values at a thin point
  // and its Jacobian over a box; unset for the border collision.
  std::function<std::vector<Mpfi>(const std::vector<Mpfi>&)> value_fn;
  std::function<Jet(const std::vector<Mpfi>&)> jet_fn;
};

// The number of unknowns (and of rows): the m points and the parameter.
size_t dim(const Setup& S) { return static_cast<size_t>(2 * S.m + 1); }

Model<Mpfi> at(const Setup& S, const Mpfi& p) { return with_parameter(S.base, S.par, p); }

// The orbit rows at (x, p): g = (P_E^Q(x_0) - x_0) for m = 1, (piece_i(x_i) - x_{i+1 mod Q})_i
// for m = Q, and every margin of every step, in the order of S.ids. x holds the 2m point
// coordinates (ignored for an orbit through the release state, whose start is exact).
struct Eval {
  std::vector<Mpfi> g;
  std::vector<Mpfi> margins;
};

Eval evaluate(const Setup& S, const std::vector<Mpfi>& x, const Mpfi& p) {
  const ImpactMap<Mpfi> map(at(S, p));
  Eval e;
  if (S.release) {
    const State<Mpfi> end = piece_orbit(map, S.R, S.pieces, &e.margins);
    e.g = {Mpfi(end.theta - S.R.theta), Mpfi(end.v - S.R.v)};
  } else if (S.m == 1) {
    const State<Mpfi> end = piece_orbit(map, State<Mpfi>{x[0], x[1]}, S.pieces, &e.margins);
    e.g = {Mpfi(end.theta - x[0]), Mpfi(end.v - x[1])};
  } else {
    const size_t q = S.pieces.size();
    for (size_t i = 0; i < q; ++i) {
      const State<Mpfi> end = piece_step(map, State<Mpfi>{x[2 * i], x[2 * i + 1]}, S.pieces[i], static_cast<long>(i),
                                         &e.margins, static_cast<std::vector<MarginId>*>(nullptr));
      const size_t k = (i + 1) % q;
      e.g.push_back(Mpfi(end.theta - x[2 * k]));
      e.g.push_back(Mpfi(end.v - x[2 * k + 1]));
    }
  }
  return e;
}

// The orbit's points as unknowns (2m numbers) from the start state of a reference orbit and
// its steps' images.
std::vector<Mpfr> point_unknowns(const Setup& S, const State<Mpfr>& start, const std::vector<State<Mpfr>>& next) {
  std::vector<Mpfr> y = {start.theta, start.v};
  for (int i = 0; i + 1 < S.m; ++i) {
    y.push_back(next[static_cast<size_t>(i)].theta);
    y.push_back(next[static_cast<size_t>(i)].v);
  }
  return y;
}

// Orbits through the release state: every margin with its derivative in p, over P.
std::vector<IDual> margin_slopes(const Setup& S, const Mpfi& P) {
  Model<IDual> dm = convert_model<IDual>(S.base, [](const Mpfi& y) { return IDual(y); });
  dm = with_parameter(dm, S.par, IDual::variable(P, 0));
  const ImpactMap<IDual> map(std::move(dm));
  std::vector<IDual> mv;
  piece_orbit(map, State<IDual>{IDual(S.R.theta), IDual(S.R.v), S.R.knot}, S.pieces, &mv);
  return mv;
}

// A clearance that vanishes with the border's knot margin, by an identity. With delta the
// knot margin of the impact ending step i:
//   A. the impact nears the END of its segment (knot k): the next flight passes knot k first,
//      after the time delta, with gap = delta (W - a delta/2), W its departure margin;
//   B. the impact nears the START of its segment (knot k): the flight passed knot k last,
//      delta before the impact, with gap = delta (q - a delta/2), q the impact speed sqrt(D).
// (The wall is linear on each segment and continuous at k.) So that clearance is > 0 where
// delta > 0 (the border margin's sign, proved separately) if the factor is > 0 over the box.
bool coincident_clearance(const Setup& S, const std::vector<Mpfi>& mv, size_t i, const Mpfi& p) {
  const MarginId& b = S.ids[S.border];
  const MarginId& c = S.ids[i];
  if (b.kind != static_cast<int>(Margin::knot) || c.kind != static_cast<int>(Margin::clearance) || c.knot != b.knot) return false;
  const long q = static_cast<long>(S.pieces.size());
  const bool at_end = b.end;
  // The step's clearances, in the order the flight passes the knots.
  auto clearances = [&](long step) {
    std::vector<size_t> idx;
    for (size_t k = 0; k < S.ids.size(); ++k)
      if (S.ids[k].step == step && S.ids[k].kind == static_cast<int>(Margin::clearance)) idx.push_back(k);
    return idx;
  };
  auto index_of = [&](long step, int kind) -> long {
    for (size_t k = 0; k < S.ids.size(); ++k)
      if (S.ids[k].step == step && S.ids[k].kind == kind) return static_cast<long>(k);
    return -1;
  };
  const Mpfi a = at(S, p).a;
  const Mpfi delta = mv[S.border];  // knot margins are positive on the branch side
  const Mpfi zero(0, S.bits);
  if (at_end) {
    const long next = (b.step + 1) % q;
    const std::vector<size_t> cl = clearances(next);
    if (c.step != next || cl.empty() || cl.front() != i) return false;
    const long dep = index_of(next, kDeparture);
    return dep >= 0 && Tr::lt(zero, Mpfi(mv[dep] - a * delta / 2)) == Truth::yes;
  }
  const std::vector<size_t> cl = clearances(b.step);
  if (c.step != b.step || cl.empty() || cl.back() != i) return false;
  const long sp = index_of(b.step, static_cast<int>(Margin::speed));
  if (sp < 0 || Tr::lt(zero, mv[sp]) != Truth::yes) return false;
  return Tr::lt(zero, Mpfi(sqrt(mv[sp]) - a * delta / 2)) == Truth::yes;
}

// The border margin, oriented (> 0 on the branch side).
Mpfi oriented(const Setup& S, const std::vector<Mpfi>& mv, size_t i) { return S.sign[i] > 0 ? mv[i] : Mpfi(-mv[i]); }

// Two margins of a step whose signs follow from its entry clearance, by identities. The gap
// to the line of the impact segment j, g(t) = g0 + W t - a t^2/2, keeps
// g'(t)^2 + 2 a g(t) = W^2 + 2 a g0 = D at every t. Let t_k be the time the flight enters
// segment j's window, at its start knot in the impact's wall period (the step's last
// clearance, c = g(t_k)). Then
//   - the impact speed: D = g'(t_k)^2 + 2 a c >= 2 a c, so D > 0 where c > 0;
//   - the impact's distance to that knot, t* - t_k = (g'(t_k) + sqrt(D)) / a, > 0 where c > 0
//     (sqrt(D) > |g'(t_k)|: t_k lies strictly between the roots, t* the larger);
// and for a flight that departs from segment j itself (no knot passed) g0 = 0 and D = W^2, W
// its departure margin. So these margins are > 0 wherever that clearance (or departure
// margin) is > 0: certainly so over the box, or because it is the border margin itself, > 0
// on the branch side by steps 2 and 3. This is what makes a corner touchdown provable: the
// release orbit at a = 8 lands on the peak with zero relative speed, where its clearance at
// the peak is 4 - a/2, D = 8 (8 - a) and the distance to the peak is of order sqrt(8 - a),
// all 0 at a*; their own intervals (differences of terms near 64) cannot decide their signs
// next to a*. It is also why a touchdown cannot end a branch alone: D reaches 0 only where c
// and g'(t_k) do (a corner touchdown), or where the departure speed does.
bool implied_by_entry(const Setup& S, const std::vector<Mpfi>& mv, size_t i) {
  const MarginId& id = S.ids[i];
  const bool speed = id.kind == static_cast<int>(Margin::speed);
  const Piece& pc = S.pieces[static_cast<size_t>(id.step)];
  if (!speed && !(id.kind == static_cast<int>(Margin::knot) && !id.end && id.knot == pc.segment)) return false;
  long from = -1;  // the step's last clearance, else (the speed) its departure margin
  for (size_t k = 0; k < S.ids.size(); ++k)
    if (S.ids[k].step == id.step && S.ids[k].kind == static_cast<int>(Margin::clearance)) from = static_cast<long>(k);
  if (from >= 0 && S.ids[static_cast<size_t>(from)].knot != pc.segment) return false;
  if (from < 0) {
    if (!speed || pc.from_segment != pc.segment || pc.periods != 0) return false;
    for (size_t k = 0; k < S.ids.size(); ++k)
      if (S.ids[k].step == id.step && S.ids[k].kind == kDeparture) from = static_cast<long>(k);
    if (from < 0) return false;
  }
  if (from == S.border) return true;
  return Tr::lt(Mpfi(0, S.bits), oriented(S, mv, static_cast<size_t>(from))) == Truth::yes;
}

// Values and Jacobian of the system over a box. Variables: the 2m point coordinates, then p
// (index 2m); rows: the 2m orbit rows of Eval::g, then the border margin (index 2m). The
// Jacobian is kept by columns, with only its structurally nonzero entries (shooting: each
// step's row pair depends on its own point, the next point and p), so that C A costs
// n^2 times a few products, not n^3.
struct Jet {
  std::vector<Mpfi> f;
  std::vector<std::vector<std::pair<size_t, Mpfi>>> col;
  explicit Jet(size_t n) : f(n), col(n) {}
  void set(size_t r, size_t c, Mpfi v) { col[c].emplace_back(r, std::move(v)); }
};

Jet jet(const Setup& S, const std::vector<Mpfi>& x) {
  const size_t N = dim(S), P = N - 1;
  Jet J(N);
  const bool margin_row = S.border >= 0;
  const bool flip = margin_row && S.sign[S.border] < 0;
  auto check = [](const IDual& y) {
    if (!ScalarTraits<IDual>::derivatives_finite(y))
      throw Fail("the derivative enclosure over the box is not finite (the enclosure of an impact speed over it reaches 0: the box is too wide at this precision)");
  };
  // One step (or the composed period, m = 1) from a start: run 0 differentiates along the
  // start (theta, v), run 1 along p. Returns the end and the margins with their derivatives.
  const size_t steps = S.m == 1 ? 1 : S.pieces.size();
  for (size_t i = 0; i < steps; ++i) {
    for (int run = S.release ? 1 : 0; run < 2; ++run) {
      Model<IDual> dm = convert_model<IDual>(S.base, [](const Mpfi& y) { return IDual(y); });
      dm = with_parameter(dm, S.par, run == 1 ? IDual::variable(x[P], 0) : IDual(x[P]));
      const ImpactMap<IDual> map(std::move(dm));
      const State<IDual> s = S.release ? State<IDual>{IDual(S.R.theta), IDual(S.R.v), S.R.knot}
                             : run == 0 ? State<IDual>{IDual::variable(x[2 * i], 0), IDual::variable(x[2 * i + 1], 1)}
                                        : State<IDual>{IDual(x[2 * i]), IDual(x[2 * i + 1])};
      std::vector<IDual> mv;
      const State<IDual> end = S.m == 1 ? piece_orbit(map, s, S.pieces, &mv)
                                        : piece_step(map, s, S.pieces[i], static_cast<long>(i), &mv,
                                                     static_cast<std::vector<MarginId>*>(nullptr));
      // The border margin's row, where it belongs to this step (m = 1: the only one).
      const IDual* border = nullptr;
      if (margin_row) {
        if (S.m == 1) {
          border = &mv[S.border];
        } else if (S.ids[S.border].step == static_cast<long>(i)) {
          // This step's margins are the ones of S.ids with step i, in the same order.
          size_t first = 0;
          while (S.ids[first].step != static_cast<long>(i)) ++first;
          border = &mv[static_cast<size_t>(S.border) - first];
        }
      }
      if (!S.release) {
        check(end.theta);
        check(end.v);
        const IDual* rows[2] = {&end.theta, &end.v};
        for (size_t r = 0; r < 2; ++r) {
          J.f[2 * i + r] = rows[r]->v;
          if (run == 0) {
            J.set(2 * i + r, 2 * i, rows[r]->d[0]);
            J.set(2 * i + r, 2 * i + 1, rows[r]->d[1]);
          } else {
            J.set(2 * i + r, P, rows[r]->d[0]);
          }
        }
      }
      if (border) {
        check(*border);
        const Mpfi v = flip ? Mpfi(-border->v) : border->v;
        J.f[P] = v;
        if (run == 0) {
          J.set(P, 2 * i, flip ? Mpfi(-border->d[0]) : border->d[0]);
          J.set(P, 2 * i + 1, flip ? Mpfi(-border->d[1]) : border->d[1]);
        } else {
          J.set(P, P, flip ? Mpfi(-border->d[0]) : border->d[0]);
        }
      }
    }
  }
  if (!S.release) {
    // g_i = end_i - x_{i+1 mod m}: the -I blocks (m = 1: on the diagonal, where run 0 put
    // d end / d x_0; the sparse sum adds both).
    for (size_t i = 0; i < steps; ++i) {
      const size_t k = (i + 1) % steps;
      J.f[2 * i] -= x[2 * k];
      J.f[2 * i + 1] -= x[2 * k + 1];
      J.set(2 * i, 2 * k, Mpfi(-1, S.bits));
      J.set(2 * i + 1, 2 * k + 1, Mpfi(-1, S.bits));
    }
  }
  return J;
}

// A Krawczyk problem: the unknowns yi and the rows (indices into the variables and rows of
// Jet), and optionally the free parameter (z = p in Z: the orbit alone, for every p in Z).
struct Problem {
  std::vector<size_t> rows, yi;
  bool free_p = false;
  Mpfi Z;
  Mpfr zhat;
  // The preconditioner of a large system (detail::kLargeSystem unknowns or more), computed
  // at the problem's first Krawczyk evaluation (copies share it): its LU costs seconds. Any C
  // keeps the operator sound; a smaller system computes its own at every evaluation, as the
  // proofs of the shorter periods were measured with.
  std::shared_ptr<std::optional<detail::Preconditioner>> C = std::make_shared<std::optional<detail::Preconditioner>>();
};

Problem augmented(const Setup& S) {
  Problem P;
  const size_t N = dim(S);
  if (S.release) {
    P.rows = {N - 1};
    P.yi = {N - 1};
  } else {
    for (size_t i = 0; i < N; ++i) {
      P.rows.push_back(i);
      P.yi.push_back(i);
    }
  }
  return P;
}

Problem orbit_problem(const Setup& S, const Mpfi& Z) {
  Problem P;
  for (size_t i = 0; i + 1 < dim(S); ++i) {
    P.rows.push_back(i);
    P.yi.push_back(i);
  }
  P.free_p = true;
  P.Z = Z;
  P.zhat = Z.mid();
  return P;
}

// The full variable vector (the points, p) from the unknowns and the free parameter.
std::vector<Mpfi> assemble(const Setup& S, const Problem& P, const std::vector<Mpfi>& y, const Mpfi& z) {
  std::vector<Mpfi> x(dim(S), Mpfi(0, S.bits));
  for (size_t k = 0; k < P.yi.size(); ++k) x[P.yi[k]] = y[k];
  if (P.free_p) x.back() = z;
  return x;
}

// f at the centre (thin), in intervals.
std::vector<Mpfi> residual(const Setup& S, const Problem& P, const std::vector<Mpfr>& yhat) {
  std::vector<Mpfi> y;
  for (const Mpfr& v : yhat) y.push_back(thin(v));
  const std::vector<Mpfi> x = assemble(S, P, y, thin(P.zhat));
  std::vector<Mpfi> all;
  if (S.value_fn) {
    all = S.value_fn(x);
  } else {
    const Eval e = evaluate(S, x, x.back());
    all = e.g;
    all.push_back(S.border >= 0 ? oriented(S, e.margins, S.border) : Mpfi(0, S.bits));
  }
  std::vector<Mpfi> f;
  for (size_t r : P.rows) f.push_back(all[r]);
  return f;
}

// K(Y) = y^ - C f(y^) - C F_z (Z - z^) + (I - C F_y(Y, Z)) (Y - y^). If K(Y) lies in the
// interior of Y, then for every z in Z exactly one y in Y has f(y; z) = 0 (no free z: exactly
// one zero in Y), and every such zero lies in K(Y) (periodic_certify.hpp has the argument).
std::vector<Mpfi> krawczyk(const Setup& S, const Problem& P, const std::vector<Mpfr>& yhat, const std::vector<Mpfi>& f,
                           const std::vector<Mpfi>& Y) {
  const size_t n = P.yi.size();
  // The derivatives over hull(Y, y^) (and Z, which holds z^): the mean value form needs them
  // on the segments from y^ to every point of Y, also when tightening has moved Y off y^.
  std::vector<Mpfi> H;
  for (size_t c = 0; c < n; ++c) H.push_back(hull(Y[c], thin(yhat[c])));
  const Jet J = S.jet_fn ? S.jet_fn(assemble(S, P, H, P.Z)) : jet(S, assemble(S, P, H, P.Z));
  // The problem's rows and columns of the Jacobian (entries of one row summed), sparse by
  // columns, and F_z, the free parameter's column.
  std::vector<long> row_of(J.f.size(), -1);
  for (size_t r = 0; r < n; ++r) row_of[P.rows[r]] = static_cast<long>(r);
  auto column = [&](size_t var) {
    std::vector<std::pair<size_t, Mpfi>> out;
    for (const auto& [row, v] : J.col[var]) {
      if (row_of[row] < 0) continue;
      const size_t r = static_cast<size_t>(row_of[row]);
      auto it = std::find_if(out.begin(), out.end(), [&](const auto& e) { return e.first == r; });
      if (it == out.end()) {
        out.emplace_back(r, v);
      } else {
        it->second += v;
      }
    }
    return out;
  };
  detail::SparseColumns A;
  for (size_t c = 0; c < n; ++c) A.push_back(column(P.yi[c]));
  std::vector<Mpfi> Fz(n, Mpfi(0, S.bits));
  if (P.free_p)
    for (const auto& [r, v] : column(J.f.size() - 1)) Fz[r] = v;
  try {
    std::optional<detail::Preconditioner> own;
    std::optional<detail::Preconditioner>& slot = n >= detail::kLargeSystem ? *P.C : own;
    if (!slot) slot.emplace(A, S.bits);
    const detail::Preconditioner& C = *slot;
    return detail::krawczyk_image(C, yhat, f, A, P.free_p ? &Fz : nullptr, P.free_p ? Mpfi(P.Z - thin(P.zhat)) : Mpfi(0, S.bits), Y,
                                  S.bits);
  } catch (const detail::KrawczykFailure& e) {
    throw Fail(e.what());
  }
}

// The box B, proved to hold the one zero of the system, tightened by B <- K(B) n B until no
// component's width halves any more (at most `rounds` times; rounds that shave the last ulps
// cost a Krawczyk evaluation each and change nothing printed): the zero stays in every B.
std::vector<Mpfi> tighten(const Setup& S, const Problem& A, const std::vector<Mpfr>& u, std::vector<Mpfi> B, int rounds = 40) {
  const std::vector<Mpfi> f = residual(S, A, u);
  for (int t = 0; t < rounds; ++t) {
    const std::vector<Mpfi> K = krawczyk(S, A, u, f, B);
    bool shrank = false;
    for (size_t i = 0; i < B.size(); ++i) {
      const Mpfi N = intersect(K[i], B[i]);
      if (N.has_nan()) throw Fail("K(B) n B is empty while tightening (an enclosure is inconsistent)");
      Mpfr half = B[i].width();
      mpfr_div_2ui(half.get(), half.get(), 1, MPFR_RNDN);
      if (mpfr_less_p(N.width().get(), half.get())) shrank = true;
      B[i] = N;
    }
    if (!shrank) break;
  }
  return B;
}

// Newton: y <- y - C f(y), the Krawczyk operator on the thin centre (free p held at z^).
std::vector<Mpfr> newton(const Setup& S, Problem P, std::vector<Mpfr> y) {
  P.Z = thin(P.zhat);
  double last_move = std::numeric_limits<double>::infinity();
  for (int it = 0; it < 60; ++it) {
    std::vector<Mpfi> Y;
    for (const Mpfr& v : y) Y.push_back(thin(v));
    const std::vector<Mpfi> K = krawczyk(S, P, y, residual(S, P, y), Y);
    // Converged when every component moved by at most a few ulps, or when the moves stop
    // shrinking (the last bits cycle: shooting's double preconditioner times the residual's
    // rounding can exceed a few ulps). The proofs never rely on this point being accurate.
    bool same = true;
    double move = 0;
    for (size_t i = 0; i < y.size(); ++i) {
      const Mpfr nx = K[i].mid();
      Mpfr tol = abs(y[i]) + 1;
      const Mpfr d = abs(Mpfr(nx - y[i]));
      move = std::max(move, Mpfr(d / tol).to_double());
      mpfr_mul_2si(tol.get(), tol.get(), -(S.bits - 6), MPFR_RNDN);
      if (d > tol) same = false;
      y[i] = nx;
    }
    if (same || (it >= 2 && move > last_move / 16)) break;
    last_move = move;
  }
  return y;
}

bool all_inside(const std::vector<Mpfi>& K, const std::vector<Mpfi>& Y) {
  for (size_t i = 0; i < K.size(); ++i)
    if (!strictly_inside(K[i], Y[i])) return false;
  return true;
}

// Epsilon inflation around y^ until K(Y) lies in the interior of Y (a small box), then
// K(Y) n Y repeatedly: the tight enclosure of the unique zero in the proof box.
std::vector<Mpfi> prove_tight(const Setup& S, const Problem& P, const std::vector<Mpfr>& yhat) {
  const std::vector<Mpfi> f = residual(S, P, yhat);
  try {
    return detail::prove_by_inflation(yhat, f, [&](const std::vector<Mpfi>& Y) { return krawczyk(S, P, yhat, f, Y); }, S.bits, 8).Y;
  } catch (const detail::KrawczykFailure& e) {
    throw Fail(e.what());
  }
}

// The period-Q point x(p) at one parameter value p (thin), enclosed tightly.
std::vector<Mpfi> orbit_at(const Setup& S, const Mpfi& p, const std::vector<Mpfr>& guess) {
  Problem P = orbit_problem(S, p);
  return prove_tight(S, P, newton(S, P, guess));
}

// The branch side's reference: events, pieces and margins from the step itself (Mpfr).
struct Reference {
  State<Mpfr> start;
  std::vector<StepResult<Mpfr>> steps;
};

Piece piece_of(const Model<Mpfr>& m, const State<Mpfr>& s, const StepResult<Mpfr>& r) {
  if (r.kind == EventKind::ride) throw Fail("a step of the orbit rides the wall (zero relative speed): not supported");
  if (r.corner) throw Fail("an impact of the branch side's orbit is exactly at a wall corner");
  Piece pc;
  pc.from_segment = s.knot >= 0 ? s.knot : m.wall.segment_of(s.theta);
  pc.sticks = r.kind == EventKind::sticking;
  pc.segment = pc.sticks ? r.stick_segment : r.segment;
  const Mpfr& th = pc.sticks ? r.stuck_theta : r.next.theta;
  Mpfr tau = r.tau;
  if (pc.sticks) {
    Mpfr ride = r.next.theta - r.stuck_theta;
    if (ride.to_double() < 0) ride = ride + 1;
    tau = tau - ride;
  }
  pc.periods = std::lround(Mpfr(s.theta + tau - th).to_double());
  if (pc.sticks) {
    // The ride after the collapse must end at a release (a downward turn). Under the paper's
    // convention (--downward-sticking paper, the models that stick) the particle rides through
    // an upward turn to the next downward one (ImpactMap::ride), so the release state is
    // still exact; with the impact convention an upward turn is a collision (r.corner), whose
    // outcome this closed form does not model.
    if (r.passed_upward_turn && r.corner)
      throw Fail("the sticking step's ride ends in a collision at an upward turn (--downward-sticking impact): not supported");
    pc.release_knot = r.next.knot;
    if (pc.release_knot < 0) throw Fail("the sticking step does not end at a wall knot");
  }
  return pc;
}

// A decimal parameter value, enclosed at `bits`.
Mpfi parameter_interval_of(const Decimal& p, long bits) {
  Mpfi x(bits);
  x.set_decimal(p.text());
  return x;
}

// The q steps of the step itself from x, restarted at the release state that ends the
// sticking step if the orbit sticks (such orbits are the release state's orbit).
Reference steps_from(const BranchEndQuestion& e, const Model<Mpfr>& m, const State<Mpfr>& x) {
  const ImpactMap<Mpfr> map(m);
  Reference ref;
  State<Mpfr> s = x;
  for (long i = 0; i < e.period; ++i) {
    ref.steps.push_back(map.step(s));
    s = ref.steps.back().next;
  }
  long last_stick = -1;
  for (long i = 0; i < e.period; ++i)
    if (ref.steps[i].kind != EventKind::impact) last_stick = i;
  ref.start = x;
  if (last_stick >= 0) {
    ref.start = ref.steps[last_stick].next;
    ref.steps.clear();
    s = ref.start;
    for (long i = 0; i < e.period; ++i) {
      ref.steps.push_back(map.step(s));
      s = ref.steps.back().next;
      if (ref.steps.back().kind != EventKind::impact && i + 1 < e.period)
        throw Fail("the release state's orbit sticks before step " + std::to_string(e.period) +
                   " (its minimal period is smaller)");
    }
    if (s.knot != ref.start.knot) throw Fail("the release state's orbit does not return to it");
  }
  return ref;
}

// The branch side's orbit by the step's own Newton (find_periodic at Mpfr) at p from the last
// point; nothing when Newton does not converge there.
std::optional<Reference> newton_reference(const BranchEndQuestion& e, const Decimal& p, long bits) {
  const Model<Mpfr> m = make_model<Mpfr>(with_parameter(e.model, e.vary, p), bits);
  const PeriodicOrbit<Mpfr> o = find_periodic(m, e.period, make_state<Mpfr>(m, e.last_point));
  // An orbit of a divisor of the period is a fixed point of P^Q too (the period-10 branch at
  // 18.1578, veldep c = 1000: Newton from its last point went to a period-2 orbit, whose own
  // border collision is at 24.595): not the branch's.
  if (!o.converged || o.points.empty() || o.minimal_period != e.period) return std::nullopt;
  return steps_from(e, m, o.points[0]);
}

// The ImpactMap's own interval steps from x at parameter p: true when every branch is
// decided and the events are those of the pieces (kind, segment, corner), false when some
// branch is undecided; throws when decided otherwise.
// With shooting (m > 1) each step starts from its own point's box x_i.
bool step_confirms(const Setup& S, const std::vector<Mpfi>& x, const Mpfi& p) {
  const ImpactMap<Mpfi> map(at(S, p));
  State<Mpfi> s = S.release ? S.R : State<Mpfi>{x[0], x[1]};
  try {
    for (size_t i = 0; i < S.pieces.size(); ++i) {
      if (S.m > 1) s = State<Mpfi>{x[2 * i], x[2 * i + 1]};
      const StepResult<Mpfi> r = map.step(s);
      const int seg = r.kind == EventKind::sticking ? r.stick_segment : r.segment;
      if (r.kind != S.events[i].kind || seg != S.events[i].segment || r.corner != S.events[i].corner)
        throw Fail("the step's own events at the branch side's check point differ from the branch side's at step " +
                   std::to_string(i) + " (the step: " + name(r.kind) + " on segment " + std::to_string(seg) +
                   (r.corner ? " at a corner" : "") + "; the branch side: " + name(S.events[i].kind) + " on segment " +
                   std::to_string(S.events[i].segment) + (S.events[i].corner ? " at a corner" : "") + ")");
      s = r.next;
    }
  } catch (const Undecided&) {
    return false;
  }
  return true;
}

// The half width of the parameter box Z = [phat - w, phat + w] at the k-th try of a proof,
// from w0 (the interval given): smaller by 16 per try, then by 2^12 from the seventh (each try
// of a long period costs q interval steps with derivatives), down to about
// 2^(48 - bits) (|phat| + 1); nullopt below that. One schedule for the border-collision and
// period-doubling proofs.
std::optional<Mpfr> z_half_width(const Mpfr& w0, const Mpfr& phat, long bits, int k) {
  Mpfr w(bits);
  mpfr_div_2si(w.get(), w0.get(), k < 6 ? 4 * k : 24 + 12 * (k - 6), MPFR_RNDN);
  if (k >= 6) {
    Mpfr least = abs(phat) + 1;
    mpfr_mul_2si(least.get(), least.get(), 48 - bits, MPFR_RNDN);
    if (w < least) return std::nullopt;
  }
  return w;
}

struct Proved {
  std::vector<Mpfi> Y;   // the orbit box (isolated)
  Mpfi Z;                // the parameter interval
  Mpfi pstar;            // the tight enclosure of a*
  std::vector<Mpfi> xstar;
};

// shooting: the unknowns are all Q points (Setup::m = Q) instead of the first alone.
void run(const BorderCollisionQuestion& q, BorderCollisionCertificate& c, std::vector<State<Mpfi>>& orbit_out,
         bool shooting) {
  const BranchEndQuestion& e = q.end;
  const long bits = q.bits;
  if (e.model.law == Law::veldep && e.model.veldep_collapse)
    throw Fail("--veldep-collapse decides sticking by a one-sided bound: no analytic margin");
  if (!(e.lo.value() < e.hi.value())) throw Fail("the interval next to a* is empty");
  Setup S;
  S.par = e.vary;
  S.bits = bits;
  S.high = e.high_end;
  // The reference orbit is taken at the interval's far end pf: the interval's end next to a*
  // comes from a double bracket, which may lie past a* (issue 23: by 1.8e-11 at the veldep
  // period-7 end when it was bisected; by 2.6e-14 at the unstable one's grazing end), where
  // the branch's orbit no longer exists.
  const Decimal& pb = e.high_end ? e.hi : e.lo;  // the end next to a*
  const Decimal& pf = e.high_end ? e.lo : e.hi;  // the far end, on the branch side
  // The events: from the step's Newton orbit at pf, or, where that Newton fails (an
  // unstable orbit moves fast with the parameter: the last point is far from the orbit at
  // pf), from the steps of the last point itself at pb, confirmed below at pf.
  std::optional<Reference> found = newton_reference(e, pf, bits);
  const bool via_piece = !found;
  const Model<Mpfr> mref = make_model<Mpfr>(with_parameter(e.model, e.vary, pf), bits);
  if (via_piece) {
    const Model<Mpfr> mb = make_model<Mpfr>(with_parameter(e.model, e.vary, pb), bits);
    found = steps_from(e, mb, make_state<Mpfr>(mb, e.last_point));
  }
  Reference ref = *found;
  {
    State<Mpfr> s = ref.start;
    for (const StepResult<Mpfr>& r : ref.steps) {
      S.pieces.push_back(piece_of(mref, s, r));
      S.events.push_back(step_event(r, mref.wall.smooth()));
      s = r.next;
    }
  }
  S.release = S.pieces.back().sticks;
  c.through_release = S.release;
  if (shooting && S.release) throw Fail("an orbit through the release state has no points to shoot from (its start is exact)");
  S.m = shooting ? static_cast<int>(S.pieces.size()) : 1;
  // The reference orbit's points after the first (the start of step i + 1 is step i's image).
  auto nexts = [](const Reference& r) {
    std::vector<State<Mpfr>> out;
    for (const StepResult<Mpfr>& st : r.steps) out.push_back(st.next);
    return out;
  };
  S.base = interval_model(with_parameter(e.model, e.vary, pf), bits);
  if (S.release) {
    const int k = ref.start.knot;
    if (k < 0) throw Fail("the release state is not at a wall knot");
    S.R = release_state(S.base, k);
  }
  if (via_piece) {
    // Newton on the piece at pf, then the step itself from its solution: the same events.
    State<Mpfr> x = ref.start;
    if (!S.release) {
      const std::vector<Mpfr> y = newton(S, orbit_problem(S, parameter_of(S.base, S.par)), point_unknowns(S, ref.start, nexts(ref)));
      x = State<Mpfr>{y[0], y[1]};
    }
    const Reference at_pf = steps_from(e, mref, x);
    for (size_t i = 0; i < at_pf.steps.size(); ++i)
      if (!step_event(at_pf.steps[i], mref.wall.smooth()).same_piece(S.events[i]))
        throw Fail("the branch side's events at " + std::string(name(e.vary)) + " = " + pf.text() +
                   " differ from those of the last point at " + pb.text());
    ref = at_pf;
  }
  // Each step departs from the segment the previous impact landed on (or from the release
  // knot): the margins of step i's impact then place step i+1's start on its segment.
  for (size_t i = 0; i < S.pieces.size(); ++i) {
    const Piece& prev = S.pieces[(i + S.pieces.size() - 1) % S.pieces.size()];
    const int landed = prev.sticks ? prev.release_knot : prev.segment;
    if (S.pieces[i].from_segment != landed)
      throw Fail("the orbit's steps do not chain: step " + std::to_string(i) + " departs from segment " +
                 std::to_string(S.pieces[i].from_segment) + ", the impact before it is on segment " + std::to_string(landed));
  }
  c.events = event_text(S.events);

  // The margins at the reference and at a second branch-side value pf2 = pf + (pf - pb),
  // farther from a*: their orientation, and the border (the margin given, or the one whose
  // zero, extrapolated linearly, is nearest).
  const Mpfi Pf = parameter_of(S.base, S.par);
  const Mpfi Pb = parameter_interval_of(pb, bits);
  const State<Mpfi> xf{thin(ref.start.theta), thin(ref.start.v)};
  std::vector<Mpfi> mf;
  {
    const ImpactMap<Mpfi> map(at(S, Pf));
    // The closed-form piece against the step: the same orbit end (shooting: every step's).
    auto compare = [&](const State<Mpfi>& end, const State<Mpfr>& want) {
      const double d = std::max(std::fabs(Mpfr(end.theta.mid() - want.theta).to_double()),
                                std::fabs(Mpfr(end.v.mid() - want.v).to_double()) / std::max(1.0, std::fabs(want.v.to_double())));
      if (!(d < std::ldexp(1.0, -static_cast<int>(bits) / 2)))
        throw Fail("the closed-form piece does not reproduce the step's orbit (off by " + std::to_string(d) + ")");
    };
    if (S.m == 1) {
      compare(piece_orbit(map, S.release ? S.R : xf, S.pieces, &mf, &S.ids), ref.steps.back().next);
    } else {
      State<Mpfr> from = ref.start;
      for (size_t i = 0; i < S.pieces.size(); ++i) {
        compare(piece_step(map, State<Mpfi>{thin(from.theta), thin(from.v)}, S.pieces[i], static_cast<long>(i), &mf, &S.ids),
                ref.steps[i].next);
        from = ref.steps[i].next;
      }
    }
  }
  for (const Mpfi& x : mf) S.sign.push_back(x.mid().to_double() >= 0 ? 1 : -1);
  {
    const mpq_class p2 = pf.value() + (pf.value() - pb.value());
    const Decimal d2 = *Decimal::parse(exact_decimal(p2));
    std::vector<Mpfi> m2;
    const Mpfi P2 = parameter_interval_of(d2, bits);
    if (S.release) {
      m2 = evaluate(S, {}, P2).margins;
    } else {
      const std::vector<Mpfr> y2 = newton(S, orbit_problem(S, P2), point_unknowns(S, ref.start, nexts(ref)));
      std::vector<Mpfi> x2;
      for (const Mpfr& y : y2) x2.push_back(thin(y));
      m2 = evaluate(S, x2, P2).margins;
    }
    const double dp = mpq_class(pf.value() - pb.value()).get_d();
    std::vector<double> dist(mf.size(), std::numeric_limits<double>::infinity());
    double best = std::numeric_limits<double>::infinity();
    for (size_t i = 0; i < mf.size(); ++i) {
      if (S.ids[i].kind == kDeparture) continue;
      if (q.margin && S.ids[i].kind != static_cast<int>(*q.margin)) continue;
      const double vf = std::fabs(mf[i].mid().to_double()), v2 = std::fabs(m2[i].mid().to_double());
      if (!(vf < v2)) continue;  // not moving towards 0 at the end
      dist[i] = vf * std::fabs(dp) / (v2 - vf);  // linear extrapolation to its zero
      best = std::min(best, dist[i]);
    }
    // Margins that vanish together (an impact at a knot and a flight's clearance at that
    // knot): the knot distance is the border, the clearance follows by an identity
    // (coincident_clearance).
    for (size_t i = 0; i < mf.size(); ++i) {
      if (!(dist[i] <= best * (1 + 1e-3))) continue;
      if (S.border < 0 || (S.ids[i].kind == static_cast<int>(Margin::knot) &&
                           S.ids[S.border].kind != static_cast<int>(Margin::knot)))
        S.border = static_cast<int>(i);
    }
    if (S.border < 0) throw Fail("no margin of the branch side's orbit decreases towards 0 at this end");
  }
  const MarginId& bid = S.ids[S.border];
  c.margin = static_cast<Margin>(bid.kind);
  c.step = static_cast<int>(bid.step);
  c.knot = bid.knot;
  c.margin_text = margin_words(bid);

  // Newton on the augmented system from the branch side's orbit at pf.
  const Problem A = augmented(S);
  const Mpfr pbr = Pb.mid(), pfr = Pf.mid();
  std::vector<Mpfr> u = S.release ? std::vector<Mpfr>{} : point_unknowns(S, ref.start, nexts(ref));
  u.push_back(pfr);
  u = newton(S, A, u);
  const Mpfr phat = u.back();
  const Mpfr w0 = abs(Mpfr(pbr - pfr));
  {
    const Mpfr gap = abs(Mpfr(phat - pbr));
    if (!(mpfr_number_p(phat.get())) || gap.to_double() > 100 * w0.to_double())
      throw Fail("Newton on the augmented system goes to " + std::string(name(S.par)) + " = " + text(phat) +
                 ", far from the interval given (no border collision of this margin next to it)");
  }

  // The proof over Y x Z, Z = [phat - w, phat + w], w shrinking (z_half_width). Long periods
  // need the small Z: the interval evaluation of q steps over Y widens it by up to the
  // product of the steps' derivative norms (a period-66 end's impact speeds straddled 0 over
  // the box of a 1e-12 wide Z), and Y is as wide as the orbit moves across Z.
  std::optional<Proved> proved;
  std::string why;
  for (int k = 0; !proved; ++k) {
    const std::optional<Mpfr> w = z_half_width(w0, phat, bits, k);
    if (!w) break;
    const Mpfr zlo = phat - *w, zhi = phat + *w;
    Proved pr;
    pr.Z = Mpfi(zlo, zhi);
    try {
      if (S.release) {
        std::vector<Mpfi> B = {pr.Z};
        Problem P = A;
        const std::vector<Mpfi> K = krawczyk(S, P, u, residual(S, P, u), B);
        if (!all_inside(K, B)) throw Fail("K(Z) is not inside Z");
        for (int t = 0; t < 40; ++t) {
          const std::vector<Mpfi> K2 = krawczyk(S, P, u, residual(S, P, u), B);
          const Mpfi N = intersect(K2[0], B[0]);
          if (N.has_nan()) throw Fail("K(B) n B is empty while tightening (an enclosure is inconsistent)");
          const bool shrank = mpfr_less_p(N.width().get(), B[0].width().get());
          B[0] = N;
          if (!shrank) break;
        }
        pr.pstar = B[0];
      } else {
        const std::vector<Mpfr> xg(u.begin(), u.end() - 1);
        const size_t ny = xg.size();
        const std::vector<Mpfi> ylo = orbit_at(S, thin(zlo), xg), yhi = orbit_at(S, thin(zhi), xg);
        // Y: the hull of the two ends' orbits and the centre, inflated until both proofs hold.
        std::vector<Mpfi> Y(ny);
        std::vector<Mpfr> rad(ny), mid(ny);
        for (size_t i = 0; i < ny; ++i) {
          const Mpfi h = hull(hull(ylo[i], yhi[i]), thin(u[i]));
          mid[i] = h.mid();
          rad[i] = h.width();
          Mpfi ulps = abs(thin(mid[i])) + 1;
          mpfi_mul_2si(ulps.get(), ulps.get(), -(bits - 16));
          rad[i] = rad[i] + ulps.upper();
        }
        bool ok = false;
        for (int t = 0; t < 6 && !ok; ++t) {
          for (size_t i = 0; i < ny; ++i) Y[i] = Mpfi(Mpfr(mid[i] - rad[i]), Mpfr(mid[i] + rad[i]));
          Problem O = orbit_problem(S, pr.Z);
          O.zhat = phat;
          const std::vector<Mpfi> KO = krawczyk(S, O, xg, residual(S, O, xg), Y);
          std::vector<Mpfi> B = Y;
          B.push_back(pr.Z);
          const std::vector<Mpfi> KA = krawczyk(S, A, u, residual(S, A, u), B);
          ok = all_inside(KO, Y) && all_inside(KA, B);
          if (!ok)
            for (size_t i = 0; i < ny; ++i) rad[i] = rad[i] * 4;
        }
        if (!ok) throw Fail("the Krawczyk operators did not map the box Y x Z into itself");
        pr.Y = Y;
        std::vector<Mpfi> B0 = Y;
        B0.push_back(pr.Z);
        const std::vector<Mpfi> B = tighten(S, A, u, B0);
        pr.pstar = B.back();
        pr.xstar.assign(B.begin(), B.end() - 1);
      }
      proved = pr;
    } catch (const Fail& f) {
      why = f.what();
    } catch (const Undecided& un) {
      why = std::string("undecided: ") + un.what();
    }
  }
  if (!proved) throw Fail("no parameter interval around a* certified (" + why + ")");
  const Proved& pr = *proved;
  const Mpfr zlo = pr.Z.lower(), zhi = pr.Z.upper();
  const Mpfr alo = pr.pstar.lower(), ahi = pr.pstar.upper();
  // The branch side [zb, a*_lo] (high end) or [a*_hi, zb] (low end), and beyond.
  const Mpfi side = S.high ? Mpfi(zlo, alo) : Mpfi(ahi, zhi);
  const Mpfi beyond = S.high ? Mpfi(ahi, zhi) : Mpfi(zlo, alo);
  const Mpfr& zb = S.high ? zlo : zhi;
  const Mpfr& zx = S.high ? zhi : zlo;

  // 3. The border margin's sign at both ends of Z, at thin parameters (with the uniqueness
  // of 1-2 and continuity it then has one sign on each side of a*: an interval evaluation
  // over a whole side would straddle 0 next to a*).
  // x(p) enclosed at one p: its box must lie in Y, where x(p) is the unique orbit.
  const std::vector<Mpfr> xg(u.begin(), u.end() - 1);  // the orbit's unknowns at the augmented Newton point
  auto inside_Y = [&](const std::vector<Mpfi>& x) {
    for (size_t i = 0; i < x.size(); ++i)
      if (!pr.Y[i].contains(x[i])) return false;
    return true;
  };
  auto orbit_in_Y = [&](const Mpfi& p) {
    const std::vector<Mpfi> x = orbit_at(S, p, xg);
    if (!inside_Y(x)) throw Fail("an orbit enclosed at one parameter value lies outside Y");
    return x;
  };
  auto border_sign = [&](const Mpfr& p) {
    std::vector<Mpfi> x;
    if (!S.release) x = orbit_in_Y(thin(p));
    const Eval ev = evaluate(S, x, thin(p));
    return oriented(S, ev.margins, S.border);
  };
  const Mpfi zero(0, bits);
  if (Tr::lt(zero, border_sign(zb)) != Truth::yes)
    throw Fail("the border margin is not certainly > 0 at the branch side's end of Z, " + std::string(name(S.par)) + " = " + text(zb));
  if (Tr::lt(border_sign(zx), zero) != Truth::yes)
    throw Fail("the border margin is not certainly < 0 at the far end of Z, " + std::string(name(S.par)) + " = " + text(zx));
  // 4. Every other margin keeps its branch-side sign on the branch side. One interval
  // evaluation over Y x side wraps badly for long periods (the box Y was inflated for the
  // proof, and its width grows through q steps: a period-11 end had its clearances straddle
  // 0 by +-0.3 where they are 0.1), so the side is cut into pieces P: over each, the
  // parametric Krawczyk operator (unknowns the orbit, p free in P) encloses x(P) in a small
  // box; if that box lies inside Y it holds the orbit unique in Y, and the margins are
  // evaluated over it. A piece where a margin is undecided is halved, at most 511 times.
  {
    // The first margin (other than the border) not certainly of its branch-side sign over
    // the orbit box X and parameters P, or -1.
    auto undecided_margin = [&](const std::vector<Mpfi>& X, const Mpfi& P) -> long {
      const Eval ev = evaluate(S, X, P);
      std::optional<std::vector<IDual>> slopes;
      for (size_t i = 0; i < ev.margins.size(); ++i) {
        if (static_cast<int>(i) == S.border) continue;
        if (Tr::lt(zero, oriented(S, ev.margins, i)) == Truth::yes) continue;
        // Orbits through the release state (the parameter the only variable): a margin that
        // also tends to 0 at a* (the knot at a = 32, reached as the flight grazes that
        // corner) is positive on the side if it is monotone there (its derivative over the
        // side has one sign) and positive at both of the side's ends.
        bool ok = implied_by_entry(S, ev.margins, i) || coincident_clearance(S, ev.margins, i, P);
        if (!ok && S.release) {
          if (!slopes) slopes = margin_slopes(S, P);
          const Mpfi& d = (*slopes)[i].d[0];
          const bool monotone = Tr::lt(zero, d) == Truth::yes || Tr::lt(d, zero) == Truth::yes;
          if (monotone) {
            const Eval e1 = evaluate(S, {}, thin(P.lower())), e2 = evaluate(S, {}, thin(P.upper()));
            ok = Tr::lt(zero, oriented(S, e1.margins, i)) == Truth::yes && Tr::lt(zero, oriented(S, e2.margins, i)) == Truth::yes;
          }
        }
        if (!ok) return static_cast<long>(i);
      }
      return -1;
    };
    // x(P) in a small box inside Y, or Y itself.
    auto orbit_over = [&](const Mpfi& P) {
      std::vector<Mpfi> X = pr.Y;
      try {
        Problem O = orbit_problem(S, P);
        const std::vector<Mpfi> T = prove_tight(S, O, newton(S, O, xg));
        if (inside_Y(T)) X = T;
      } catch (const Fail&) {
      } catch (const Undecided&) {
      }
      return X;
    };
    std::vector<Mpfi> todo = {side};
    int evaluations = 0;
    while (!todo.empty()) {
      const Mpfi P = todo.back();
      todo.pop_back();
      const long i = undecided_margin(S.release ? std::vector<Mpfi>{} : orbit_over(P), P);
      if (i < 0) continue;
      if (S.release || ++evaluations > 511)
        throw Fail("on the branch side, " + margin_words(S.ids[static_cast<size_t>(i)]) +
                   " is not certainly of its branch-side sign over the proof's box (a second margin near 0 at a*?)");
      const Mpfr m = P.mid();
      todo.push_back(Mpfi(P.lower(), m));
      todo.push_back(Mpfi(m, P.upper()));
    }
  }
  // 5. The step's own events at a branch-side point next to a*: a short decimal, enclosed
  // (the check covers its enclosure, so the decimal printed is a point checked).
  std::optional<std::string> checked;
  {
    // The first point is the enclosure's width away from it, at least a few ulps: an a*
    // found exactly (the corner touchdown at a = 8: [8, 8]) has width 0, and a* itself is
    // not on the branch side.
    Mpfr width = Mpfr(ahi - alo);
    Mpfr ulps(bits);
    mpfr_mul_2si(ulps.get(), Mpfr(abs(alo) + 1).get(), 8 - bits, MPFR_RNDU);
    if (width.to_double() < ulps.to_double()) width = ulps;
    for (int k : {0, 8, 16, 32, 48, 64, 80, 96}) {
      Mpfr d(bits);
      mpfr_mul_2si(d.get(), width.get(), k, MPFR_RNDN);
      const Mpfr pc = S.high ? Mpfr(alo - d) : Mpfr(ahi + d);
      // The decimal rounded away from a*, so that it stays on the branch side.
      const std::string dec = S.high ? Tr::lower_string(thin(pc)) : Tr::upper_string(thin(pc));
      Mpfi Pc(bits);
      Pc.set_decimal(dec);
      if (!side.contains(Pc)) break;
      std::vector<Mpfi> x;
      if (!S.release) {
        try {
          x = orbit_in_Y(Pc);
        } catch (const Fail&) {
          continue;
        } catch (const Undecided&) {
          continue;
        }
      }
      if (step_confirms(S, x, Pc)) {
        checked = dec;
        break;
      }
    }
    if (!checked) throw Fail("the step's own interval evaluation did not decide the events next to a*");
  }

  // The certificate.
  c.certified = true;
  c.shooting = S.m > 1;
  c.lo = to_q(alo);
  c.hi = to_q(ahi);
  c.parameter = enclosure(pr.pstar);
  c.width = Mpfr(ahi - alo).to_double();
  c.z_lo = to_q(zlo);
  c.z_hi = to_q(zhi);
  c.checked_at = Decimal::parse(*checked)->value();
  if (S.m > 1) {
    for (size_t i = 0; i + 1 < pr.xstar.size(); i += 2) orbit_out.push_back(State<Mpfi>{pr.xstar[i], pr.xstar[i + 1]});
  } else {
    const ImpactMap<Mpfi> map(at(S, pr.pstar));
    std::vector<State<Mpfi>> pts;
    piece_orbit(map, S.release ? S.R : State<Mpfi>{pr.xstar[0], pr.xstar[1]}, S.pieces, static_cast<std::vector<Mpfi>*>(nullptr),
                nullptr, &pts);
    orbit_out = pts;
  }
  for (const State<Mpfi>& x : orbit_out) c.orbit.push_back({enclosure(x.theta), enclosure(x.v)});
  // A clearance at the knot where the flight enters its impact segment takes the impact speed
  // with it where the relative velocity there is 0 too (D = g'^2 + 2 a c, implied_by_entry):
  // a corner touchdown. Say so where D's enclosure at a* holds 0.
  if (bid.kind == static_cast<int>(Margin::clearance) && bid.knot == S.pieces[static_cast<size_t>(bid.step)].segment) {
    const Eval at_star = evaluate(S, S.release ? std::vector<Mpfi>{} : pr.xstar, pr.pstar);
    for (size_t k = 0; k < S.ids.size(); ++k)
      if (S.ids[k].step == bid.step && S.ids[k].kind == static_cast<int>(Margin::speed) && at_star.margins[k].contains(Mpfi(0, bits)))
        c.margin_text += std::string(" (and with it the impact speed: a corner touchdown; at a* the squared speed ") +
                         (Tr::is_zero(at_star.margins[k]) == Truth::yes ? "is exactly 0" : "is enclosed in an interval holding 0") + ")";
  }
  const std::string p = name(S.par);
  std::ostringstream s;
  // Short decimals, rounded so that each claim stays true: the branch side's interval
  // inwards, a*'s enclosure outwards, the far end of "beyond" towards a*.
  const std::string up_zlo = Tr::upper_string(thin(zlo)), down_zhi = Tr::lower_string(thin(zhi));
  const std::string side_text = S.high ? "[" + up_zlo + ", " + c.parameter.lo + ")" : "(" + c.parameter.hi + ", " + down_zhi + "]";
  const std::string beyond_text = S.high ? "(a*, " + down_zhi + "]" : "[" + up_zlo + ", a*)";
  s << "For every " << p << " in " << side_text << " the map has a period-" << e.period << " "
    << (S.release ? "orbit through the release state" : "orbit (unique in its box)") << " with events " << c.events
    << " (every margin of every step certainly of its branch-side sign; the interval step itself takes these events at "
    << p << " = " << *checked << "); at exactly one a* in [" << c.parameter.lo << ", " << c.parameter.hi
    << "] (width " << c.width << ") " << c.margin_text << " reaches 0 (> 0 on the branch side); for " << p << " in "
    << beyond_text << " that margin is < 0 on the branch's piece: no period-" << e.period << " orbit with events " << c.events
    << (S.release ? " through the release state" : " in the box")
    << ". Proved by the Krawczyk operator on the augmented system (the orbit equations of the branch side's piece, "
       "extended analytically across the border, and the margin = 0"
    << (S.m > 1 ? "; multiple shooting: the unknowns are all " + std::to_string(S.m) + " orbit points and the parameter" : "")
    << ") at " << bits << " bits.";
  c.statement = s.str();
}


// ---- Period doubling ----------------------------------------------------------------

// Second derivatives: Dual<IDual>, the outer derivative along one variable e of (theta, v,
// p), the inner ones along (theta, v). Dual's shortcut for constant operands (outer
// derivative enclosed by [0, 0]) is exact here because every box is wide in all three
// variables: a first derivative that is 0 on the whole open box has zero derivatives there.
using IDual2 = Dual<IDual>;

State<IDual> orbit_dual(const Model<Mpfi>& base, Parameter par, const Mpfi x[3], long q, std::vector<StepEvent>* events) {
  Model<IDual> dm = convert_model<IDual>(base, [](const Mpfi& y) { return IDual(y); });
  dm = with_parameter(dm, par, IDual(x[2]));
  const ImpactMap<IDual> map(std::move(dm));
  State<IDual> s{IDual::variable(x[0], 0), IDual::variable(x[1], 1)};
  for (long i = 0; i < q; ++i) {
    StepResult<IDual> r;
    try {
      r = map.step(s);
    } catch (const Undecided& u) {
      throw Fail("step " + std::to_string(i) + " of the period is undecided over the box: " + u.what());
    }
    if (r.kind != EventKind::impact) throw Fail("the orbit sticks: no multiplier -1 (superstable)");
    if (events) events->push_back(step_event(r, base.wall.smooth()));
    s = r.next;
  }
  return s;
}

// (P^Q(x) - x, det(DP^Q(x) + I)) at a point, in intervals.
// sigma = +1: det(DP^q + I) (a multiplier -1, period doubling); -1: det(DP^q - I) (a
// multiplier +1, fold).
std::vector<Mpfi> pd_value(const Model<Mpfi>& base, Parameter par, long q, const std::vector<Mpfi>& x, int sigma = 1) {
  const State<IDual> e = orbit_dual(base, par, x.data(), q, nullptr);
  const Mpfi J00 = e.theta.d[0] + sigma, J01 = e.theta.d[1], J10 = e.v.d[0], J11 = e.v.d[1] + sigma;
  return {e.theta.v - x[0], e.v.v - x[1], J00 * J11 - J01 * J10};
}

Jet pd_jet(const Model<Mpfi>& base, Parameter par, long q, const std::vector<Mpfi>& x, int sigma = 1) {
  Jet J(3);
  const long bits = x[0].bits();
  for (int var = 0; var < 3; ++var) {
    auto lift = [&](const Mpfi& y) { return IDual2(IDual(y)); };
    Model<IDual2> dm = convert_model<IDual2>(base, lift);
    const IDual one(Mpfi(1, bits)), zero(Mpfi(0, bits));
    dm = with_parameter(dm, par, IDual2(IDual(x[2]), var == 2 ? one : zero, zero));
    const ImpactMap<IDual2> map(std::move(dm));
    State<IDual2> s{IDual2(IDual::variable(x[0], 0), var == 0 ? one : zero, zero),
                    IDual2(IDual::variable(x[1], 1), var == 1 ? one : zero, zero)};
    for (long i = 0; i < q; ++i) {
      try {
        s = map.step(s).next;
      } catch (const Undecided& u) {
        throw Fail("step " + std::to_string(i) + " of the period is undecided over the box: " + u.what());
      }
    }
    const IDual2* rows[2] = {&s.theta, &s.v};
    Mpfi Jm[2][2], dJ[2][2];
    for (int r = 0; r < 2; ++r) {
      const IDual2& y = *rows[r];
      if (!ScalarTraits<IDual>::derivatives_finite(y.v) || !ScalarTraits<IDual>::is_finite(y.d[0]) ||
          !ScalarTraits<IDual>::derivatives_finite(y.d[0]))
        throw Fail("the second-derivative enclosure over the box is not finite");
      J.f[r] = y.v.v - x[r];
      J.set(static_cast<size_t>(r), static_cast<size_t>(var), var == r ? Mpfi(y.d[0].v - 1) : y.d[0].v);
      for (int k = 0; k < 2; ++k) {
        Jm[r][k] = y.v.d[k];
        dJ[r][k] = y.d[0].d[k];
      }
    }
    Jm[0][0] += Mpfi(sigma, bits);
    Jm[1][1] += Mpfi(sigma, bits);
    J.f[2] = Jm[0][0] * Jm[1][1] - Jm[0][1] * Jm[1][0];
    J.set(2, static_cast<size_t>(var), dJ[0][0] * Jm[1][1] + Jm[0][0] * dJ[1][1] - dJ[0][1] * Jm[1][0] - Jm[0][1] * dJ[1][0]);
  }
  return J;
}

// Multiple shooting for the smooth systems (long periods, where the composed steps' box
// straddles a knot): unknowns the Q points and p; rows F(x_i) - x_{i+1 mod Q} and
// h = det(M_{Q-1} ... M_0 + sigma I), M_i = DF(x_i; p), every step over its own point's box.
// Jacobian of h: d det(A) = tr(adj(A) dA), and along a variable t of step i,
// dA/dt = L_i (dM_i/dt) R_i with L_i = M_{Q-1} ... M_{i+1}, R_i = M_{i-1} ... M_0, so
// dh/dt = tr(W_i dM_i/dt), W_i = R_i adj(A) L_i.
// analysis/jacobian.hpp's 2x2 matrix and product, entries by index here.
using Mat2I = Mat2<Mpfi>;

Mpfi& el(Mat2I& m, size_t r, size_t k) { return r == 0 ? (k == 0 ? m.a11 : m.a12) : (k == 0 ? m.a21 : m.a22); }
const Mpfi& el(const Mat2I& m, size_t r, size_t k) { return el(const_cast<Mat2I&>(m), r, k); }

// One step's image and Jacobian over the box x_i at p (every branch decided over the box).
void step_jacobian(const Model<Mpfi>& base, Parameter par, const Mpfi& th, const Mpfi& v, const Mpfi& p, long i,
                   std::array<Mpfi, 2>& F, Mat2I& M, StepEvent* event = nullptr) {
  Model<IDual> dm = convert_model<IDual>(base, [](const Mpfi& y) { return IDual(y); });
  dm = with_parameter(dm, par, IDual(p));
  const ImpactMap<IDual> map(std::move(dm));
  StepResult<IDual> r;
  try {
    r = map.step(State<IDual>{IDual::variable(th, 0), IDual::variable(v, 1)});
  } catch (const Undecided& u) {
    throw Fail("step " + std::to_string(i) + " of the period is undecided over its box: " + u.what());
  }
  if (r.kind != EventKind::impact) throw Fail("the orbit sticks: no multiplier -1 or +1 (superstable)");
  if (event) *event = step_event(r, base.wall.smooth());
  const IDual* rows[2] = {&r.next.theta, &r.next.v};
  for (int a = 0; a < 2; ++a) {
    F[a] = rows[a]->v;
    for (int k = 0; k < 2; ++k) el(M, static_cast<size_t>(a), static_cast<size_t>(k)) = rows[a]->d[k];
  }
}

std::vector<Mpfi> pd_value_shoot(const Model<Mpfi>& base, Parameter par, long q, const std::vector<Mpfi>& x, int sigma) {
  const long bits = x[0].bits();
  const Mpfi& p = x.back();
  std::vector<Mpfi> out;
  Mat2I P = identity2<Mpfi>(bits);
  for (long i = 0; i < q; ++i) {
    std::array<Mpfi, 2> F;
    Mat2I M;
    step_jacobian(base, par, x[2 * i], x[2 * i + 1], p, i, F, M);
    const long k = (i + 1) % q;
    out.push_back(Mpfi(F[0] - x[2 * k]));
    out.push_back(Mpfi(F[1] - x[2 * k + 1]));
    P = M * P;
  }
  out.push_back(Mpfi((P.a11 + sigma) * (P.a22 + sigma) - P.a12 * P.a21));
  return out;
}

Jet pd_jet_shoot(const Model<Mpfi>& base, Parameter par, long q, const std::vector<Mpfi>& x, int sigma) {
  const long bits = x[0].bits();
  const size_t N = x.size(), PI = N - 1;
  Jet J(N);
  std::vector<Mat2I> M(static_cast<size_t>(q));
  std::vector<std::array<Mat2I, 3>> dM(static_cast<size_t>(q));  // along theta_i, v_i, p
  for (long i = 0; i < q; ++i) {
    const size_t ii = static_cast<size_t>(i);
    for (int var = 0; var < 3; ++var) {
      auto lift = [&](const Mpfi& y) { return IDual2(IDual(y)); };
      Model<IDual2> dm = convert_model<IDual2>(base, lift);
      const IDual one(Mpfi(1, bits)), zero(Mpfi(0, bits));
      dm = with_parameter(dm, par, IDual2(IDual(x[PI]), var == 2 ? one : zero, zero));
      const ImpactMap<IDual2> map(std::move(dm));
      State<IDual2> s{IDual2(IDual::variable(x[2 * ii], 0), var == 0 ? one : zero, zero),
                      IDual2(IDual::variable(x[2 * ii + 1], 1), var == 1 ? one : zero, zero)};
      try {
        s = map.step(s).next;
      } catch (const Undecided& u) {
        throw Fail("step " + std::to_string(i) + " of the period is undecided over its box: " + u.what());
      }
      const IDual2* rows[2] = {&s.theta, &s.v};
      for (size_t r = 0; r < 2; ++r) {
        const IDual2& y = *rows[r];
        if (!ScalarTraits<IDual>::derivatives_finite(y.v) || !ScalarTraits<IDual>::is_finite(y.d[0]) ||
            !ScalarTraits<IDual>::derivatives_finite(y.d[0]))
          throw Fail("the second-derivative enclosure over the box is not finite");
        for (size_t k = 0; k < 2; ++k) {
          el(M[ii], r, k) = y.v.d[k];
          el(dM[ii][static_cast<size_t>(var)], r, k) = y.d[0].d[k];
        }
        if (var == 0) {
          const size_t next = static_cast<size_t>((i + 1) % q);
          J.f[2 * ii + r] = y.v.v - x[2 * next + r];
          for (size_t k = 0; k < 2; ++k) J.set(2 * ii + r, 2 * ii + k, y.v.d[k]);
          J.set(2 * ii + r, 2 * next + r, Mpfi(-1, bits));
        }
        if (var == 2) J.set(2 * ii + r, PI, y.d[0].v);
      }
    }
  }
  // Prefix R_i = M_{i-1} ... M_0, suffix L_i = M_{Q-1} ... M_{i+1}.
  std::vector<Mat2I> R(static_cast<size_t>(q) + 1), L(static_cast<size_t>(q));
  R[0] = identity2<Mpfi>(bits);
  for (size_t i = 0; i < static_cast<size_t>(q); ++i) R[i + 1] = M[i] * R[i];
  L[static_cast<size_t>(q) - 1] = identity2<Mpfi>(bits);
  for (size_t i = static_cast<size_t>(q) - 1; i > 0; --i) L[i - 1] = L[i] * M[i];
  const Mat2I& P = R[static_cast<size_t>(q)];
  const Mpfi a00 = P.a11 + sigma, a11 = P.a22 + sigma;
  J.f[PI] = a00 * a11 - P.a12 * P.a21;
  const Mat2I adj{a11, Mpfi(-P.a12), Mpfi(-P.a21), a00};
  Mpfi dp(0, bits);
  for (size_t i = 0; i < static_cast<size_t>(q); ++i) {
    const Mat2I W = R[i] * adj * L[i];
    for (size_t var = 0; var < 3; ++var) {
      Mpfi t(0, bits);
      for (size_t j = 0; j < 2; ++j)
        for (size_t k = 0; k < 2; ++k) t += el(W, j, k) * el(dM[i][var], k, j);
      if (var < 2)
        J.set(PI, 2 * i + var, t);
      else
        dp += t;
    }
  }
  J.set(PI, PI, dp);
  return J;
}

// The system of a smooth end on S: (P^Q(x) - x, det(DP^Q(x) + sigma I)) (sigma = +1: period
// doubling, -1: fold). S must outlive its use (the functions refer to it).
// shooting: the unknowns are all Q points (S.m = Q), else the first.
void smooth_system(Setup& S, const PeriodDoublingQuestion& q, int sigma, bool shooting) {
  if (!(q.lo.value() < q.hi.value())) throw Fail("the interval holding a* is empty");
  S.par = q.vary;
  S.bits = q.bits;
  S.base = interval_model(with_parameter(q.model, q.vary, q.lo), q.bits);
  S.m = shooting ? static_cast<int>(q.period) : 1;
  if (shooting) {
    S.value_fn = [&S, &q, sigma](const std::vector<Mpfi>& x) { return pd_value_shoot(S.base, S.par, q.period, x, sigma); };
    S.jet_fn = [&S, &q, sigma](const std::vector<Mpfi>& x) { return pd_jet_shoot(S.base, S.par, q.period, x, sigma); };
  } else {
    S.value_fn = [&S, &q, sigma](const std::vector<Mpfi>& x) { return pd_value(S.base, S.par, q.period, x, sigma); };
    S.jet_fn = [&S, &q, sigma](const std::vector<Mpfi>& x) { return pd_jet(S.base, S.par, q.period, x, sigma); };
  }
}

// The orbit's Q points at parameter p (Mpfr steps of the map from x), as shooting unknowns
// (only x for the composed form).
// The orbit is started at its point farthest from the wall's knots: a first point next to a
// knot (theta = 0.0006 on the period-164 orbit at a = 30) puts its box across the corner,
// where the step cannot decide the departure segment.
std::vector<Mpfr> smooth_unknowns(const Setup& S, const PeriodDoublingQuestion& q, const Mpfr& th, const Mpfr& v,
                                  const Mpfr& p) {
  const Model<Mpfr> m = make_model<Mpfr>(with_parameter(q.model, q.vary, *Decimal::parse(exact_decimal(to_q(p)))), q.bits);
  const ImpactMap<Mpfr> map(m);
  std::vector<State<Mpfr>> pts = {State<Mpfr>{th, v}};
  for (long i = 0; i + 1 < q.period; ++i) pts.push_back(map.step(pts.back()).next);
  auto clearance = [&](const State<Mpfr>& x) {
    double d = 1;
    for (const Mpfr& k : m.wall.start) {
      const double t = std::fabs(Mpfr(x.theta - k).to_double());
      d = std::min({d, t, std::fabs(1 - t)});
    }
    return d;
  };
  size_t first = 0;
  for (size_t i = 1; i < pts.size(); ++i)
    if (clearance(pts[i]) > clearance(pts[first])) first = i;
  std::vector<Mpfr> y;
  for (size_t i = 0; i < (S.m == 1 ? 1 : pts.size()); ++i) {
    const State<Mpfr>& x = pts[(first + i) % pts.size()];
    y.push_back(x.theta);
    y.push_back(x.v);
  }
  return y;
}

// Trace, det and events of DP^Q over the box B (the points, then p).
struct Multipliers {
  Mpfi trace, det;
  std::vector<StepEvent> events;
};

Multipliers multipliers_over(const Setup& S, const PeriodDoublingQuestion& q, const std::vector<Mpfi>& B) {
  Multipliers r;
  if (S.m == 1) {
    const Mpfi xb[3] = {B[0], B[1], B.back()};
    const State<IDual> e = orbit_dual(S.base, S.par, xb, q.period, &r.events);
    r.trace = e.theta.d[0] + e.v.d[1];
    r.det = e.theta.d[0] * e.v.d[1] - e.theta.d[1] * e.v.d[0];
    return r;
  }
  Mat2I P = identity2<Mpfi>(S.bits);
  for (long i = 0; i < q.period; ++i) {
    std::array<Mpfi, 2> F;
    Mat2I M;
    StepEvent ev;
    step_jacobian(S.base, S.par, B[2 * i], B[2 * i + 1], B.back(), i, F, M, &ev);
    r.events.push_back(ev);
    P = M * P;
  }
  r.trace = P.a11 + P.a22;
  r.det = P.a11 * P.a22 - P.a12 * P.a21;
  return r;
}

void run_pd(const PeriodDoublingQuestion& q, PeriodDoublingCertificate& c, bool shooting) {
  const long bits = q.bits;
  Setup S;
  smooth_system(S, q, 1, shooting);
  const mpq_class mid = (q.lo.value() + q.hi.value()) / 2;
  Mpfr pm(bits);
  mpfr_set_q(pm.get(), mid.get_mpq_t(), MPFR_RNDN);
  // The orbit at the middle (Newton on the map), then Newton on the augmented system.
  const Model<Mpfr> mm = make_model<Mpfr>(with_parameter(q.model, q.vary, *Decimal::parse(exact_decimal(mid))), bits);
  const PeriodicOrbit<Mpfr> o = find_periodic(mm, q.period, make_state<Mpfr>(mm, q.point));
  if (!o.converged || o.points.empty() || o.minimal_period != q.period)
    throw Fail("Newton found no orbit of minimal period " + std::to_string(q.period) + " in the interval");
  const Problem A = augmented(S);
  std::vector<Mpfr> u = smooth_unknowns(S, q, o.points[0].theta, o.points[0].v, pm);
  u.push_back(pm);
  u = newton(S, A, u);
  const Mpfr phat = u.back();
  Mpfr w0(bits);
  {
    const double width = std::max(mpq_class(q.hi.value() - q.lo.value()).get_d(), 1e-6 * std::max(1.0, std::fabs(phat.to_double())));
    mpfr_set_d(w0.get(), width, MPFR_RNDN);
    if (std::fabs(Mpfr(phat - pm).to_double()) > 100 * width)
      throw Fail("Newton on the augmented system goes to " + std::string(name(q.vary)) + " = " + text(phat) +
                 ", far from the interval given (no multiplier -1 next to it)");
  }
  std::optional<std::vector<Mpfi>> B;
  const std::vector<Mpfr> xg(u.begin(), u.end() - 1);
  const size_t ny = xg.size();
  Mpfi Z;
  std::vector<Mpfi> Y(ny);
  std::string why;
  // Z shrinks as for a border collision (z_half_width). The determinant row's second
  // derivatives over Y are large for long contracting periods (the period-82 doubling at
  // a = 30.00005, veldep c = 1000: K(Y x Z)'s parameter component about 1e18 rad(Y)^2 wide),
  // so Z must be far smaller than the 1e-11 a double bracket gives.
  for (int k = 0; !B; ++k) {
    const std::optional<Mpfr> w = z_half_width(w0, phat, bits, k);
    if (!w) break;
    const Mpfr zlo = phat - *w, zhi = phat + *w;
    Z = Mpfi(zlo, zhi);
    try {
      const std::vector<Mpfi> ylo = orbit_at(S, thin(zlo), xg), yhi = orbit_at(S, thin(zhi), xg);
      std::vector<Mpfr> rad(ny), mid2(ny);
      for (size_t i = 0; i < ny; ++i) {
        const Mpfi h = hull(hull(ylo[i], yhi[i]), thin(u[i]));
        mid2[i] = h.mid();
        Mpfi ulps = abs(thin(mid2[i])) + 1;
        mpfi_mul_2si(ulps.get(), ulps.get(), -(bits - 16));
        rad[i] = Mpfr(h.width() + ulps.upper());
      }
      bool ok = false;
      for (int t = 0; t < 6 && !ok; ++t) {
        for (size_t i = 0; i < ny; ++i) Y[i] = Mpfi(Mpfr(mid2[i] - rad[i]), Mpfr(mid2[i] + rad[i]));
        Problem O = orbit_problem(S, Z);
        O.zhat = phat;
        const std::vector<Mpfi> KO = krawczyk(S, O, xg, residual(S, O, xg), Y);
        std::vector<Mpfi> box = Y;
        box.push_back(Z);
        const std::vector<Mpfi> KA = krawczyk(S, A, u, residual(S, A, u), box);
        ok = all_inside(KO, Y) && all_inside(KA, box);
        if (!ok)
          for (size_t i = 0; i < ny; ++i) rad[i] = rad[i] * 4;
      }
      if (!ok) throw Fail("the Krawczyk operators did not map the box Y x Z into itself");
      std::vector<Mpfi> box = Y;
      box.push_back(Z);
      B = tighten(S, A, u, box);
    } catch (const Fail& f) {
      why = f.what();
    } catch (const Undecided& un) {
      why = std::string("undecided: ") + un.what();
    }
  }
  if (!B) throw Fail("no parameter interval around a* certified (" + why + ")");
  // The sign change of det(DP^Q + I) along x(p), at both ends of Z.
  const Mpfi zero(0, bits);
  Truth sides[2];
  for (int end = 0; end < 2; ++end) {
    const Mpfr p = end == 0 ? Z.lower() : Z.upper();
    std::vector<Mpfi> x = orbit_at(S, thin(p), xg);
    for (size_t i = 0; i < ny; ++i)
      if (!Y[i].contains(x[i])) throw Fail("an orbit enclosed at one parameter value lies outside Y");
    x.push_back(thin(p));
    sides[end] = Tr::lt(zero, S.value_fn(x).back());
    if (sides[end] == Truth::unknown || sides[end] == Truth::invalid)
      throw Fail("det(DP^Q + I) has no certain sign at an end of Z");
  }
  if (sides[0] == sides[1]) throw Fail("det(DP^Q + I) has the same sign at both ends of Z");
  // The multipliers at p*: trace and det over the tight box.
  const Multipliers mu = multipliers_over(S, q, *B);
  const Mpfi& tr = mu.trace;
  const Mpfi& det = mu.det;
  // The other multiplier is det / (-1); it must not be -1 too (a simple multiplier -1).
  if (Tr::is_zero(Mpfi(det - 1)) != Truth::no) throw Fail("the other multiplier may be -1 as well");
  const Mpfi& pstar = B->back();
  c.certified = true;
  c.lo = to_q(pstar.lower());
  c.hi = to_q(pstar.upper());
  c.parameter = enclosure(pstar);
  c.width = Mpfr(pstar.upper() - pstar.lower()).to_double();
  c.events = event_text(mu.events);
  c.z_lo = to_q(Z.lower());
  c.z_hi = to_q(Z.upper());
  c.trace = enclosure(tr);
  c.det = enclosure(det);
  c.other = enclosure(Mpfi(-det));
  c.orbit.push_back({enclosure((*B)[0]), enclosure((*B)[1])});
  const std::string p = name(q.vary);
  std::ostringstream st;
  st << "For every " << p << " in [" << Tr::upper_string(thin(Z.lower())) << ", " << Tr::lower_string(thin(Z.upper()))
     << "] the map has exactly one period-" << q.period << " point in the box [" << enclosure(Y[0]).lo << ", "
     << enclosure(Y[0]).hi << "] x [" << enclosure(Y[1]).lo << ", " << enclosure(Y[1]).hi << "] (events " << c.events
     << ", every branch decided); at exactly one " << p << "* in [" << c.parameter.lo << ", " << c.parameter.hi
     << "] (width " << c.width << ") it has a multiplier exactly -1 (the other is " << c.other.lo << " .. " << c.other.hi
     << "), and det(DP^" << q.period << " + I) changes sign there: a real multiplier crosses -1 (period doubling; "
     << "the direction of the doubled branch is not certified). Proved by the Krawczyk operator on (P^" << q.period
     << "(x) - x, det(DP^" << q.period << "(x) + I)) with second derivatives from nested interval duals"
     << (S.m > 1 ? " (multiple shooting: all " + std::to_string(S.m) + " orbit points unknowns, the box above the first's)" : "")
     << ", at " << bits << " bits.";
  c.statement = st.str();
}

// The fold (see certify_fold in the header): Krawczyk on H(x, p) = (P^Q(x) - x,
// det(DP^Q(x) - I)) over a box around the augmented Newton point. K(B) inside B proves one
// zero (x*, p*) in B and that every Jacobian H' over B is nonsingular. At (x*, p*), with
// F = P^Q - x: H' nonsingular makes [D_x F, F_p] of rank 2, so the period-Q points near it
// form one smooth curve; D_x F has rank exactly 1 (rank 0 would zero the last row of H');
// along the curve's tangent t, H' t = (0, 0, grad(det) . t) != 0, and t = (v, 0) with v the
// kernel of D_x F (F_p is not in the range of D_x F, else the kernel of [D_x F, F_p] would
// be two-dimensional): the curve turns at p*, and d det/dv = c <w, D^2F(v, v)> != 0 (adj of
// a rank-1 2x2 matrix is c v w^T, w the left kernel) makes p'' != 0 along it: a quadratic
// fold, two period-Q orbits near x* on one side of p*, none on the other.
// With shooting, the Jacobian of the shooting system reduces to the composed one by
// eliminating x_1 .. x_{Q-1} along the chain x_{i+1} = F(x_i) (block elimination with the -I
// blocks as pivots): one is regular exactly where the other is, and the argument above holds.
void run_fold(const PeriodDoublingQuestion& q, PeriodDoublingCertificate& c, bool shooting) {
  const long bits = q.bits;
  Setup S;
  smooth_system(S, q, -1, shooting);
  // Newton on the augmented system (regular at a fold, where Newton on the orbit alone is
  // not) from the branch's orbit point given and the middle of the interval; with shooting,
  // from that point's orbit under the map (the composed Newton would evaluate the Q steps
  // composed, which is what fails for long periods).
  const mpq_class mid = (q.lo.value() + q.hi.value()) / 2;
  std::vector<Mpfr> u;
  {
    const Model<Mpfr> mm = make_model<Mpfr>(with_parameter(q.model, q.vary, *Decimal::parse(exact_decimal(mid))), bits);
    const State<Mpfr> x0 = make_state<Mpfr>(mm, q.point);
    Mpfr p(bits);
    mpfr_set_q(p.get(), mid.get_mpq_t(), MPFR_RNDN);
    u = smooth_unknowns(S, q, x0.theta, x0.v, p);
    u.push_back(p);
    u = newton(S, augmented(S), u);
  }
  {
    const Mpfr& phat = u.back();
    const double width = std::max(mpq_class(q.hi.value() - q.lo.value()).get_d(), 1e-6 * std::max(1.0, std::fabs(phat.to_double())));
    if (!mpfr_number_p(phat.get()) || std::fabs(phat.to_double() - mid.get_d()) > 100 * width)
      throw Fail("Newton on the augmented system goes to " + std::string(name(q.vary)) + " = " + text(phat) +
                 ", far from the interval given (no multiplier +1 next to it)");
  }
  const std::vector<Mpfi> B = prove_tight(S, augmented(S), u);
  const Multipliers mu = multipliers_over(S, q, B);
  const Mpfi& tr = mu.trace;
  const Mpfi& det = mu.det;
  // One multiplier is exactly +1, so the other is det; it must not be +1 too.
  if (Tr::is_zero(Mpfi(det - 1)) != Truth::no) throw Fail("the other multiplier may be +1 as well");
  const Mpfi& pstar = B.back();
  c.certified = true;
  c.lo = to_q(pstar.lower());
  c.hi = to_q(pstar.upper());
  c.parameter = enclosure(pstar);
  c.width = Mpfr(pstar.upper() - pstar.lower()).to_double();
  c.events = event_text(mu.events);
  c.z_lo = c.lo;
  c.z_hi = c.hi;
  c.trace = enclosure(tr);
  c.det = enclosure(det);
  c.other = enclosure(det);
  c.orbit.push_back({enclosure(B[0]), enclosure(B[1])});
  const std::string p = name(q.vary);
  std::ostringstream st;
  st << "Exactly one period-" << q.period << " point x* in the box [" << enclosure(B[0]).lo << ", " << enclosure(B[0]).hi
     << "] x [" << enclosure(B[1]).lo << ", " << enclosure(B[1]).hi << "] (events " << c.events
     << ", every branch decided) at exactly one " << p << "* in [" << c.parameter.lo << ", " << c.parameter.hi << "] (width "
     << c.width << ") has a multiplier exactly +1 (the other is " << c.other.lo << " .. " << c.other.hi
     << "), and the augmented system is regular there: a nondegenerate fold (saddle-node), near which the period-"
     << q.period << " orbits form one curve that turns back at " << p
     << "*: two orbits on one side, none on the other (the size of that neighbourhood is not certified). Proved by the "
     << "Krawczyk operator on (P^" << q.period << "(x) - x, det(DP^" << q.period
     << "(x) - I)) with second derivatives from nested interval duals"
     << (S.m > 1 ? " (multiple shooting: all " + std::to_string(S.m) + " orbit points unknowns, the box above the first's)" : "")
     << ", at " << bits << " bits.";
  c.statement = st.str();
}
}  // namespace

namespace {

// Runs one proof: any step that fails (Fail) or cannot be decided (Undecided) leaves the
// certificate uncertified with the reason, and nothing is claimed (`what` says about what).
template <class Certificate, class Proof>
Certificate attempt(long bits, const char* what, Proof&& proof) {
  const auto t0 = std::chrono::steady_clock::now();
  Certificate c;
  c.bits = bits;
  try {
    proof(c);
  } catch (const Fail& f) {
    c.certified = false;
    c.reason = f.what();
  } catch (const Undecided& u) {
    c.certified = false;
    c.reason = std::string("undecided: ") + u.what();
  }
  if (!c.certified)
    c.statement = "Not certified at " + std::to_string(bits) + " bits: " + c.reason + ". Nothing is claimed" + what + ".";
  c.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return c;
}

}  // namespace

BorderCollisionCertificate certify_border_collision(const BorderCollisionQuestion& q) {
  const auto t0 = std::chrono::steady_clock::now();
  BorderCollisionQuestion at = q;
  // Both formulations at each precision: the composed map (one point) first for short
  // periods, multiple shooting (every point) first from kShootingFrom steps on, where the
  // composed map's wrapping makes it slow to fail; an orbit through the release state has
  // only the composed form (its start is exact).
  for (;;) {
    auto one = [&](bool shooting) {
      return attempt<BorderCollisionCertificate>(at.bits, " about a*", [&](BorderCollisionCertificate& r) {
        std::vector<State<Mpfi>> orbit;
        run(at, r, orbit, shooting);
      });
    };
    const bool shoot_first = q.formulation == Formulation::shooting ||
                             (q.formulation == Formulation::automatic && q.end.period >= kShootingFrom);
    BorderCollisionCertificate c = one(shoot_first);
    if (!c.certified && q.formulation == Formulation::automatic && q.end.period > 1 && !c.through_release) {
      BorderCollisionCertificate other = one(!shoot_first);
      if (other.certified) {
        c = other;
      } else if (other.reason != c.reason) {
        const std::string& composed = shoot_first ? other.reason : c.reason;
        const std::string& shot = shoot_first ? c.reason : other.reason;
        c.reason = "the composed map: " + composed + "; multiple shooting: " + shot;
        c.statement = "Not certified at " + std::to_string(at.bits) + " bits: " + c.reason + ". Nothing is claimed about a*.";
      }
    }
    if (c.certified || 2 * at.bits > q.max_bits) {
      c.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();  // every attempt
      return c;
    }
    at.bits *= 2;
  }
}

namespace {

// One smooth proof at q.bits, composed and then (period > 1) by multiple shooting, then at
// twice the bits while both fail, up to q.max_bits.
template <class Proof>
PeriodDoublingCertificate smooth_attempts(const PeriodDoublingQuestion& q, Proof&& proof) {
  const auto t0 = std::chrono::steady_clock::now();
  PeriodDoublingQuestion at = q;
  for (;;) {
    PeriodDoublingCertificate c =
        attempt<PeriodDoublingCertificate>(at.bits, "", [&](PeriodDoublingCertificate& r) { proof(at, r, false); });
    if (!c.certified && q.period > 1) {
      PeriodDoublingCertificate shot =
          attempt<PeriodDoublingCertificate>(at.bits, "", [&](PeriodDoublingCertificate& r) { proof(at, r, true); });
      if (shot.certified) {
        c = shot;
      } else if (shot.reason != c.reason) {
        c.reason = "the composed map: " + c.reason + "; multiple shooting: " + shot.reason;
        c.statement = "Not certified at " + std::to_string(at.bits) + " bits: " + c.reason + ". Nothing is claimed.";
      }
    }
    if (c.certified || 2 * at.bits > q.max_bits) {
      c.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();  // every attempt
      // The map's phase coordinate wraps at theta = 0, which is no knot of a smooth wall: an
      // orbit through it (the sine wall's period-1 saddle-node is at theta = 0 exactly) puts
      // the boxes across the wrap, where no Newton step or floor is decided.
      const double th = q.point.theta.approx();
      if (!c.certified && q.model.wall.shape != WallShape::piecewise && std::fabs(th - std::round(th)) < 1e-2) {
        c.reason = "the orbit's phase " + q.point.theta.text() +
                   " is next to theta = 0, where the map's phase coordinate wraps: a smooth wall's bifurcation there is not "
                   "certified by this method (the attempt: " + c.reason + ")";
        c.statement = "Not certified at " + std::to_string(at.bits) + " bits: " + c.reason + ". Nothing is claimed.";
      }
      return c;
    }
    at.bits *= 2;
  }
}

}  // namespace

PeriodDoublingCertificate certify_period_doubling(const PeriodDoublingQuestion& q) {
  return smooth_attempts(q, [](const PeriodDoublingQuestion& a, PeriodDoublingCertificate& c, bool shoot) { run_pd(a, c, shoot); });
}

PeriodDoublingCertificate certify_fold(const PeriodDoublingQuestion& q) {
  return smooth_attempts(q, [](const PeriodDoublingQuestion& a, PeriodDoublingCertificate& c, bool shoot) { run_fold(a, c, shoot); });
}

}  // namespace bouncer
