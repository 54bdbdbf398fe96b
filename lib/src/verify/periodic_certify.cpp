// Certified periodic orbits by the Krawczyk operator (verify/periodic_certify.hpp).
#include "bouncer/verify/periodic_certify.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <functional>
#include <limits>
#include <set>
#include <sstream>

#include "bouncer/base/cancel.hpp"
#include "bouncer/verify/enclosure.hpp"
#include "bouncer/verify/interval_dual.hpp"
#include "bouncer/verify/sticking.hpp"
#include "sparse_krawczyk.hpp"

namespace bouncer {

FamilyMode parse_family_mode(const std::string& field, const std::string& text) {
  if (text == "auto") return FamilyMode::automatic;
  if (text == "off") return FamilyMode::isolated;
  if (text == "on") return FamilyMode::family;
  throw InputError(field, "must be auto, on or off (got '" + text + "')");
}

Formulation parse_formulation(const std::string& field, const std::string& text) {
  if (text == "auto") return Formulation::automatic;
  if (text == "composed") return Formulation::composed;
  if (text == "shooting") return Formulation::shooting;
  throw InputError(field, "must be auto, composed or shooting (got '" + text + "')");
}

const char* name(PeriodicOutcome o) {
  switch (o) {
    case PeriodicOutcome::isolated: return "isolated";
    case PeriodicOutcome::family: return "family";
    case PeriodicOutcome::through_release: return "through_release";
    case PeriodicOutcome::not_found: return "not_found";
    case PeriodicOutcome::undecided: return "undecided";
  }
  return "?";
}

namespace {

using Tr = ScalarTraits<Mpfi>;

// Why one attempt at one precision failed (caught by the escalation loop).
struct NotCertified : std::runtime_error {
  using std::runtime_error::runtime_error;
};

Mpfi thin(const Mpfr& x) { return Mpfi(x, x); }

Mpfr at_bits(const Mpfr& x, long bits) {
  Mpfr r(bits);
  mpfr_set(r.get(), x.get(), MPFR_RNDN);
  return r;
}

Enclosure enclosure(const Mpfi& x) {
  // MPFI keeps an upper end 0 as -0: print it as 0.
  const std::string hi = Tr::upper_string(x);
  return {Tr::lower_string(x), hi == "-0" ? "0" : hi, x.mid().to_double(), x.width().to_double()};
}

bool strictly_inside(const Mpfi& x, const Mpfi& y) { return mpfi_is_strictly_inside(x.get(), y.get()) > 0; }
bool disjoint(const Mpfi& x, const Mpfi& y) {
  return Tr::lt(x, y) == Truth::yes || Tr::lt(y, x) == Truth::yes;
}
bool inside(const Mpfi& x, const Mpfi& y) { return y.contains(x); }


// What a step was, in words ("impact(seg 1, corner)"; a smooth wall has no segments:
// "impact(indirect)").
std::string event_text(const StepResult<Mpfi>& r, bool smooth_wall) {
  std::vector<std::string> parts;
  if (!smooth_wall) parts.push_back("seg " + std::to_string(r.segment));
  if (r.corner) parts.push_back("corner");
  if (r.indirect == Truth::yes) parts.push_back("indirect");
  std::string s = name(r.kind);
  if (parts.empty()) return s;
  s += "(" + parts[0];
  for (size_t i = 1; i < parts.size(); ++i) s += ", " + parts[i];
  return s + ")";
}

// Q interval steps from a box; every step's result (throws Undecided, naming the step).
std::vector<StepResult<Mpfi>> interval_orbit(const Model<Mpfi>& m, const State<Mpfi>& start, long q) {
  const ImpactMap<Mpfi> map(m);
  std::vector<StepResult<Mpfi>> out;
  State<Mpfi> s = start;
  for (long i = 0; i < q; ++i) {
    try {
      out.push_back(map.step(s));
    } catch (const Undecided& u) {
      throw NotCertified("step " + std::to_string(i + 1) + " of the period is undecided over the box: " + u.what());
    }
    s = out.back().next;
  }
  return out;
}

// Variables of the Krawczyk problem: 0 = theta, 1 = v, 2 = the parameter.
struct Box3 {
  Mpfi x[3];
};

// P^Q over a box with its derivatives D[row][var] (row: theta, v; var: theta, v, p),
// from two interval-dual runs through the same step.
struct Derivatives {
  Mpfi value[2];
  Mpfi D[2][3];
};

Derivatives derivatives(const Model<Mpfi>& m, Parameter par, const Box3& b, long q) {
  Derivatives out;
  for (int run = 0; run < 2; ++run) {
    Model<IDual> dm = convert_model<IDual>(m, [](const Mpfi& x) { return IDual(x); });
    dm = with_parameter(dm, par, run == 1 ? IDual::variable(b.x[2], 0) : IDual(b.x[2]));
    State<IDual> s = run == 0 ? State<IDual>{IDual::variable(b.x[0], 0), IDual::variable(b.x[1], 1)}
                              : State<IDual>{IDual(b.x[0]), IDual(b.x[1])};
    const ImpactMap<IDual> map(std::move(dm));
    for (long i = 0; i < q; ++i) {
      try {
        s = map.step(s).next;
      } catch (const Undecided& u) {
        throw NotCertified("step " + std::to_string(i + 1) + " of the period is undecided over the box: " + u.what());
      }
    }
    const IDual* rows[2] = {&s.theta, &s.v};
    for (int r = 0; r < 2; ++r) {
      if (!ScalarTraits<IDual>::derivatives_finite(*rows[r]))
        throw NotCertified("the Jacobian enclosure over the box is not finite (the enclosure of an impact speed over it reaches 0: the box is too wide at this precision, or the orbit touches down)");
      if (run == 0) {
        out.value[r] = rows[r]->v;
        out.D[r][0] = rows[r]->d[0];
        out.D[r][1] = rows[r]->d[1];
      } else {
        out.D[r][2] = rows[r]->d[0];
      }
    }
  }
  return out;
}

// The Krawczyk problem: unknowns y = (x[yi[0]], x[yi[1]]), free variable z = x[zi].
struct Problem {
  const Model<Mpfi>& model;  // parameters as given (overridden per evaluation)
  Parameter par;
  long q;
  int yi[2];
  int zi;
  Mpfi Z;                    // interval of the free variable
  Mpfr yhat[2];
  Mpfr zhat;
};

Box3 assemble(const Problem& P, const Mpfi y[2], const Mpfi& z) {
  Box3 b;
  b.x[P.yi[0]] = y[0];
  b.x[P.yi[1]] = y[1];
  b.x[P.zi] = z;
  return b;
}

// F(y^; z^) = P^Q(x) - (theta, v) at the point, in intervals.
void residual(const Problem& P, Mpfi f[2]) {
  const Mpfi yh[2] = {thin(P.yhat[0]), thin(P.yhat[1])};
  const Box3 b = assemble(P, yh, thin(P.zhat));
  Model<Mpfi> m = P.model;
  m = with_parameter(m, P.par, b.x[2]);
  const std::vector<StepResult<Mpfi>> orbit = interval_orbit(m, State<Mpfi>{b.x[0], b.x[1]}, P.q);
  f[0] = orbit.back().next.theta - b.x[0];
  f[1] = orbit.back().next.v - b.x[1];
}

// dF_row/dvar: P^Q's derivative minus the identity's.
Mpfi dF(const Derivatives& d, int row, int var) {
  return row == var ? d.D[row][var] - 1 : d.D[row][var];
}

struct KrawczykStep {
  Mpfi K[2];
  Derivatives d;
};

KrawczykStep krawczyk(const Problem& P, const Mpfi f[2], const Mpfi Y[2]) {
  Model<Mpfi> m = P.model;
  const Box3 b = assemble(P, Y, P.Z);
  m = with_parameter(m, P.par, b.x[2]);
  KrawczykStep out{{}, derivatives(m, P.par, b, P.q)};
  const Derivatives& d = out.d;
  Mpfi Fy[2][2], Fz[2];
  for (int r = 0; r < 2; ++r) {
    for (int k = 0; k < 2; ++k) Fy[r][k] = dF(d, r, P.yi[k]);
    Fz[r] = dF(d, r, P.zi);
  }
  // C: an approximate inverse of mid(F_y), as exact points (any C is valid).
  const Mpfi m11 = thin(Fy[0][0].mid()), m12 = thin(Fy[0][1].mid()), m21 = thin(Fy[1][0].mid()),
             m22 = thin(Fy[1][1].mid());
  const Mpfi det = m11 * m22 - m12 * m21;
  if (Tr::is_zero(det) != Truth::no) throw NotCertified("the midpoint Jacobian of F is singular");
  const Mpfi C[2][2] = {{thin((m22 / det).mid()), thin((-m12 / det).mid())},
                        {thin((-m21 / det).mid()), thin((m11 / det).mid())}};
  const Mpfi dz = P.Z - thin(P.zhat);
  const Mpfi dy[2] = {Y[0] - thin(P.yhat[0]), Y[1] - thin(P.yhat[1])};
  for (int r = 0; r < 2; ++r) {
    Mpfi k = thin(P.yhat[r]) - (C[r][0] * f[0] + C[r][1] * f[1]) - (C[r][0] * Fz[0] + C[r][1] * Fz[1]) * dz;
    for (int c = 0; c < 2; ++c) {
      Mpfi M = (r == c ? Mpfi(1, P.model.bits) : Mpfi(0, P.model.bits)) - (C[r][0] * Fy[0][c] + C[r][1] * Fy[1][c]);
      k += M * dy[c];
    }
    if (k.has_nan() || !k.bounded()) throw NotCertified("the Krawczyk image is not finite");
    out.K[r] = k;
  }
  return out;
}

// Newton on y at z^ (for families, whose parameter is an unknown): y <- y - C F(y),
// evaluated in thin intervals (their midpoints are the iterates).
void refine(Problem& P) {
  for (int it = 0; it < 40; ++it) {
    Mpfi f[2];
    residual(P, f);
    const Mpfi Y[2] = {thin(P.yhat[0]), thin(P.yhat[1])};
    const Problem at{P.model, P.par, P.q, {P.yi[0], P.yi[1]}, P.zi, thin(P.zhat), {P.yhat[0], P.yhat[1]}, P.zhat};
    // K(thin y) = y - C F(y) exactly the Newton step (dy and dz are 0).
    const KrawczykStep k = krawczyk(at, f, Y);
    const Mpfr next[2] = {k.K[0].mid(), k.K[1].mid()};
    const bool same = next[0] == P.yhat[0] && next[1] == P.yhat[1];
    P.yhat[0] = next[0];
    P.yhat[1] = next[1];
    if (same) return;
  }
}

// Epsilon inflation (Rump): grow Y around y^ until K(Y) lies inside it; then tighten with
// Y <- K(Y) n Y, which keeps the unique zero.
struct KrawczykResult {
  Mpfi Y0[2], K0[2];  // the proof: K(Y0) inside the interior of Y0
  Mpfi Y[2];          // the tightened enclosure of the zero
  Derivatives d;
  int inflations = 0;
};

KrawczykResult prove(const Problem& P) {
  const long bits = P.model.bits;
  Mpfi f[2];
  residual(P, f);
  Mpfr r[2];
  for (int i = 0; i < 2; ++i) {
    // Start from the residual's size (and a few ulps of y^), then let K tell the size.
    Mpfi ulps = abs(thin(P.yhat[i])) + 1;
    mpfi_mul_2si(ulps.get(), ulps.get(), -(bits - 8));
    const Mpfi s = abs(f[0]) + abs(f[1]) + ulps;
    r[i] = s.upper();
  }
  KrawczykResult out;
  Mpfi Y[2];
  for (int it = 0; it < 24; ++it) {
    for (int i = 0; i < 2; ++i) Y[i] = Mpfi(Mpfr(P.yhat[i] - r[i]), Mpfr(P.yhat[i] + r[i]));
    KrawczykStep k = krawczyk(P, f, Y);
    if (strictly_inside(k.K[0], Y[0]) && strictly_inside(k.K[1], Y[1])) {
      out.inflations = it;
      for (int i = 0; i < 2; ++i) {
        out.Y0[i] = Y[i];
        out.K0[i] = k.K[i];
      }
      out.d = std::move(k.d);
      // Tighten: every zero in Y lies in K(Y).
      Mpfi T[2] = {intersect(k.K[0], Y[0]), intersect(k.K[1], Y[1])};
      for (int t = 0; t < 6; ++t) {
        KrawczykStep kt = krawczyk(P, f, T);
        const Mpfi N[2] = {intersect(kt.K[0], T[0]), intersect(kt.K[1], T[1])};
        // K(T) n T holds the zero proved in Y0; an empty (NaN) intersection would mean an
        // enclosure is wrong: refuse rather than report a NaN box.
        if (N[0].has_nan() || N[1].has_nan()) throw NotCertified("K(Y) n Y is empty while tightening the proved box (an enclosure is inconsistent)");
        const bool shrank = mpfr_less_p(N[0].width().get(), T[0].width().get()) ||
                            mpfr_less_p(N[1].width().get(), T[1].width().get());
        T[0] = N[0];
        T[1] = N[1];
        out.d = std::move(kt.d);
        if (!shrank) break;
      }
      out.Y[0] = T[0];
      out.Y[1] = T[1];
      // The final derivatives are over the tightened box (for the multipliers).
      Model<Mpfi> m = P.model;
      const Box3 b = assemble(P, T, P.Z);
      m = with_parameter(m, P.par, b.x[2]);
      out.d = derivatives(m, P.par, b, P.q);
      return out;
    }
    for (int i = 0; i < 2; ++i) {
      const Mpfi dist = abs(k.K[i] - thin(P.yhat[i]));
      Mpfr grown(bits);
      grown = dist.upper() * 2;
      Mpfr doubled(bits);
      doubled = r[i] * 2;
      r[i] = mpfr_greater_p(grown.get(), doubled.get()) ? grown : doubled;
    }
  }
  throw NotCertified("the Krawczyk operator did not map any box around the Newton point into itself");
}

// Eigenvalues (multipliers) of every matrix of an interval 2x2 Jacobian, and stability by
// the Jury conditions on trace and determinant: both |mu| < 1 iff |det| < 1 and
// |tr| < 1 + det.
// Given enclosures of the trace and the determinant of the period map's Jacobian.
MultiplierEnclosure multipliers(const Mpfi& tr, const Mpfi& det, std::string& stability, bool family) {
  MultiplierEnclosure e;
  const long bits = tr.bits();
  const Mpfi disc = tr * tr - 4 * det;
  const Mpfi zero(0, bits), one(1, bits);
  e.trace = enclosure(tr);
  e.det = enclosure(det);
  Mpfi mu[2];
  if (Tr::lt(zero, disc) == Truth::yes) {
    e.kind = "real";
    const Mpfi s = sqrt(disc);
    mu[0] = (tr + s) / 2;
    mu[1] = (tr - s) / 2;
    if (Tr::lt(abs(mu[0]), abs(mu[1])) == Truth::yes) std::swap(mu[0], mu[1]);
    e.mu[0] = enclosure(mu[0]);
    e.mu[1] = enclosure(mu[1]);
  } else if (Tr::lt(disc, zero) == Truth::yes) {
    e.kind = "complex";
    e.mu[0] = enclosure(tr / 2);
    e.mu[1] = enclosure(sqrt(-disc) / 2);
    e.modulus = enclosure(sqrt(det));
  } else {
    e.kind = "undecided";
  }
  if (family) {
    // One multiplier is 1 along the family: the other one decides transversal stability.
    if (e.kind == "real") {
      const Mpfi& other = Tr::lt(abs(mu[0] - 1), abs(mu[1] - 1)) == Truth::yes ? mu[1] : mu[0];
      stability = Tr::lt(abs(other), one) == Truth::yes   ? "neutral-stable"
                  : Tr::lt(one, abs(other)) == Truth::yes ? "neutral-unstable"
                                                          : "undecided";
    } else {
      stability = "undecided";
    }
    return e;
  }
  const Mpfi onep = one + det;
  const bool stable = Tr::lt(det, one) == Truth::yes && Tr::lt(-one, det) == Truth::yes &&
                      Tr::lt(abs(tr), onep) == Truth::yes;
  const bool unstable = Tr::lt(one, det) == Truth::yes || Tr::lt(det, -one) == Truth::yes ||
                        Tr::lt(onep, abs(tr)) == Truth::yes;
  const bool elliptic = e.kind == "complex" && Tr::le(sqrt(det), one) != Truth::no && Tr::le(one, sqrt(det)) != Truth::no;
  stability = stable ? "stable" : unstable ? "unstable" : elliptic ? "elliptic" : "undecided";
  return e;
}

std::vector<long> proper_divisors(long q) {
  std::vector<long> d;
  for (long k = 1; k < q; ++k)
    if (q % k == 0) d.push_back(k);
  return d;
}

// Multiple shooting (long periods). The composed map's interval evaluation widens a box by
// the product of the Q steps' derivative norms: a period-1096 attractor of the veldep model
// (c = 1000, a = 21) is undecided at its 689th step at any precision the schedule tries.
// Shooting never composes. Unknowns: all Q points y = (x_0, ..., x_{Q-1}); rows
//     G_i(y; z) = P(x_i; z) - x_{i+1 mod Q},
// each step over its own point's box Y_i, the parameter z over Z inside the model (an
// interval: F(y^; Z) and the Jacobian over Y x Z enclose those of every z in Z, so K(Y) in
// the interior of Y proves, for every z in Z, exactly one zero in Y). The interval step and
// the interval-dual step decide every branch over Y_i x Z or throw, so on each box P is one
// smooth piece and the zero is a period-Q orbit of the map, unique among orbits whose i-th
// point lies in Y_i for every i. The Jacobian is sparse (J_i and -I blocks); C is
// sparse_krawczyk.hpp's double LU inverse, computed once at the thin Newton point.
class Shooting {
 public:
  Shooting(const Model<Mpfi>& m, long q) : model_(m), q_(static_cast<size_t>(q)), bits_(m.bits) {}

