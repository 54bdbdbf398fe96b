// Certified periodic orbits: existence and local uniqueness of a period-Q orbit of the
// impact map by the Krawczyk operator, with enclosures of its points and multipliers, its
// event sequence and its minimal period; at one parameter value (an exact decimal,
// enclosed) or for every value of a parameter interval.
//
// The map P is smooth on every box over which all of its branch decisions are taken the
// same way. The interval step (ImpactMap<Mpfi>) and the interval-dual step
// (ImpactMap<Dual<Mpfi>>) decide every branch for the whole box or throw Undecided, so on a
// box where they finish, the event sequence is fixed and P^Q is one smooth formula.
//
// Unknowns y (two of theta, v, parameter) and a "free" scalar z with an interval Z:
//   isolated orbits:  y = (theta, v), z = the parameter p,
//                     F(y; z) = P^Q(theta, v; p) - (theta, v);
//   families:         y = (v, p),     z = theta,
//                     F(y; z) = P^Q(theta, v; p) - (theta, v).
// theta needs no wrapping: theta = 0 is a wall knot, where no certified box can sit, so both
// sides of F's theta component lie in (0, 1).
// Krawczyk with a parameter (mean value form in y and z):
//   K(Y) = y^ - C F(y^; z^) - C F_z(Y, Z)(Z - z^) + (I - C F_y(Y, Z))(Y - y^),
// C an approximate inverse of mid F_y (any C is valid). If K(Y) lies in the interior of Y,
// then for every z in Z there is exactly one y in Y with F(y; z) = 0 (the standard argument:
// y -> y - C F(y; z) is a contraction of Y into itself; C is then invertible). The
// derivative enclosures over Y x Z come from two interval-dual runs of Q steps (seeds
// (theta, v) and then p), through the same step as every other scalar type.
//
// Long periods (multiple shooting, from period 12 on, or where P^Q fails): the unknowns are
// all Q points, the rows P(x_i; z) - x_{i+1 mod Q}, each step over its own point's box (the
// composed map widens a box by the product of the Q steps' derivative norms); the same
// Krawczyk argument in 2Q dimensions, with a double LU preconditioner
// (src/verify/sparse_krawczyk.hpp). Its multipliers: the determinant as the product of the
// steps' determinants, the trace from the product of the steps' Jacobians kept in Lohner's
// form (a point rotation times an interval matrix), which avoids the wrapping of a plain
// interval product.
//
// Families (a multiplier exactly 1, e.g. the paper's eq. 5 fixed points, for which
// F_(theta, v) is singular) are certified on the quotient by the free direction theta: for
// every theta in Z there is exactly one (v, p) in Y. That proves a curve of period-Q points
// crossing the strip, with p inside an enclosure of small width; that the curve has
// exactly constant p (a codimension-one coincidence) is beyond what intervals can prove,
// and the statement says so.
//
// Orbits through a sticking (or ride) step pass through the release state R, a constant of
// the wall: the orbit of R is followed in intervals from R exactly, and it is a period-Q
// orbit iff the first step that ends at a release is step Q, which ends at R again.
#pragma once

#include <gmpxx.h>

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "bouncer/analysis/periodic.hpp"
#include "bouncer/model/spec.hpp"
#include "bouncer/verify/escalation.hpp"

