#include "bouncer/io/requests/certify_periodic.hpp"

#include <string>
#include <utility>

#include "bouncer/io/options.hpp"
#include "bouncer/io/requests/guess.hpp"

namespace bouncer {

CertifyPeriodicRequest certify_periodic_request(const Options& o) {
  static const char* const kRangeKeys[] = {"a-range", "eps-range", "c-range"};
  CertifyPeriodicRequest r;
  PeriodicQuestion& q = r.question;
  // --a-range, --eps-range or --c-range: at most one; it names the varied parameter.
  std::optional<std::string> range_key;
  for (const char* k : kRangeKeys)
    if (o.has(k)) {
      if (range_key) throw InputError(k, "give at most one of --a-range, --eps-range, --c-range");
      range_key = k;
    }
  q.vary = parse_parameter("vary", o.get_or("vary", range_key ? range_key->substr(0, range_key->find('-')) : "a"));
  const std::string par = name(q.vary);
  if (range_key && *range_key != par + "-range") throw InputError("vary", "is " + par + " but the range is --" + *range_key);
  const std::string law = o.get_or("model", "");
  if ((q.vary == Parameter::eps && law != "constant") || (q.vary == Parameter::c && law != "veldep"))
    throw InputError(range_key ? *range_key : "vary",
                     par + " varies only with --model " + (q.vary == Parameter::eps ? "constant" : "veldep"));
  Options parse = o;
  std::optional<std::pair<Decimal, Decimal>> range;
  if (range_key) {
    if (o.has(par)) throw InputError(*range_key, "give either --" + par + " or --" + *range_key + ", not both");
    const std::string text = o.get(*range_key);
    const auto colon = text.find(':');
    if (colon == std::string::npos) throw InputError(*range_key, "must be LO:HI with LO < HI (got '" + text + "')");
    range = std::make_pair(parse_decimal(*range_key, text.substr(0, colon)), parse_decimal(*range_key, text.substr(colon + 1)));
    if (!(range->first < range->second)) throw InputError(*range_key, "needs LO < HI (got '" + text + "')");
    parse.set(par, range->first.text());
  }
  q.model = model_from(parse);
  if (range) {
    validate_range_ends(q.model, q.vary, *range_key, range->first, range->second);
    q.range = std::make_pair(range->first.value(), range->second.value());
  }
  if (!o.has("period")) throw InputError("period", "is required (an integer in [1, " + std::to_string(kMaxCertifiedPeriod) + "])");
  q.period = integer_from(o, "period", 1, kMaxCertifiedPeriod, 1);
  q.guess = guess_from(o, q.model);
  q.family = parse_family_mode("family", o.get_or("family", "auto"));
  q.formulation = parse_formulation("formulation", o.get_or("formulation", "auto"));
  if (o.has("lift")) {
    r.lift = parse_decimal("lift", o.get("lift"));
    if (q.model.law != Law::elastic) throw InputError("lift", "needs --model elastic (accelerator modes are elastic)");
    require_piecewise_wall(q.model, "certify-periodic --lift (its ladder's exact check uses the wall's rational knots)");
    if (q.period != 1)
      throw InputError("lift", "needs --period 1 (exact accelerator modes are ladders of period 1: docs/guide/certified.md, certify-periodic)");
    if (!q.guess) throw InputError("lift", "needs --guess THETA,V (the start of the ladder)");
    if (range) throw InputError("lift", "cannot be combined with a parameter range");
  }
  if (q.family == FamilyMode::family && range)
    throw InputError("family", "on cannot be combined with a parameter range: a family exists at one parameter value "
                               "(its parameter is one of the unknowns)");
  q.schedule.max_bits = integer_from(o, "max-bits", kMinBits, kMaxBits, 1024);
  q.schedule.start_bits = integer_from(o, "start-bits", kMinBits, kMaxBits, 64);
  if (q.schedule.start_bits > q.schedule.max_bits)
    throw InputError("start-bits", "must be <= --max-bits (" + std::to_string(q.schedule.max_bits) + ")");
  q.max_depth = static_cast<int>(integer_from(o, "max-depth", 0, 40, 8));
  q.max_pieces = static_cast<int>(integer_from(o, "max-pieces", 1, 100000, 256));
  if (!range && (o.has("max-depth") || o.has("max-pieces")))
    throw InputError(o.has("max-depth") ? "max-depth" : "max-pieces", "is only used with a parameter range");
  q.newton.max_iter = integer_from(o, "max-iter", 1, 10000, 60);
  q.newton.grid = static_cast<int>(integer_from(o, "grid", 1, 64, 8));
  return r;
}

}  // namespace bouncer