  // Every step from its box (thin boxes: the residual), the event of each step.
  std::vector<StepResult<Mpfi>> steps(const std::vector<Mpfi>& y) const {
    const ImpactMap<Mpfi> map(model_);
    std::vector<StepResult<Mpfi>> out;
    out.reserve(q_);
    for (size_t i = 0; i < q_; ++i) {
      try {
        out.push_back(map.step(State<Mpfi>{y[2 * i], y[2 * i + 1]}));
      } catch (const Undecided& u) {
        throw NotCertified("step " + std::to_string(i + 1) + " of the period is undecided over its box: " + u.what());
      }
    }
    return out;
  }

  std::vector<Mpfi> residual(const std::vector<Mpfr>& yhat) const {
    std::vector<Mpfi> y;
    for (const Mpfr& v : yhat) y.push_back(thin(v));
    const std::vector<StepResult<Mpfi>> r = steps(y);
    std::vector<Mpfi> f;
    for (size_t i = 0; i < q_; ++i) {
      const size_t k = (i + 1) % q_;
      f.push_back(Mpfi(r[i].next.theta - y[2 * k]));
      f.push_back(Mpfi(r[i].next.v - y[2 * k + 1]));
    }
    return f;
  }

  // Each step's 2x2 Jacobian over its box (rows theta', v'; columns theta, v).
  std::vector<std::array<Mpfi, 4>> step_jacobians(const std::vector<Mpfi>& Y) const {
    Model<IDual> dm = convert_model<IDual>(model_, [](const Mpfi& x) { return IDual(x); });
    const ImpactMap<IDual> map(std::move(dm));
    std::vector<std::array<Mpfi, 4>> J;
    J.reserve(q_);
    for (size_t i = 0; i < q_; ++i) {
      State<IDual> s{IDual::variable(Y[2 * i], 0), IDual::variable(Y[2 * i + 1], 1)};
      try {
        s = map.step(s).next;
      } catch (const Undecided& u) {
        throw NotCertified("step " + std::to_string(i + 1) + " of the period is undecided over its box: " + u.what());
      }
      for (const IDual* x : {&s.theta, &s.v})
        if (!ScalarTraits<IDual>::derivatives_finite(*x))
          throw NotCertified("the Jacobian enclosure of step " + std::to_string(i + 1) +
                             " over its box is not finite (the enclosure of an impact speed over it reaches 0: the box is too wide at this precision, or the orbit touches down)");
      J.push_back({s.theta.d[0], s.theta.d[1], s.v.d[0], s.v.d[1]});
    }
    return J;
  }

