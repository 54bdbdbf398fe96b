#include "bouncer/io/options.hpp"

#include <algorithm>

namespace bouncer {

std::pair<Decimal, Decimal> parse_range(const std::string& field, const std::string& text, bool allow_equal) {
  const auto colon = text.find(':');
  if (colon == std::string::npos) throw InputError(field, "must be LO:HI (got '" + text + "')");
  const Decimal lo = parse_decimal(field, text.substr(0, colon));
  const Decimal hi = parse_decimal(field, text.substr(colon + 1));
  if (allow_equal ? !(lo <= hi) : !(lo < hi)) throw InputError(field, "needs LO < HI (got '" + text + "')");
  return {lo, hi};
}

std::pair<long, long> parse_grid(const std::string& field, const std::string& text, long limit) {
  const auto x = text.find('x');
  auto whole = [&](const std::string& s) {
    if (s.empty() || s.size() > 7 || s.find_first_not_of("0123456789") != std::string::npos)
      throw InputError(field, "must be NxM with whole numbers 1.." + std::to_string(limit) + " (got '" + text + "')");
    const long n = std::stol(s);
    if (n < 1 || n > limit) throw InputError(field, "must be NxM with 1 <= N, M <= " + std::to_string(limit) + " (got '" + text + "')");
    return n;
  };
  if (x == std::string::npos) throw InputError(field, "must be NxM, e.g. 200x150 (got '" + text + "')");
  return {whole(text.substr(0, x)), whole(text.substr(x + 1))};
}

bool flag_from(const Options& o, const std::string& key) {
  const std::string v = o.get_or(key, "false");
  if (v != "true" && v != "false") throw InputError(key, "must be true or false (got '" + v + "')");
  return v == "true";
}

InitialCondition start_from(const Options& o, const ModelSpec& spec) {
  InitialCondition ic{parse_decimal("theta", o.get("theta")), parse_decimal("v", o.get("v"))};
  validate(spec, ic, "theta", "v");
  return ic;
}

ClassifyOptions classify_options_from(const Options& o) {
  ClassifyOptions c;
  c.transient = integer_from(o, "transient", 0, 10000000000LL, 5000);
  c.steps = integer_from(o, "steps", 8, 1000000000LL, 500);
  c.max_period = integer_from(o, "max-period", 1, 1000000000LL, std::min<long>(64, c.steps / 2));
  if (c.max_period * 2 > c.steps)
    throw InputError("max-period", "must be at most steps/2 (" + std::to_string(c.steps / 2) + ")");
  c.recheck_factor = integer_from(o, "recheck-factor", 0, 1000, 20);
  return c;
}

Precision point_precision(const Options& o) {
  Precision p = precision_from(o);
  if (!p.is_analysis())
    throw InputError("precision", "interval precision is not supported here (use " +
                                      precision_names<AnalysisScalars>(" or ") + ")");
  return p;
}

Precision analysis_precision(const Options& o, const std::string& command) {
  const Precision p = precision_from(o);
  if (!p.is_analysis())
    throw InputError("precision", "'" + p.text() + "' is not available for " + command +
                                      ": it follows one point orbit (allowed: " + precision_names<AnalysisScalars>() + " with " +
                                      std::to_string(kMinBits) + " <= BITS <= " + std::to_string(kMaxBits) +
                                      "; certified answers: certify-sticking, sweep)");
  return p;
}

void default_to_range_start(Options& o, const std::string& vary) {
  if (o.has(vary) || !o.has("range") || (vary != "a" && vary != "eps" && vary != "c")) return;
  const std::string range = o.get("range");
  const auto colon = range.find(':');
  if (colon == std::string::npos) throw InputError("range", "must be LO:HI (got '" + range + "')");
  o.set(vary, parse_decimal("range", range.substr(0, colon)).text());
}

void validate_range_ends(const ModelSpec& m, Parameter p, const std::string& field, const Decimal& lo, const Decimal& hi) {
  for (const Decimal& end : {lo, hi}) {
    try {
      validate(with_parameter(m, p, end));
    } catch (const InputError& e) {
      throw InputError(field, "end " + end.text() + " is outside the model's range (" + e.what() + ")");
    }
  }
}

LyapunovOptions lyapunov_options_from(const Options& o) {
  LyapunovOptions lo;
  lo.transient = integer_from(o, "transient", 0, 1000000000000LL, 1000);
  lo.steps = integer_from(o, "steps", 1, 1000000000000LL, 10000);
  lo.blocks = integer_from(o, "blocks", 1, 10000, 20);
  return lo;
}

long periodic_period_from(const Options& o) {
  if (!o.has("period")) throw InputError("period", "is required (an integer in [1, 100])");
  return integer_from(o, "period", 1, 100, 0);
}

NewtonOptions periodic_newton_from(const Options& o) {
  NewtonOptions no;
  no.max_iter = integer_from(o, "max-iter", 1, 10000, 60);
  no.grid = static_cast<int>(integer_from(o, "grid", 1, 64, 8));
  return no;
}

}  // namespace bouncer
