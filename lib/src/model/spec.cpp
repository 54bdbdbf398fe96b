#include "bouncer/model/spec.hpp"

#include <map>
#include <sstream>

#include "bouncer/scalar/traits.hpp"

namespace bouncer {

const char* name(Law l) {
  switch (l) {
    case Law::elastic: return "elastic";
    case Law::constant: return "constant";
    case Law::veldep: return "veldep";
  }
  return "?";
}

const char* name(DownwardSticking d) { return d == DownwardSticking::paper ? "paper" : "impact"; }

std::string allowed_range(const std::string& field) {
  static const std::map<std::string, std::string> ranges{
      {"a", "a decimal with 0 < a <= 1e9"},
      {"eps", "a decimal in [0, 1]"},
      {"c", "a decimal > 0"},
      {"theta", "a decimal in [0, 1)"},
      {"v", "a decimal >= the wall velocity at theta, <= 1e15"},
      {"model", "elastic, constant or veldep"},
  };
  auto it = ranges.find(field);
  return it == ranges.end() ? "" : it->second;
}

Decimal parse_decimal(const std::string& field, const std::string& text) {
  auto d = Decimal::parse(text);
  if (!d) {
    const std::string range = allowed_range(field);
    throw InputError(field, "'" + text + "' is not a finite decimal number (allowed: " +
                                (range.empty() ? "a decimal such as 28.82 or 1e-9" : range) + ")");
  }
  return *d;
}

Law parse_law(const std::string& field, const std::string& text) {
  if (text == "elastic") return Law::elastic;
  if (text == "constant") return Law::constant;
  if (text == "veldep") return Law::veldep;
  throw InputError(field, "unknown model '" + text + "' (allowed: elastic, constant, veldep)");
}

DownwardSticking parse_downward(const std::string& field, const std::string& text) {
  if (text == "paper") return DownwardSticking::paper;
  if (text == "impact") return DownwardSticking::impact;
  throw InputError(field, "unknown downward-sticking convention '" + text + "' (allowed: paper, impact)");
}

namespace {

std::vector<std::string> split(const std::string& s, char sep) {
  std::vector<std::string> out;
  std::string cur;
  std::istringstream in(s);
  while (std::getline(in, cur, sep)) out.push_back(cur);
  if (!s.empty() && s.back() == sep) out.push_back("");
  return out;
}

// Rising for a fraction r of the period from -1 to 1, then falling back.
WallSpec asymmetric(const std::string& field, const std::string& text, const std::string& r_text) {
  Decimal r = parse_decimal(field, r_text);
  if (!(r > Decimal::from_int(0) && r < Decimal::from_int(1)))
    throw InputError(field, "rise fraction " + r_text + " out of range (allowed: 0 < R < 1)");
  return WallSpec{text, {Decimal::from_int(0), r}, {Decimal::from_int(-1), Decimal::from_int(1)}};
}

}  // namespace

WallSpec parse_wall(const std::string& field, const std::string& text) {
  if (text == "triangle") return asymmetric(field, text, "0.5");
  if (text == "sine") return WallSpec{text, {}, {}, WallShape::sine};
  // A continuous stand-in for a sawtooth: slow rise for 9/10 of the period, fast drop.
  if (text == "sawtooth") return asymmetric(field, text, "0.9");
  const std::string asym = "asymmetric:", knots = "knots:";
  if (text.rfind(asym, 0) == 0) return asymmetric(field, text, text.substr(asym.size()));
  if (text.rfind(knots, 0) == 0) {
    // knots:s0:h0,s1:h1,... with s0 = 0
    WallSpec w{text, {}, {}};
    for (const std::string& pair : split(text.substr(knots.size()), ',')) {
      auto sh = split(pair, ':');
      if (sh.size() != 2) throw InputError(field, "knot '" + pair + "' is not THETA:HEIGHT");
      w.knots.push_back(parse_decimal(field, sh[0]));
      w.heights.push_back(parse_decimal(field, sh[1]));
    }
    return w;
  }
  throw InputError(field, "unknown wall '" + text + "' (allowed: triangle, sawtooth, asymmetric:R with 0<R<1, knots:0:H0,S1:H1,..., sine)");
}

void validate(const ModelSpec& m) {
  const Decimal zero = Decimal::from_int(0), one = Decimal::from_int(1);
  if (!(m.a > zero)) throw InputError("a", "must be > 0 (got " + m.a.text() + ")");
  if (m.a > Decimal::from_int(1000000000)) throw InputError("a", "must be <= 1e9 (got " + m.a.text() + ")");
  if (m.law == Law::constant && !(m.eps >= zero && m.eps <= one))
    throw InputError("eps", "must be in [0, 1] (got " + m.eps.text() + ")");
  if (m.law == Law::veldep && !(m.c > zero)) throw InputError("c", "must be > 0 (got " + m.c.text() + ")");
  const WallSpec& w = m.wall;
  if (w.shape == WallShape::sine) {
    if (!(m.a < *Decimal::parse(kFourPiSquaredBelow)))
      throw InputError("a", "must be < 4 pi^2 = " + std::string(kFourPiSquaredBelow) +
                                "... with --wall sine (got " + m.a.text() +
                                "; at larger gravity the wall never throws a riding particle off)");
    if (m.veldep_collapse) throw InputError("veldep-collapse", "is not available with --wall sine (allowed: off)");
    return;
  }
  if (w.knots.size() < 2 || w.knots.size() != w.heights.size())
    throw InputError("wall", "needs at least two knots THETA:HEIGHT");
  if (!(w.knots[0] == zero)) throw InputError("wall", "the first knot must be at theta = 0");
  for (size_t j = 1; j < w.knots.size(); ++j)
    if (!(w.knots[j - 1] < w.knots[j]) || !(w.knots[j] < one))
      throw InputError("wall", "knots must increase strictly within [0, 1)");
  bool flat = true;
  for (size_t j = 1; j < w.heights.size(); ++j) flat = flat && w.heights[j] == w.heights[0];
  if (flat) throw InputError("wall", "a flat wall never turns: at least two different heights");
}

void require_piecewise_wall(const ModelSpec& m, const std::string& what) {
  if (m.wall.shape == WallShape::sine)
    throw InputError("wall", what + " knows only piecewise-linear walls (allowed: triangle, sawtooth, asymmetric:R, knots:...; not sine)");
}

int wall_segment_exact(const WallSpec& w, const mpq_class& theta) {
  int j = 0;
  for (size_t k = 1; k < w.knots.size(); ++k)
    if (w.knots[k].value() <= theta) j = static_cast<int>(k);
  return j;
}

mpq_class wall_velocity_exact(const WallSpec& w, const mpq_class& theta) {
  const size_t n = w.knots.size();
  const size_t j = static_cast<size_t>(wall_segment_exact(w, theta));
  const mpq_class s0 = w.knots[j].value(), h0 = w.heights[j].value();
  const mpq_class s1 = j + 1 < n ? w.knots[j + 1].value() : mpq_class(1);
  const mpq_class h1 = j + 1 < n ? w.heights[j + 1].value() : w.heights[0].value();
  return (h1 - h0) / (s1 - s0);
}

void validate(const ModelSpec& m, const InitialCondition& ic, const std::string& theta_field,
              const std::string& v_field) {
  const Decimal zero = Decimal::from_int(0), one = Decimal::from_int(1);
  if (!(ic.theta >= zero && ic.theta < one))
    throw InputError(theta_field, "must be in [0, 1) (got " + ic.theta.text() + ")");
  if (m.wall.shape == WallShape::sine) {
    // u = 2 pi cos(2 pi theta) is irrational but at four phases: compared with v by the
    // interval type's own enclosures (scalar.cpp, trig_2pi_enclosure) at 256 bits.
    using Ti = ScalarTraits<Mpfi>;
    const Mpfi u = Ti::two_pi(256) * Ti::cos_2pi(Ti::from_decimal(ic.theta.text(), 256));
    const Mpfi v = Ti::from_decimal(ic.v.text(), 256);
    const Truth inside = Ti::lt(v, u);
    if (inside == Truth::yes)
      throw InputError(v_field, "must be >= the wall velocity 2 pi cos(2 pi theta) = " +
                                    mpfr_to_string_digits(&u.get()->left, MPFR_RNDD, 12) + "... at theta = " +
                                    ic.theta.text() + " (got " + ic.v.text() + "; the particle would be inside the wall; " +
                                    "a state on the wall printed in double, such as a release, starts at rest with v = " +
                                    mpfr_to_string_digits(&u.get()->right, MPFR_RNDU, 17) + ")");
    if (inside != Truth::no)
      throw InputError(v_field, "cannot be told from the wall velocity 2 pi cos(2 pi theta) at theta = " + ic.theta.text() +
                                    " at 256 bits (got " + ic.v.text() + "): start a little above it");
    if (ic.v > Decimal::parse("1e15").value())
      throw InputError(v_field, "must be <= 1e15 (got " + ic.v.text() + ")");
    return;
  }
  const mpq_class u = wall_velocity_exact(m.wall, ic.theta.value());
  if (ic.v.value() < u) {
    std::ostringstream msg;
    msg << "must be >= the wall velocity " << u.get_str() << " at theta = " << ic.theta.text()
        << " (got " << ic.v.text() << "; the particle would be inside the wall)";
    throw InputError(v_field, msg.str());
  }
  if (ic.v > Decimal::parse("1e15").value())
    throw InputError(v_field, "must be <= 1e15 (got " + ic.v.text() + ")");
}

const char* name(Parameter p) {
  switch (p) {
    case Parameter::a: return "a";
    case Parameter::eps: return "eps";
    case Parameter::c: return "c";
  }
  return "?";
}

Parameter parse_parameter(const std::string& field, const std::string& text) {
  if (text == "a") return Parameter::a;
  if (text == "eps") return Parameter::eps;
  if (text == "c") return Parameter::c;
  throw InputError(field, "must be a, eps or c (got '" + text + "')");
}

const Decimal& parameter_of(const ModelSpec& m, Parameter p) {
  return p == Parameter::a ? m.a : p == Parameter::eps ? m.eps : m.c;
}

ModelSpec with_parameter(ModelSpec m, Parameter p, const Decimal& value) {
  (p == Parameter::a ? m.a : p == Parameter::eps ? m.eps : m.c) = value;
  return m;
}

}  // namespace bouncer