  detail::SparseColumns jacobian(const std::vector<Mpfi>& Y) const {
    const std::vector<std::array<Mpfi, 4>> J = step_jacobians(Y);
    detail::SparseColumns A(2 * q_);
    for (size_t i = 0; i < q_; ++i) {
      const size_t prev = (i + q_ - 1) % q_;
      for (size_t c = 0; c < 2; ++c) {
        auto& col = A[2 * i + c];
        col.emplace_back(2 * i, J[i][c]);
        col.emplace_back(2 * i + 1, J[i][2 + c]);
        col.emplace_back(2 * prev + c, Mpfi(-1, bits_));  // G_prev = P(x_prev) - x_i
      }
    }
    return A;
  }

  std::vector<Mpfi> image(const std::vector<Mpfr>& yhat, const std::vector<Mpfi>& f, const std::vector<Mpfi>& Y) const {
    std::vector<Mpfi> H;  // the mean value form needs the derivatives over hull(Y, y^)
    for (size_t c = 0; c < Y.size(); ++c) H.push_back(hull(Y[c], thin(yhat[c])));
    try {
      return detail::krawczyk_image(C_, yhat, f, jacobian(H), nullptr, Mpfi(0, bits_), Y, bits_);
    } catch (const detail::KrawczykFailure& e) {
      throw NotCertified(e.what());
    }
  }

