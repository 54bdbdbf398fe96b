// The check language of a manifest's claims: [PATH, OP, VALUE], evaluated against the JSON a
// claim's command printed. PATH is dotted ("a.b.0.c": object keys and array indices); a "*"
// segment maps over an array, and the value found is then the array of what each element
// holds at the rest of the path (flattened when a later segment is "*" too). OP is one of
//   == !=          equal or not (numbers by value, 3 == 3.0; anything else exactly as JSON)
//   < <= > >=      numeric, for numbers and for texts that are a whole finite number ("1e-3");
//                  anything else, or a missing path, does not hold
//   has lacks      the value found is an array that holds (or does not hold) VALUE
// A path that does not exist never holds (got: "missing"), whatever the operator; nor does an
// index too long for any array (it is past the end), nor an operator not listed here.
// The JSON crosses this API as text and VALUE as a typed scalar, so that the library's users
// need no JSON library (nlohmann-json is private to bouncer::bouncer).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

namespace bouncer {

// A check's VALUE: what a TOML scalar can be (std::monostate: another TOML value, e.g. an
// array, which is JSON null here).
using CheckValue = std::variant<std::monostate, bool, std::int64_t, double, std::string>;

struct Check {
  std::string path, op;
  CheckValue value;
  // "PATH OP VALUE", VALUE as JSON ("verdict == \"refuted\""): how reports name the check.
  std::string text() const;
};

// The operators above, in the order messages list them.
bool is_check_operator(std::string_view op);

struct CheckResult {
  std::string check;   // Check::text()
  std::string got;     // the value found, as JSON (cut at 200 characters + "..."), or "missing"
  bool found = false;  // the path exists
  bool held = false;
};

// Evaluates `checks` against the JSON document `json_text`, in order; std::nullopt when the
// text is not JSON.
std::optional<std::vector<CheckResult>> evaluate_checks(const std::vector<Check>& checks, std::string_view json_text);

// One check (the same, for one).
std::optional<CheckResult> evaluate_check(const Check& check, std::string_view json_text);

}  // namespace bouncer
