// Shared plumbing of the analysis commands (periodic, lyapunov, classify): precision
// restricted to the point types the analysis layer is instantiated for, the JSON summary
// with the provenance, and the text summary with "# " provenance lines.
#pragma once

#include <nlohmann/json.hpp>

#include <cmath>
#include <iostream>
#include <string>

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

}  // namespace bouncer::cli