  // Chord Newton at the working precision, y <- y - C G(y) with C from the first point,
  // until the moves stop shrinking: the points of a long unstable orbit stepped from x_0
  // drift by the product of the steps' growth; the proof never relies on this being accurate.
  std::vector<Mpfr> refine(std::vector<Mpfr> y) {
    std::vector<Mpfi> Y;
    for (const Mpfr& v : y) Y.push_back(thin(v));
    try {
      C_ = detail::Preconditioner(jacobian(Y), bits_);
    } catch (const detail::KrawczykFailure& e) {
      throw NotCertified(e.what());
    }
    double last = std::numeric_limits<double>::infinity();
    for (int it = 0; it < 20; ++it) {
      std::vector<Mpfi> T;
      for (const Mpfr& v : y) T.push_back(thin(v));
      const std::vector<Mpfi> K = image(y, residual(y), T);
      double move = 0;
      for (size_t i = 0; i < y.size(); ++i) {
        const Mpfr nx = K[i].mid();
        move = std::max(move, Mpfr(abs(Mpfr(nx - y[i])) / (abs(y[i]) + 1)).to_double());
        y[i] = nx;
      }
      if (move == 0 || move > last / 16) break;
      last = move;
    }
    return y;
  }

  // Epsilon inflation around y^ (refined first), then Y <- K(Y) n Y (sparse_krawczyk.hpp).
  detail::InflationProof prove(const std::vector<Mpfr>& start) {
    const std::vector<Mpfr> yhat = refine(start);
    const std::vector<Mpfi> f = residual(yhat);
    try {
      return detail::prove_by_inflation(
          yhat, f,
          [&](const std::vector<Mpfi>& Y) {
            throw_if_cancelled();
            return image(yhat, f, Y);
          },
          bits_, 6);
    } catch (const detail::KrawczykFailure& e) {
      throw NotCertified(e.what());
    }
  }

  // Trace and determinant of the period map's Jacobian J_{Q-1} ... J_0 over the boxes Y.
  // The determinant is the product of the steps' determinants (scalars: no wrapping). The
  // product of 2x2 interval matrices is kept in Lohner's form B R (B a point rotation, R an
  // interval matrix), B_{k+1} the Q factor of mid(J_k B_k), R_{k+1} = (B_{k+1}^-1 J_k B_k) R_k
  // with B^-1 enclosed: R stays nearly triangular, so the wrapping of a plain product
  // (which grows like the product of the steps' norms, 1e500 over the period 1096) is avoided.
  std::pair<Mpfi, Mpfi> trace_det(const std::vector<Mpfi>& Y) const {
    const std::vector<std::array<Mpfi, 4>> J = step_jacobians(Y);
    const Mpfi zero(0, bits_), one(1, bits_);
    Mpfi B[2][2] = {{one, zero}, {zero, one}}, R[2][2] = {{one, zero}, {zero, one}};
    Mpfi det = one;
    for (const auto& j : J) {
      det *= j[0] * j[3] - j[1] * j[2];
      Mpfi T[2][2];
      for (int r = 0; r < 2; ++r)
        for (int c = 0; c < 2; ++c) T[r][c] = j[2 * r] * B[0][c] + j[2 * r + 1] * B[1][c];
      // The rotation of mid(T)'s first column onto e_1 (any cos, sin are valid).
      const Mpfr t0 = T[0][0].mid(), t1 = T[1][0].mid();
      Mpfr n = sqrt(Mpfr(t0 * t0 + t1 * t1));
      if (n.to_double() == 0) n = Mpfr(1, bits_);
      const Mpfi cs = thin(Mpfr(t0 / n)), sn = thin(Mpfr(t1 / n));
      const Mpfi Bn[2][2] = {{cs, -sn}, {sn, cs}};
      const Mpfi d = cs * cs + sn * sn;  // B^-1 = B^T / d, enclosed
      const Mpfi Bi[2][2] = {{cs / d, sn / d}, {-sn / d, cs / d}};
      Mpfi U[2][2], Rn[2][2];
      for (int r = 0; r < 2; ++r)
        for (int c = 0; c < 2; ++c) U[r][c] = Bi[r][0] * T[0][c] + Bi[r][1] * T[1][c];
      for (int r = 0; r < 2; ++r)
        for (int c = 0; c < 2; ++c) Rn[r][c] = U[r][0] * R[0][c] + U[r][1] * R[1][c];
      for (int r = 0; r < 2; ++r)
        for (int c = 0; c < 2; ++c) {
          B[r][c] = Bn[r][c];
          R[r][c] = Rn[r][c];
        }
    }
    const Mpfi tr = B[0][0] * R[0][0] + B[0][1] * R[1][0] + B[1][0] * R[0][1] + B[1][1] * R[1][1];
    return {tr, det};
  }

