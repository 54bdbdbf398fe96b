// Accelerator ladders of the elastic map (verify/accelerator.hpp): exact rational checks.
#include "bouncer/verify/accelerator.hpp"

#include <algorithm>
#include <sstream>

#include "bouncer/verify/sticking.hpp"  // exact_decimal

namespace bouncer {

namespace {

mpq_class floor_q(const mpq_class& x) {
  mpz_class f;
  mpz_fdiv_q(f.get_mpz_t(), x.get_num_mpz_t(), x.get_den_mpz_t());
  return mpq_class(f);
}

// f(phi) for any phi (periodic), exact.
mpq_class wall_height(const WallSpec& w, const mpq_class& phi) {
  const mpq_class t = phi - floor_q(phi);
  const size_t j = static_cast<size_t>(wall_segment_exact(w, t));
  return w.heights[j].value() + wall_velocity_exact(w, t) * (t - w.knots[j].value());
}

std::string q(const mpq_class& x) { return exact_decimal(x); }

}  // namespace

LadderCertificate certify_ladder(const ModelSpec& m, const InitialCondition& start, const Decimal& lift) {
  if (m.law != Law::elastic) throw InputError("model", "accelerator ladders (--lift) need --model elastic");
  LadderCertificate c;
  const WallSpec& w = m.wall;
  const mpq_class a = m.a.value(), th = start.theta.value(), v0 = start.v.value(), D = lift.value();
  const int j = wall_segment_exact(w, th);
  c.u = wall_velocity_exact(w, th);
  c.D = 2 * c.u;
  auto fail = [&](const std::string& why) {
    c.statement = "Not an exact accelerator ladder: " + why + ". Nothing else is claimed.";
    return c;
  };
  if (w.knots[static_cast<size_t>(j)].value() == th) return fail("theta0 is a wall knot (a corner)");
  if (c.u <= 0) return fail("the wall moves down (or is flat) at theta0, u = " + q(c.u) + ": elastic impacts there lose speed");
  if (D != c.D) return fail("the gain per impact is D = 2u = " + q(c.D) + ", not " + lift.text());
  c.m0 = 2 * v0 / a;
  c.J = 2 * D / a;
  if (c.m0.get_den() != 1)
    return fail("the first flight lasts 2 v0 / a = " + q(c.m0) + " periods, not a whole number, so it does not land at its launch phase");
  if (c.J.get_den() != 1)
    return fail("each impact lengthens the flight by 2D/a = " + q(c.J) + " periods, not a whole number (a = 4u/J is needed, e.g. 16/J on the triangle)");
  if (!(v0 > c.u)) return fail("v0 = " + q(v0) + " does not exceed the wall's velocity u = " + q(c.u) + " (the particle does not leave the wall)");
  // Flight 0: the gap at every knot time in (0, m0).
  const mpq_class h0 = wall_height(w, th);
  bool first = true;
  const long periods = mpz_class(c.m0.get_num()).get_si();
  for (long p = -1; p <= periods; ++p) {
    for (const Decimal& s : w.knots) {
      const mpq_class t = mpq_class(p) + s.value() - th;
      if (!(t > 0) || !(t < c.m0)) continue;
      const mpq_class g = h0 - wall_height(w, th + t) + a * t * (c.m0 - t) / 2;
      if (first || g < c.min_gap) c.min_gap = g;
      first = false;
      if (!(g > 0)) return fail("the first flight meets the wall at t = " + q(t) + " (gap " + q(g) + ")");
    }
  }
  // Flights k >= 1 away from their first and last period.
  mpq_class top = w.heights[0].value();
  for (const Decimal& h : w.heights) top = std::max(top, h.value());
  const mpq_class middle = a * (c.m0 + c.J - 1) / 2 - (top - h0);
  if (!(middle > 0)) return fail("the bound a (m1 - 1)/2 - (top - h0) = " + q(middle) + " for the later flights is not positive");
  c.certified = true;
  std::ostringstream s;
  s << "Theorem (exact rational arithmetic): from (theta, v) = (" << start.theta.text() << ", " << start.v.text()
    << ") the elastic map gives (theta, v + " << q(D) << "k) after k impacts, for every k >= 0: an accelerator mode of period 1 "
    << "with gain " << q(D) << " per impact (v grows linearly, without bound). Flight k lasts " << q(c.m0) << " + " << q(c.J)
    << "k whole periods and lands at its launch phase and height; the elastic law on the rising wall (u = " << q(c.u)
    << ") adds 2u. No flight meets the wall early: the first flight's least gap at the knots it passes is " << q(c.min_gap)
    << ", and every later flight keeps a gap of at least " << q(middle) << " away from its first and last period.";
  c.statement = s.str();
  return c;
}

}  // namespace bouncer