namespace bouncer {

// Parameter (a | eps | c), its parsing and parameter_of / with_parameter: model/spec.hpp.

enum class FamilyMode { automatic, isolated, family };
FamilyMode parse_family_mode(const std::string& field, const std::string& text);

enum class PeriodicOutcome {
  isolated,         // certified: a unique period-Q point in the box (for every parameter)
  family,           // certified: a curve of period-Q points across a theta strip
  through_release,  // certified: the release state's orbit returns to it after Q steps
  not_found,        // Newton found no period-Q orbit to certify (nothing is claimed)
  undecided,        // Newton found one, but no precision of the schedule certified it
};
const char* name(PeriodicOutcome o);

// The unknowns of a proof about a period-Q orbit (here, and the border-collision, period
// doubling and fold proofs of verify/border_collision.hpp): the first orbit point (composed:
// P^Q(x_0) = x_0, the Q steps composed in one interval evaluation), or all Q points
// (multiple shooting: P(x_i) = x_{i+1 mod Q}, each step over its own point's box). The
// composed map widens a box by the product of the Q steps' derivative norms (about 2^66 over
// a period-66 orbit), so long periods need shooting; short ones are quicker composed.
// automatic: shooting first from period kShootingFrom = 12 on, composed first below, the
// other where the first fails.
enum class Formulation { automatic, composed, shooting };
constexpr long kShootingFrom = 12;
Formulation parse_formulation(const std::string& field, const std::string& text);

// The longest period certify-periodic takes: 2000. Shooting's preconditioner is a dense
// (2Q)^2 double matrix (128 MB) with an LU of (2Q)^3 flops (about 20 s at Q = 2000).
constexpr long kMaxCertifiedPeriod = 2000;

struct PeriodicQuestion {
  ModelSpec model;
  long period = 1;
  std::optional<InitialCondition> guess;  // else Newton from a grid in the trapping region
  Parameter vary = Parameter::a;          // the parameter of `range` (and of families)
  std::optional<std::pair<mpq_class, mpq_class>> range;  // certify for every value in it
  FamilyMode family = FamilyMode::automatic;
  Formulation formulation = Formulation::automatic;  // of isolated orbits
  EscalationSchedule schedule{64, 1024, false};
  int max_depth = 8;      // parameter ranges: bisection depth
  int max_pieces = 256;   // parameter ranges: at most this many pieces
  NewtonOptions newton;
};

// An interval as exact endpoint texts (each end rounded outward, round-trips at `bits`).
struct Enclosure {
  std::string lo, hi;
  double mid = 0;      // for display and plots
  double width = 0;
};

// (Not named CertifiedPoint: verify/certified_point.hpp has that class in this namespace, and
// two classes of one name break the one-definition rule: their inline destructors were mixed.)
struct EnclosedOrbitPoint {
  Enclosure theta, v;
};

struct MultiplierEnclosure {
  Enclosure trace, det;   // of the Jacobian of P^Q over the final box
  std::string kind;       // "real" (discriminant > 0), "complex" (< 0) or "undecided"
  Enclosure mu[2];        // real: the two multipliers, larger first; complex: re, |im|
  Enclosure modulus;      // complex: |mu| = sqrt(det)
};

struct PeriodicCertificate {
  PeriodicOutcome outcome = PeriodicOutcome::undecided;
  bool certified = false;
  // Proved with every orbit point an unknown (multiple shooting: periods >= 12 first, or
  // where the composed map P^Q failed), else with the first point alone.
  bool shooting = false;
  long period = 0;
  long minimal_period = 0;             // certified divisor structure, 0 if undecided
  bool minimal_period_certified = false;
  long bits = 0;                       // the precision that certified (0: none)
  std::vector<EnclosedOrbitPoint> points;  // enclosures of the Q orbit points, in orbit order
  std::vector<std::string> events;     // per step: "impact(seg 0)", "sticking", ...
  std::vector<long long> wall_periods; // per step
  MultiplierEnclosure multipliers;
  std::string stability;               // stable | unstable | neutral-stable | neutral-unstable | undecided | superstable
  // Krawczyk: the box Y and its image K(Y) (unknowns in the order of `unknowns`).
  std::string unknowns;                // "theta, v" or "v, a" ...
  Enclosure box[2], image[2];
  Enclosure free_range;                // Z: the parameter (isolated) or theta (family)
  std::string free_name;
  int inflations = 0;
  // Families: the parameter at theta^ (points[0].theta, thin), and over the widest strip of
  // theta around it that certified: for every theta in strip_theta exactly one (v, p) in
  // strip_v x strip_parameter.
  std::optional<Enclosure> family_parameter;
  std::optional<Enclosure> strip_theta, strip_v, strip_parameter;
  std::string given_parameter;         // the given value vs family_parameter: inside | outside | overlaps
  // The double-precision Newton point, and its distance to the nearest certified point box
  // (max of |d theta| and |d v| / max(1, |v|); 0 inside): how far plain double is off.
  std::string double_theta, double_v;
  std::optional<double> double_distance;
  std::string statement;
  std::string reason;                  // why not certified
  std::vector<Attempt> attempts;
  double seconds = 0;
};

// One certification at one parameter value or over one parameter interval, with precision
// escalation. `guess` overrides the question's (used to chain pieces of a range).
PeriodicCertificate certify_periodic(const PeriodicQuestion& q);

struct PeriodicPiece {
  mpq_class lo, hi;
  PeriodicCertificate cert;
};
struct PeriodicRangeReport {
  std::vector<PeriodicPiece> pieces;   // in order, covering the range
  mpq_class uncertified_length;
  std::string theorem;
  double seconds = 0;
};
// Adaptive bisection of q.range (required): each piece is certified on its own (chained
// from the previous piece's orbit); a piece that fails is bisected.
PeriodicRangeReport certify_periodic_range(const PeriodicQuestion& q);

}  // namespace bouncer
