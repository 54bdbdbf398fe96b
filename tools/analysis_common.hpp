// Shared plumbing of the analysis commands (periodic, lyapunov, classify): the JSON summary
// with the provenance, and the text summary with "# " provenance lines. Their option
// readers are the library's (bouncer/io/options.hpp).
#pragma once

#include <nlohmann/json.hpp>

#include <cmath>
#include <iostream>
#include <string>

#include "bouncer/analysis/lyapunov.hpp"
#include "bouncer/analysis/periodic.hpp"
#include "cli_common.hpp"

namespace bouncer::cli {

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
