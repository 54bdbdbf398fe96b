// Private to the io layer's reports (lib/src/io/reports/): nlohmann::json, which the public
// headers never expose, and the two written forms of a certified command's result.
#pragma once

// GCC 12 at -O3 reports false "maybe uninitialized" warnings inside nlohmann::json.
#pragma GCC diagnostic push
#if !defined(__clang__)
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif
#include <nlohmann/json.hpp>
#pragma GCC diagnostic pop

#include <cmath>
#include <optional>
#include <ostream>
#include <string>

#include "bouncer/io/provenance.hpp"

namespace bouncer::reports {

using json = nlohmann::ordered_json;

// A JSON number, or a string for the values JSON cannot hold (inf, -inf, nan).
inline json json_number(double x) {
  if (std::isnan(x)) return "nan";
  if (std::isinf(x)) return x > 0 ? "inf" : "-inf";
  return x;
}

inline json null_or(const std::optional<long long>& x) { return x ? json(*x) : json(nullptr); }

// The text form of a certified command's result: "# " provenance lines, then one
// "key: value" line per field (nested objects and arrays of objects as dotted/indexed keys).
// Timings go to "# time:" lines, which audit ignores.
void write_key_values(std::ostream& out, const Provenance& p, const json& body);

// A certified command's result (certify-sticking, certify-periodic): JSON with the
// provenance first (one-space indent), or the key: value text.
void write_certified(std::ostream& out, bool as_json, const Provenance& p, const json& body);

}  // namespace bouncer::reports