 private:
  const Model<Mpfi>& model_;
  size_t q_;
  long bits_;
  detail::Preconditioner C_;
};

// One certification at `bits` for the parameter in [zlo, zhi] (equal for one value).
class Attempt1 {
 public:
  Attempt1(const PeriodicQuestion& q, long bits, const Mpfi& Z, const std::optional<State<Mpfr>>& guess)
      : q_(q), bits_(bits), Z_(Z), guess_(guess), model_(interval_model(q.model, bits)) {
    model_ = with_parameter(model_, q.vary, Z_);
  }

  PeriodicCertificate run() {
    PeriodicCertificate c;
    c.period = q_.period;
    c.bits = bits_;
    const PeriodicOrbit<Mpfr> newton = newton_orbit();
    newton_point = newton.points.empty() ? std::nullopt : std::optional<State<Mpfr>>(newton.points[0]);
    // A family exists at one parameter value only, where Newton at fixed parameter may not
    // converge: with --family on, start from the guess and solve for (v, p) instead.
    if (q_.family == FamilyMode::family && !newton.converged && (guess_ || q_.guess)) {
      const State<Mpfr> g = guess_ ? *guess_ : make_state<Mpfr>(*q_.guess, bits_);
      return family_orbit(g, c);
    }
    if (!newton.converged)
      throw NotFound("Newton found no period-" + std::to_string(q_.period) + " orbit" +
                     (newton.note.empty() ? "" : " (" + newton.note + ")"));
    const bool contracted =
        std::any_of(newton.kinds.begin(), newton.kinds.end(), [](EventKind k) { return k != EventKind::impact; });
    if (contracted) return through_release(newton, c);
    if (q_.family == FamilyMode::family) return family_orbit(newton.points[0], c);
    // A real multiplier 1 (Newton's, in double) makes F_(theta, v) singular: a family.
    // Elliptic orbits (a complex pair on the unit circle) are isolated.
    const Eigen2<Mpfr>& mu = newton.multipliers;
    const bool one = !mu.complex && (std::fabs(mu.re[0].to_double() - 1) < 1e-6 || std::fabs(mu.re[1].to_double() - 1) < 1e-6);
    if (q_.family == FamilyMode::automatic && one && !q_.range) return family_orbit(newton.points[0], c);
    return isolated(newton, c);
  }

  struct NotFound : std::runtime_error {
    using std::runtime_error::runtime_error;
  };
  std::optional<State<Mpfr>> newton_point;

 private:
  const PeriodicQuestion& q_;
  long bits_;
  Mpfi Z_;
  std::optional<State<Mpfr>> guess_;
  Model<Mpfi> model_;

  PeriodicOrbit<Mpfr> newton_orbit() const {
    Model<Mpfr> m = make_model<Mpfr>(q_.model, bits_);
    m = with_parameter(m, q_.vary, Z_.mid());
    if (guess_) return find_periodic(m, q_.period, *guess_, q_.newton);
    if (q_.guess) return find_periodic(m, q_.period, make_state<Mpfr>(*q_.guess, bits_), q_.newton);
    return search_periodic(m, q_.period, q_.newton);
  }

  void fill_orbit(PeriodicCertificate& c, const State<Mpfi>& start, const Model<Mpfi>& m) const {
    const std::vector<StepResult<Mpfi>> orbit = interval_orbit(m, start, q_.period);
    c.points.push_back({enclosure(start.theta), enclosure(start.v)});
    for (size_t i = 0; i + 1 < orbit.size(); ++i)
      c.points.push_back({enclosure(orbit[i].next.theta), enclosure(orbit[i].next.v)});
    for (const StepResult<Mpfi>& r : orbit) {
      c.events.push_back(event_text(r, m.wall.smooth()));
      c.wall_periods.push_back(r.periods);
    }
    boxes_.assign(1, start);
    for (size_t i = 0; i + 1 < orbit.size(); ++i) boxes_.push_back(orbit[i].next);
  }
  mutable std::vector<State<Mpfi>> boxes_;

  // Minimal period. Disjoint point boxes prove P^d(x*) != x*. For an isolated orbit whose
  // box d meets box 0, the Krawczyk operator for P^d around the same point may prove a
  // period-d point x' in a box inside the proof box of P^Q; x' is then a period-Q point
  // there, so x' = x* by uniqueness and x* has period d. (Families: disjointness only.)
  void minimal_period(PeriodicCertificate& c, const std::optional<State<Mpfi>>& unique_box,
                      const Mpfr* yhat = nullptr) const {
    for (long d : proper_divisors(q_.period)) {
      const State<Mpfi>& b = boxes_[d];
      if (disjoint(b.theta, boxes_[0].theta) || disjoint(b.v, boxes_[0].v)) continue;
      if (unique_box && yhat) {
        try {
          const Problem P{model_, q_.vary, d, {0, 1}, 2, Z_, {yhat[0], yhat[1]}, Z_.mid()};
          const KrawczykResult k = prove(P);
          if (inside(k.Y[0], unique_box->theta) && inside(k.Y[1], unique_box->v)) {
            c.minimal_period = d;
            c.minimal_period_certified = true;
            return;
          }
        } catch (const NotCertified&) {
        } catch (const Undecided&) {
        }
      }
      c.minimal_period = 0;
      c.minimal_period_certified = false;
      return;
    }
    c.minimal_period = q_.period;
    c.minimal_period_certified = true;
  }

