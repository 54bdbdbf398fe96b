// Shared plumbing of the analysis commands (periodic, lyapunov, classify): precision
// restricted to the point types the analysis layer is instantiated for, the JSON summary
// with the provenance, and the text summary with "# " provenance lines.
#pragma once

#include <nlohmann/json.hpp>

#include <cmath>
#include <iostream>
#include <string>

#include "bouncer/analysis/lyapunov.hpp"
#include "bouncer/analysis/periodic.hpp"
#include "cli_common.hpp"

namespace bouncer::cli {

// The precision of an analysis scalar (scalar/scalar_set.hpp); anything else is an
// InputError naming the allowed values.
inline Precision analysis_precision(const Options& o, const std::string& command) {
  const Precision p = precision_from(o);
  if (!p.is_analysis())
    throw InputError("precision", "'" + p.text() + "' is not available for " + command +
                                      ": it follows one point orbit (allowed: " + precision_names<AnalysisScalars>() + " with " +
                                      std::to_string(kMinBits) + " <= BITS <= " + std::to_string(kMaxBits) +
                                      "; certified answers: certify-sticking, sweep)");
  return p;
}


// A JSON number, or a string for the values JSON cannot hold (inf, -inf, nan).
inline nlohmann::ordered_json json_number(double x) {
  if (std::isnan(x)) return "nan";
  if (std::isinf(x)) return x > 0 ? "inf" : "-inf";
  return x;
}

inline void print_summary(const Provenance& p, const nlohmann::ordered_json& body, bool json) {
  if (json) {
    nlohmann::ordered_json out;
    out["provenance"] = nlohmann::ordered_json::parse(p.as_json());
    for (const auto& [k, v] : body.items()) out[k] = v;
    command_out() << out.dump(1) << "\n";
    return;
  }
  command_out() << p.as_comment_lines();
  for (const auto& [k, v] : body.items()) command_out() << k << ": " << (v.is_string() ? v.get<std::string>() : v.dump()) << "\n";
}

// The options of `bouncer lyapunov` (one exponent) and `bouncer periodic`, their ranges and
// defaults, read once for the command line and the Python module (python/module.cpp).
inline LyapunovOptions lyapunov_options_from(const Options& o) {
  LyapunovOptions lo;
  lo.transient = integer_from(o, "transient", 0, 1000000000000LL, 1000);
  lo.steps = integer_from(o, "steps", 1, 1000000000000LL, 10000);
  lo.blocks = integer_from(o, "blocks", 1, 10000, 20);
  return lo;
}
inline long periodic_period_from(const Options& o) {
  if (!o.has("period")) throw InputError("period", "is required (an integer in [1, 100])");
  return integer_from(o, "period", 1, 100, 0);
}
inline NewtonOptions periodic_newton_from(const Options& o) {
  NewtonOptions no;
  no.max_iter = integer_from(o, "max-iter", 1, 10000, 60);
  no.grid = static_cast<int>(integer_from(o, "grid", 1, 64, 8));
  return no;
}

}  // namespace bouncer::cli
