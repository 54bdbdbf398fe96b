#include "bouncer/io/requests/continue.hpp"

#include <string>
#include <tuple>

#include "bouncer/io/options.hpp"
#include "bouncer/io/requests/guess.hpp"

namespace bouncer {

ContinueRequest continue_request(const Options& given) {
  ContinueRequest r;
  const std::string vary = given.get_or("vary", "a");
  if (vary != "a" && vary != "eps" && vary != "c") throw InputError("vary", "must be a, eps or c (got '" + vary + "')");
  r.vary = parse_parameter("vary", vary);
  if (!given.has("range")) throw InputError("range", "is required (LO:HI, the interval of " + vary + ")");
  if (!given.has("period")) throw InputError("period", "is required (an integer in [1, " + std::to_string(kMaxBranchPeriod) + "])");
  if (!given.has("guess")) throw InputError("guess", "is required (theta,v of a point near the period-q orbit)");
  // The varied parameter must belong to the model (checked before the model is built, so
  // that the message names --vary rather than the parameter filled in below).
  const Law law = parse_law("model", given.get("model"));
  if (r.vary == Parameter::eps && law != Law::constant) throw InputError("vary", "eps can only vary with --model constant");
  if (r.vary == Parameter::c && law != Law::veldep) throw InputError("vary", "c can only vary with --model veldep");
  Options o = given;
  // The varied parameter starts at the range's low end unless given.
  default_to_range_start(o, vary);
  r.model = model_from(o);
  std::tie(r.lo, r.hi) = parse_range("range", o.get("range"));
  validate_range_ends(r.model, r.vary, "range", r.lo, r.hi);
  const Decimal& start = parameter_of(r.model, r.vary);
  if (start < r.lo || r.hi < start)
    throw InputError(vary, "the start value " + start.text() + " must lie in the range [" + r.lo.text() + ", " +
                               r.hi.text() + "]");
  r.period = integer_from(o, "period", 1, kMaxBranchPeriod, 0);
  r.guess = *guess_from(o, r.model);
  r.precision = analysis_precision(o, "continue");
  if (o.has("step")) {
    const Decimal s = parse_decimal("step", o.get("step"));
    const double range = r.hi.approx() - r.lo.approx();
    if (!(s.approx() > 0) || s.approx() > range)
      throw InputError("step", "must be a decimal in (0, HI - LO] = (0, " + std::to_string(range) + "] (got " + s.text() + ")");
    r.opt.step = s.approx();
  }
  r.opt.max_points = integer_from(o, "max-points", 2, 100000, 2000);
  r.opt.newton.max_iter = integer_from(o, "max-iter", 1, 10000, 30);
  if (o.has("beyond")) {
    const Decimal b = parse_decimal("beyond", o.get("beyond"));
    if (!(b.approx() > 0) || b.approx() > 0.1)
      throw InputError("beyond", "must be a decimal in (0, 0.1] (relative distance past a*; got " + b.text() + ")");
    r.opt.beyond = b.approx();
  }
  r.opt.classify = classify_options_from(o);
  const std::string certify = o.get_or("certify", "false");
  if (certify != "true" && certify != "false") throw InputError("certify", "must be true or false");
  r.certify = certify == "true";
  return r;
}

}  // namespace bouncer