  // Composed or shooting, in the order of kShootingFrom; the other where the first fails
  // (the reason reported is the first formulation's, with the second's).
  PeriodicCertificate isolated(const PeriodicOrbit<Mpfr>& newton, PeriodicCertificate& c) {
    const bool points = newton.points.size() == static_cast<size_t>(q_.period);
    if (q_.formulation == Formulation::composed) return composed(newton, c);
    if (q_.formulation == Formulation::shooting) {
      if (!points) throw NotCertified("multiple shooting: Newton's orbit has no points to start from");
      return shooting(newton, c);
    }
    const bool shooting_first = q_.period >= kShootingFrom && points;
    const PeriodicCertificate blank = c;
    try {
      return shooting_first ? shooting(newton, c) : composed(newton, c);
    } catch (const NotCertified& first) {
      if (q_.period == 1 || !points) throw;
      c = blank;
      try {
        return shooting_first ? composed(newton, c) : shooting(newton, c);
      } catch (const NotCertified& second) {
        throw NotCertified(std::string(shooting_first ? "multiple shooting: " : "") + first.what() + "; " +
                           (shooting_first ? "" : "multiple shooting: ") + second.what());
      } catch (const Undecided& second) {
        throw NotCertified(std::string(first.what()) + "; undecided: " + second.what());
      }
    }
  }

  PeriodicCertificate shooting(const PeriodicOrbit<Mpfr>& newton, PeriodicCertificate& c) {
    Shooting S(model_, q_.period);
    std::vector<Mpfr> start;
    for (const State<Mpfr>& x : newton.points) {
      start.push_back(at_bits(x.theta, bits_));
      start.push_back(at_bits(x.v, bits_));
    }
    const detail::InflationProof p = S.prove(start);
    c.outcome = PeriodicOutcome::isolated;
    c.shooting = true;
    c.unknowns = "theta, v (of every point: multiple shooting)";
    c.free_name = name(q_.vary);
    for (int i = 0; i < 2; ++i) {
      c.box[i] = enclosure(p.Y0[i]);
      c.image[i] = enclosure(p.K0[i]);
    }
    c.free_range = enclosure(Z_);
    c.inflations = p.inflations;
    const std::vector<StepResult<Mpfi>> steps = S.steps(p.Y);
    boxes_.clear();
    for (long i = 0; i < q_.period; ++i) {
      const size_t k = static_cast<size_t>(2 * i);
      c.points.push_back({enclosure(p.Y[k]), enclosure(p.Y[k + 1])});
      boxes_.push_back(State<Mpfi>{p.Y[k], p.Y[k + 1]});
      c.events.push_back(event_text(steps[static_cast<size_t>(i)], model_.wall.smooth()));
      c.wall_periods.push_back(steps[static_cast<size_t>(i)].periods);
    }
    const auto [tr, det] = S.trace_det(p.Y);
    c.multipliers = multipliers(tr, det, c.stability, false);
    c.certified = true;
    minimal_period(c, std::nullopt);
    return c;
  }

  PeriodicCertificate composed(const PeriodicOrbit<Mpfr>& newton, PeriodicCertificate& c) {
    Problem P{model_, q_.vary, q_.period, {0, 1}, 2, Z_, {newton.points[0].theta, newton.points[0].v}, Z_.mid()};
    const KrawczykResult k = prove(P);
    c.outcome = PeriodicOutcome::isolated;
    c.unknowns = "theta, v";
    c.free_name = name(q_.vary);
    finish(c, P, k, State<Mpfi>{k.Y[0], k.Y[1]}, model_, false);
    const Mpfr yhat[2] = {newton.points[0].theta, newton.points[0].v};
    minimal_period(c, State<Mpfi>{k.Y0[0], k.Y0[1]}, yhat);
    return c;
  }

  // Families: unknowns (v, p), first at theta^ exactly (tight enclosures, multipliers), then
  // for every theta of the widest strip around theta^ that certifies (the family statement).
  PeriodicCertificate family_orbit(const State<Mpfr>& start, PeriodicCertificate& c) {
    const Mpfr& th = start.theta;
    Problem at{model_, q_.vary, q_.period, {1, 2}, 0, thin(th), {start.v, Z_.mid()}, th};
    KrawczykResult k0;
    try {
      refine(at);
      k0 = prove(at);
    } catch (const NotCertified& nc) {
      throw NotCertified(std::string("family (unknowns v, ") + name(q_.vary) + " at theta = theta^): " + nc.what());
    }
    c.outcome = PeriodicOutcome::family;
    c.unknowns = std::string("v, ") + name(q_.vary);
    c.free_name = "theta";
    Model<Mpfi> m = model_;
    m = with_parameter(m, q_.vary, k0.Y[1]);
    finish(c, at, k0, State<Mpfi>{thin(th), k0.Y[0]}, m, true);
    c.family_parameter = enclosure(k0.Y[1]);
    c.given_parameter = inside(Z_, k0.Y[1]) ? "inside" : disjoint(Z_, k0.Y[1]) ? "outside" : "overlaps";
    minimal_period(c, std::nullopt);
    for (int e : {4, 8, 12, 16, 24, 32}) {
      // theta^ +- 2^-e / 2, outward.
      const Mpfi w = Mpfi(1, bits_) / (1L << (e / 2)) / (1L << (e - e / 2));
      const Mpfi strip((thin(th) - w / 2).lower(), (thin(th) + w / 2).upper());
      const Problem P{model_, q_.vary, q_.period, {1, 2}, 0, strip, {k0.Y[0].mid(), k0.Y[1].mid()}, th};
      try {
        const KrawczykResult k = prove(P);
        c.strip_theta = enclosure(strip);
        c.strip_v = enclosure(k.Y[0]);
        c.strip_parameter = enclosure(k.Y[1]);
        break;
      } catch (const NotCertified&) {
      } catch (const Undecided&) {
      }
    }
    return c;
  }

  void finish(PeriodicCertificate& c, const Problem& P, const KrawczykResult& k, const State<Mpfi>& start,
              const Model<Mpfi>& m, bool family) const {
    for (int i = 0; i < 2; ++i) {
      c.box[i] = enclosure(k.Y0[i]);
      c.image[i] = enclosure(k.K0[i]);
    }
    c.free_range = enclosure(P.Z);
    c.inflations = k.inflations;
    fill_orbit(c, start, m);
    const Mpfi(&J)[2][3] = k.d.D;
    c.multipliers = multipliers(Mpfi(J[0][0] + J[1][1]), Mpfi(J[0][0] * J[1][1] - J[0][1] * J[1][0]), c.stability, family);
    c.certified = true;
  }

