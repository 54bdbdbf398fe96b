// What a scene asks of the model, in exact decimals, validated once for every front end
// (command line, scene file, tests). Model<T> is built from this for a chosen scalar type.
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

#include "bouncer/base/error.hpp"
#include "bouncer/scalar/decimal.hpp"

namespace bouncer {

// Collision models (paper sec. I, eq. 2 and the eps(v) law).
enum class Law { elastic, constant, veldep };
// What happens when a collapse on a downward-moving wall reaches the wall's upward turn.
//   paper:  the particle keeps riding the wall through the turn and is released at the
//           next downward turn, (1/2, 4) for the triangle (paper sec. II.B.3);
//   impact: the turn is an impact of relative speed u_next - u_prev (8 for the triangle),
//           after which the map goes on (and may stick again).
enum class DownwardSticking { paper, impact };

const char* name(Law);

const char* name(DownwardSticking);

// The wall's shape: piecewise linear (the paper's triangle and its relatives), or the smooth
// sine wall f(theta) = sin(2 pi theta) of the classical bouncer (docs/model.md, "The sine wall").
enum class WallShape : unsigned char { piecewise, sine };

// A continuous periodic piecewise-linear wall: knots 0 = s_0 < s_1 < ... < s_{n-1} < 1 with
// heights h_j; segment j runs from s_j to s_{j+1} (s_n = 1, h_n = h_0). The sine wall has no
// knots.
struct WallSpec {
  std::string text;  // as given: triangle, sawtooth, asymmetric:R, knots:s1:h1,s2:h2,..., sine
  std::vector<Decimal> knots;
  std::vector<Decimal> heights;
  WallShape shape = WallShape::piecewise;
};

// 4 pi^2 = 39.4784176043574344753...: the sine wall's largest downward acceleration. The sine
// wall needs a < 4 pi^2 (validate): at larger gravity the wall never throws a riding particle
// off. These two decimals bracket it (exact), for validation without floating point.
inline constexpr const char* kFourPiSquaredBelow = "39.4784176043574344";
inline constexpr const char* kFourPiSquaredAbove = "39.4784176043574345";

struct ModelSpec {
  Law law = Law::constant;
  Decimal a = Decimal::from_int(24);
  Decimal eps = Decimal::from_int(1);   // used by Law::constant
  Decimal c = Decimal::from_int(1000);  // used by Law::veldep
  WallSpec wall;
  DownwardSticking downward = DownwardSticking::paper;
  // Law::veldep only: end a chatter sequence whose collapse provably completes before the
  // wall turns (bound in README "Velocity-dependent collapse"), as constant eps does.
  bool veldep_collapse = false;
};

// A parameter of the model that a family is followed or certified in (continuation,
// certify-periodic): its name ("a", "eps", "c"), its exact decimal in a spec, and the spec
// with it replaced.
enum class Parameter { a, eps, c };
const char* name(Parameter p);
Parameter parse_parameter(const std::string& field, const std::string& text);
const Decimal& parameter_of(const ModelSpec& m, Parameter p);
ModelSpec with_parameter(ModelSpec m, Parameter p, const Decimal& value);

struct InitialCondition {
  Decimal theta = Decimal::from_int(0);
  Decimal v = Decimal::from_int(4);
};

// The allowed values of a model or initial-condition field, for error messages ("" if none).
std::string allowed_range(const std::string& field);

// Parsers for the text forms; each throws InputError naming `field`.
Decimal parse_decimal(const std::string& field, const std::string& text);
Law parse_law(const std::string& field, const std::string& text);
DownwardSticking parse_downward(const std::string& field, const std::string& text);
WallSpec parse_wall(const std::string& field, const std::string& text);

// Range checks of the model parameters (a > 0, 0 <= eps <= 1, c > 0, wall shape).
void validate(const ModelSpec& m);
// theta in [0, 1) and v at least the wall's velocity at theta (else inside the wall).
void validate(const ModelSpec& m, const InitialCondition& ic, const std::string& theta_field,
              const std::string& v_field);

// The commands and library calls that know only the piecewise-linear wall refuse the sine
// wall with this (an InputError naming --wall and what does support it).
void require_piecewise_wall(const ModelSpec& m, const std::string& what);

// Exact wall quantities (rationals) for validation and for classifying corners; piecewise
// walls only.
mpq_class wall_velocity_exact(const WallSpec& w, const mpq_class& theta);
int wall_segment_exact(const WallSpec& w, const mpq_class& theta);

}  // namespace bouncer
