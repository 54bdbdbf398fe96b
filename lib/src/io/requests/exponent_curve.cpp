// `bouncer lyapunov --vary`'s request from its options (io/requests/exponent_curve.hpp).
#include "bouncer/io/requests/exponent_curve.hpp"

#include "bouncer/io/options.hpp"

namespace bouncer {

ExponentCurveRequest exponent_curve_request(const Options& given) {
  ExponentCurveRequest r;
  const std::string vary = given.get("vary");
  Options o = given;
  default_to_range_start(o, vary);
  r.model = model_from(o);
  r.vary = parse_parameter("vary", vary);
  if (r.vary == Parameter::eps && r.model.law != Law::constant) throw InputError("vary", "eps can only vary with --model constant");
  if (r.vary == Parameter::c && r.model.law != Law::veldep) throw InputError("vary", "c can only vary with --model veldep");
  if (!o.has("range")) throw InputError("range", "is needed with --vary: LO:HI (decimals, LO < HI)");
  std::tie(r.lo, r.hi) = parse_range("range", o.get("range"));
  validate_range_ends(r.model, r.vary, "range", r.lo, r.hi);
  r.samples = integer_from(o, "samples", 1, 100000, 100);
  r.ics = integer_from(o, "ics", 1, 1000, 1);
  r.lyapunov.transient = integer_from(o, "transient", 0, 1000000000LL, 1000);
  r.lyapunov.steps = integer_from(o, "steps", 1, 1000000000LL, 10000);
  r.lyapunov.blocks = integer_from(o, "blocks", 1, 10000, 20);
  // The class is decided where the measured window ended (the orbit has then run
  // transient + steps steps): no further transient, the classifier's default window.
  Options co = o;
  co.set("transient", "0");
  co.values.erase("steps");
  r.classify = classify_options_from(co);
  r.precision = analysis_precision(o, "lyapunov");
  if (o.has("theta") || o.has("v")) r.start = start_from(o, r.model);
  return r;
}

}  // namespace bouncer