  // The orbit of the release state: certified iff the first step ending at a release is
  // step Q and it ends at the same release.
  PeriodicCertificate through_release(const PeriodicOrbit<Mpfr>& newton, PeriodicCertificate& c) {
    long last = -1;
    for (long i = 0; i < q_.period; ++i)
      if (newton.kinds[i] != EventKind::impact) last = i;
    const int k = newton.points[(last + 1) % q_.period].knot;
    if (k < 0) throw NotCertified("the Newton orbit's release state is not at a wall knot");
    // The step's own release state (exact, so the comparison below is exact too).
    const State<Mpfi> R = release_state(model_, k);
    const std::vector<StepResult<Mpfi>> orbit = interval_orbit(model_, R, q_.period);
    for (long i = 0; i < q_.period; ++i) {
      if (orbit[i].kind == EventKind::impact) continue;
      if (orbit[i].next.knot != k || mpfi_cmp(orbit[i].next.v.get(), R.v.get()) != 0)
        throw NotCertified("step " + std::to_string(i + 1) + " from the release ends at another release state");
      if (q_.period % (i + 1) != 0)
        throw NotCertified("the release state has period " + std::to_string(i + 1) + ", which does not divide " +
                           std::to_string(q_.period));
      c.minimal_period = i + 1;
      c.minimal_period_certified = true;
      break;
    }
    if (!c.minimal_period_certified) throw NotCertified("the orbit of the release state does not return within the period");
    c.outcome = PeriodicOutcome::through_release;
    c.unknowns = "none (the release state is exact)";
    c.free_name = name(q_.vary);
    c.free_range = enclosure(Z_);
    fill_orbit(c, R, model_);
    c.multipliers.kind = "real";
    c.multipliers.mu[0] = c.multipliers.mu[1] = enclosure(Mpfi(0, bits_));
    c.multipliers.trace = c.multipliers.det = enclosure(Mpfi(0, bits_));
    c.stability = "superstable";
    c.certified = true;
    return c;
  }
};

std::string point_text(const EnclosedOrbitPoint& p) {
  return "(theta, v) in [" + p.theta.lo + ", " + p.theta.hi + "] x [" + p.v.lo + ", " + p.v.hi + "]";
}

std::string statement(const PeriodicQuestion& q, const PeriodicCertificate& c, const std::string& where) {
  std::ostringstream s;
  const std::string Q = std::to_string(q.period);
  switch (c.outcome) {
    case PeriodicOutcome::isolated:
      s << (q.range ? "For every " : "At ") << where << " there is exactly one point of period " << Q << " of the map in the box "
        << point_text(c.points[0]) << "; its minimal period is "
        << (c.minimal_period_certified ? std::to_string(c.minimal_period) : "undecided") << ", it is " << c.stability
        << " (multipliers " << c.multipliers.kind << ")";
      if (c.shooting) s << "; proved by multiple shooting, with every one of the " << Q << " points an unknown";
      break;
    case PeriodicOutcome::family: {
      const std::string p = name(q.vary);
      s << "Family (a multiplier 1; the parameter " << p << " is an unknown, theta is free): at theta = "
        << c.points[0].theta.lo << " there is exactly one (v, " << p << ") in [" << c.points[0].v.lo << ", "
        << c.points[0].v.hi << "] x [" << c.family_parameter->lo << ", " << c.family_parameter->hi << "] with P^" << Q
        << "(theta, v) = (theta, v)";
      if (c.strip_theta)
        s << "; for every theta in [" << c.strip_theta->lo << ", " << c.strip_theta->hi << "] there is exactly one (v, "
          << p << ") in [" << c.strip_v->lo << ", " << c.strip_v->hi << "] x [" << c.strip_parameter->lo << ", "
          << c.strip_parameter->hi << "]: a curve of period-" << Q << " points across that strip";
      s << ". The given " << p << " = " << parameter_of(q.model, q.vary).text() << " "
        << (c.given_parameter == "inside"     ? "lies in the enclosure at theta^"
            : c.given_parameter == "outside" ? "lies OUTSIDE the enclosure at theta^ (the family is elsewhere)"
                                             : "overlaps the enclosure at theta^")
        << "; that the curve has exactly constant " << p
        << " (a whole family at one parameter value) is a codimension-one coincidence that intervals cannot prove. "
           "Transversal stability: "
        << c.stability;
      break;
    }
    case PeriodicOutcome::through_release:
      s << (q.range ? "For every " : "At ") << where << " the orbit of the release state (" << c.points[0].theta.lo << ", " << c.points[0].v.lo
        << ") sticks for the first time at step " << c.minimal_period << " and is released at the same state: a periodic "
        << "sticking orbit of minimal period " << c.minimal_period << " (superstable: the release state does not depend "
        << "on the state before the collapse)";
      break;
    default:
      break;
  }
  s << ". Event sequence: ";
  for (size_t i = 0; i < c.events.size(); ++i) s << (i ? ", " : "") << c.events[i];
  s << ".";
  return s.str();
}

std::string where_text(const PeriodicQuestion& q) {
  const std::string p = name(q.vary);
  if (q.range) return p + " in [" + exact_decimal(q.range->first) + ", " + exact_decimal(q.range->second) + "]";
  return p + " = " + parameter_of(q.model, q.vary).text() + " (the exact decimal)";
}

Mpfi parameter_interval(const PeriodicQuestion& q, long bits) {
  if (q.range) return enclose(q.range->first, q.range->second, bits);
  Mpfi x(bits);
  x.set_decimal(parameter_of(q.model, q.vary).text());
  return x;
}

PeriodicCertificate certify_with_guess(const PeriodicQuestion& q, const std::optional<State<Mpfr>>& chained,
                                       std::optional<State<Mpfr>>* solution) {
  const auto t0 = std::chrono::steady_clock::now();
  PeriodicCertificate best;
  best.period = q.period;
  std::vector<Attempt> attempts;
  bool found = false;
  for (long bits : q.schedule.bits()) {
    throw_if_cancelled();
    Attempt a;
    a.bits = bits;
    const auto ta = std::chrono::steady_clock::now();
    std::optional<State<Mpfr>> guess;
    if (chained) guess = State<Mpfr>{at_bits(chained->theta, bits), at_bits(chained->v, bits), chained->knot};
    Attempt1 run(q, bits, parameter_interval(q, bits), guess);
    try {
      PeriodicCertificate c = run.run();
      a.decided = true;
      a.seconds = detail::seconds_since(ta);
      attempts.push_back(a);
      c.attempts = attempts;
      c.statement = statement(q, c, where_text(q));
      if (solution) *solution = run.newton_point;
      c.seconds = detail::seconds_since(t0);
      return c;
    } catch (const Attempt1::NotFound& nf) {
      a.reason = nf.what();
      found = false;
    } catch (const NotCertified& nc) {
      a.reason = nc.what();
      found = true;
    } catch (const Undecided& u) {
      a.reason = std::string("undecided: ") + u.what();
      found = true;
    }
    a.seconds = detail::seconds_since(ta);
    attempts.push_back(a);
    if (solution && run.newton_point) *solution = run.newton_point;
    if (!found && !chained && !q.guess) break;  // a grid search that found nothing at all: more bits won't help
  }
  best.outcome = found ? PeriodicOutcome::undecided : PeriodicOutcome::not_found;
  best.attempts = attempts;
  best.reason = attempts.empty() ? "" : attempts.back().reason;
  best.statement = found ? "Not certified at " + std::to_string(attempts.back().bits) +
                               " bits (the largest precision tried): " + best.reason
                         : "No period-" + std::to_string(q.period) + " orbit was found to certify: " + best.reason +
                               ". Nothing is claimed.";
  best.seconds = detail::seconds_since(t0);
  return best;
}

void compare_with_double(const PeriodicQuestion& q, PeriodicCertificate& c) {
  // The double Newton orbit from the same start, at the nearest double of the parameter.
  Decimal mid = parameter_of(q.model, q.vary);
  if (q.range) mid = *Decimal::parse(exact_decimal((q.range->first + q.range->second) / 2));
  const Model<double> m = make_model<double>(with_parameter(q.model, q.vary, mid), 53);
  const PeriodicOrbit<double> o =
      q.guess ? find_periodic(m, q.period, make_state<double>(*q.guess, 53), q.newton) : search_periodic(m, q.period, q.newton);
  if (!o.converged || o.points.empty()) return;
  c.double_theta = ScalarTraits<double>::to_string(o.points[0].theta);
  c.double_v = ScalarTraits<double>::to_string(o.points[0].v);
  if (!c.certified) return;
  // Distance to the nearest of the orbit's point boxes (Newton may land on another point of
  // the cycle), max(|d theta|, |d v| / max(1, |v|)); 0 inside. In double: a report, not a proof.
  double best = std::numeric_limits<double>::infinity();
  const double t = o.points[0].theta, w = o.points[0].v;
  for (const EnclosedOrbitPoint& p : c.points) {
    auto gap = [](double x, const Enclosure& e) {
      const double lo = std::strtod(e.lo.c_str(), nullptr), hi = std::strtod(e.hi.c_str(), nullptr);
      return x < lo ? lo - x : x > hi ? x - hi : 0.0;
    };
    best = std::min(best, std::max(gap(t, p.theta), gap(w, p.v) / std::max(1.0, std::fabs(w))));
  }
  c.double_distance = best;
}

}  // namespace

PeriodicCertificate certify_periodic(const PeriodicQuestion& q) {
  if (q.guess) {
    PeriodicCertificate c = certify_with_guess(q, std::nullopt, nullptr);
    compare_with_double(q, c);
    return c;
  }
  // No guess: search the grid once, in double, and start every precision of the schedule
  // (and the double comparison) from the orbit found, instead of a grid search per precision.
  Decimal mid = parameter_of(q.model, q.vary);
  if (q.range) mid = *Decimal::parse(exact_decimal((q.range->first + q.range->second) / 2));
  const PeriodicOrbit<double> o =
      search_periodic(make_model<double>(with_parameter(q.model, q.vary, mid), 53), q.period, q.newton);
  if (!o.converged || o.points.empty()) {
    PeriodicCertificate c = certify_with_guess(q, std::nullopt, nullptr);  // reports not_found at 64 bits
    return c;
  }
  PeriodicQuestion found = q;
  found.guess = InitialCondition{*Decimal::parse(ScalarTraits<double>::to_string(o.points[0].theta)),
                                 *Decimal::parse(ScalarTraits<double>::to_string(o.points[0].v))};
  PeriodicCertificate c = certify_with_guess(found, std::nullopt, nullptr);
  compare_with_double(found, c);
  return c;
}

PeriodicRangeReport certify_periodic_range(const PeriodicQuestion& q) {
  if (!q.range) throw InputError("range", "is required");
  const auto t0 = std::chrono::steady_clock::now();
  PeriodicRangeReport rep;
  int runs = 0;
  std::optional<State<Mpfr>> chain;
  std::function<void(const mpq_class&, const mpq_class&, int)> rec = [&](const mpq_class& lo, const mpq_class& hi,
                                                                         int depth) {
    PeriodicQuestion sub = q;
    sub.range = std::make_pair(lo, hi);
    std::optional<State<Mpfr>> next;
    PeriodicCertificate c = certify_with_guess(sub, chain, &next);
    ++runs;
    if (!c.certified && c.outcome != PeriodicOutcome::not_found && depth < q.max_depth && runs + 2 <= q.max_pieces) {
      const mpq_class mid = (lo + hi) / 2;
      rec(lo, mid, depth + 1);
      rec(mid, hi, depth + 1);
      return;
    }
    if (c.certified && next) chain = next;
    rep.pieces.push_back({lo, hi, std::move(c)});
  };
  rec(q.range->first, q.range->second, 0);
  rep.uncertified_length = 0;
  std::set<std::string> sequences;
  for (const PeriodicPiece& p : rep.pieces) {
    if (!p.cert.certified) rep.uncertified_length += p.hi - p.lo;
    else {
      std::string seq;
      for (const std::string& e : p.cert.events) seq += e + " ";
      sequences.insert(seq);
    }
  }
  std::ostringstream t;
  const std::string par = name(q.vary);
  t << "For every " << par << " in [" << exact_decimal(q.range->first) << ", " << exact_decimal(q.range->second) << "]";
  if (rep.uncertified_length != 0) t << " except a set of total length " << exact_decimal(rep.uncertified_length);
  size_t released = 0, krawczyk = 0;  // certified pieces by how they were proved
  for (const PeriodicPiece& p : rep.pieces)
    if (p.cert.certified) ++(p.cert.outcome == PeriodicOutcome::through_release ? released : krawczyk);
  t << ", the map has a period-" << q.period << " orbit, proved on " << rep.pieces.size() << " piece(s)";
  if (released == 0) t << " by the Krawczyk operator, each with its own box (unique in it)";
  else if (krawczyk == 0)
    t << " through the release state, whose interval orbit over each piece sticks and returns to it (a superstable sticking orbit)";
  else
    t << " (" << released << " through the release state, " << krawczyk << " by the Krawczyk operator, each with its own box, unique in it)";
  if (sequences.size() == 1) t << ", all with the same event sequence";
  else if (sequences.size() > 1) t << "; the event sequence changes between pieces (" << sequences.size() << " sequences)";
  t << ".";
  if (rep.uncertified_length == mpq_class(q.range->second - q.range->first)) {
    t.str("");
    t << "Nothing certified for " << par << " in [" << exact_decimal(q.range->first) << ", "
      << exact_decimal(q.range->second) << "].";
  }
  rep.theorem = t.str();
  rep.seconds = detail::seconds_since(t0);
  return rep;
}

}  // namespace bouncer
