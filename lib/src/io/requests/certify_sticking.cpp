#include "bouncer/io/requests/certify_sticking.hpp"

#include <string>
#include <utility>
#include <vector>

namespace bouncer {

namespace {

std::pair<mpq_class, mpq_class> parse_a_range(const std::string& text) {
  const auto colon = text.find(':');
  if (colon == std::string::npos) throw InputError("a-range", "must be A0:A1 with 0 < A0 < A1 (got '" + text + "')");
  const Decimal lo = parse_decimal("a-range", text.substr(0, colon));
  const Decimal hi = parse_decimal("a-range", text.substr(colon + 1));
  if (!(Decimal::from_int(0) < lo) || !(lo < hi))
    throw InputError("a-range", "must be A0:A1 with 0 < A0 < A1 (got '" + text + "')");
  if (hi > *Decimal::parse("1e9")) throw InputError("a-range", "A1 must be <= 1e9 (got '" + text + "')");
  return {lo.value(), hi.value()};
}

}  // namespace

void certify_sticking_defaults(Options& o) {
  if (!o.has("model")) o.set("model", "constant");
  // A smooth wall's default start is its release state (from_release), which no decimal is.
  if (o.get_or("wall", "") == "sine") return;
  if (!o.has("theta")) o.set("theta", "0.5");
  if (!o.has("v")) o.set("v", "4");
}

CertifyStickingRequest certify_sticking_request(const Options& given) {
  Options o = given;
  certify_sticking_defaults(o);
  const bool ranged = o.has("a-range");
  if (ranged && o.has("a")) throw InputError("a-range", "give either --a or --a-range, not both");
  if (!ranged && !o.has("a")) throw InputError("a", "is required (or --a-range A0:A1)");
  CertifyStickingRequest r;
  StickingQuestion& q = r.question;
  std::optional<std::pair<mpq_class, mpq_class>> range;
  Options parse = o;
  if (ranged) {
    range = parse_a_range(o.get("a-range"));
    parse.set("a", o.get("a-range").substr(0, o.get("a-range").find(':')));
  }
  q.model = model_from(parse);
  if (q.model.law != Law::constant)
    throw InputError("model", "certify-sticking needs --model constant (its certified collapse test is the "
                              "constant-restitution threshold; velocity-dependent collapse, which does occur: "
                              "bouncer orbit --model veldep --veldep-collapse on)");
  q.from_release = q.model.wall.shape == WallShape::sine && !o.has("theta") && !o.has("v");
  if (!q.from_release) {
    const std::vector<InitialCondition> ic = initial_conditions_from(parse, q.model);
    if (ic.size() != 1) throw InputError("theta", "takes one initial condition");
    q.start = ic[0];
  }
  q.a_range = range;
  q.max_steps = integer_from(o, "max-steps", 1, 1000000000LL, 100000);
  q.schedule.max_bits = integer_from(o, "max-bits", kMinBits, kMaxBits, 4096);
  // "double" (the default): interval:double first, then MPFI from 64 bits; BITS: MPFI only.
  const std::string start = o.get_or("start-bits", "double");
  q.schedule.double_first = start == "double";
  if (!q.schedule.double_first && (start.empty() || start.find_first_not_of("0123456789") != std::string::npos))
    throw InputError("start-bits", "'" + start + "' (allowed: double, or BITS with " + std::to_string(kMinBits) +
                                       " <= BITS <= " + std::to_string(kMaxBits) + ")");
  q.schedule.start_bits = q.schedule.double_first ? 64 : integer_from(o, "start-bits", kMinBits, kMaxBits, 64);
  if (q.schedule.start_bits > q.schedule.max_bits)
    throw InputError("start-bits", "must be <= --max-bits (" + std::to_string(q.schedule.max_bits) + ")");
  q.method = parse_enclosure_method("method", o.get_or("method", "lohner"));
  const std::string pa = o.get_or("prove-attractor", "on");
  if (pa != "on" && pa != "off") throw InputError("prove-attractor", "must be on or off (got '" + pa + "')");
  q.prove_attractor = pa == "on";
  r.range.max_depth = static_cast<int>(integer_from(o, "max-depth", 0, 40, 10));
  r.range.max_pieces = static_cast<int>(integer_from(o, "max-pieces", 1, 100000, 400));
  if (!ranged && (o.has("max-depth") || o.has("max-pieces")))
    throw InputError(o.has("max-depth") ? "max-depth" : "max-pieces", "is only used with --a-range");
  return r;
}

}  // namespace bouncer
