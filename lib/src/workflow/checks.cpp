#include "bouncer/workflow/checks.hpp"

#pragma GCC diagnostic push
#if !defined(__clang__)  // clang has no such warning (the fuzzing build, tests/fuzz/)
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif
#include <nlohmann/json.hpp>
#pragma GCC diagnostic pop

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>

namespace bouncer {

namespace {

using json = nlohmann::ordered_json;

json to_json(const CheckValue& v) {
  return std::visit(
      [](const auto& x) -> json {
        if constexpr (std::is_same_v<std::decay_t<decltype(x)>, std::monostate>)
          return nullptr;
        else
          return x;
      },
      v);
}

// Resolves PATH's segments from `i` on in j; std::nullopt when the path does not exist.
std::optional<json> resolve(const json& j, const std::vector<std::string>& segs, size_t i) {
  if (i == segs.size()) return j;
  const std::string& s = segs[i];
  if (s == "*") {
    if (!j.is_array()) return std::nullopt;
    json out = json::array();
    for (const json& e : j)
      if (auto r = resolve(e, segs, i + 1)) {
        if (std::find(segs.begin() + i + 1, segs.end(), "*") != segs.end() && r->is_array())
          for (const json& x : *r) out.push_back(x);
        else
          out.push_back(*r);
      }
    return out;
  }
  if (j.is_object()) {
    if (!j.contains(s)) return std::nullopt;
    return resolve(j[s], segs, i + 1);
  }
  if (j.is_array() && !s.empty() && std::all_of(s.begin(), s.end(), ::isdigit)) {
    // (an index too long for size_t is past any array's end, not an error)
    if (s.size() > 18) return std::nullopt;
    const size_t k = std::stoul(s);
    if (k >= j.size()) return std::nullopt;
    return resolve(j[k], segs, i + 1);
  }
  return std::nullopt;
}

// A number, or a text that is a whole finite number: what < <= > >= compare.
std::optional<double> number(const json& v) {
  if (v.is_number()) return v.get<double>();
  if (v.is_string()) {
    const std::string s = v.get<std::string>();
    char* end = nullptr;
    const double d = std::strtod(s.c_str(), &end);
    if (!s.empty() && end == s.c_str() + s.size() && std::isfinite(d)) return d;
  }
  return std::nullopt;
}

bool equal(const json& a, const json& b) {
  if (a.is_number() && b.is_number()) return a.get<double>() == b.get<double>();
  return a == b;
}

CheckResult evaluate(const Check& c, const json& doc) {
  CheckResult r;
  r.check = c.text();
  std::vector<std::string> segs;
  for (size_t start = 0;;) {  // PATH split at '.', as getline would: no segment after a final '.'
    const size_t dot = c.path.find('.', start);
    if (dot == std::string::npos) {
      if (start < c.path.size()) segs.push_back(c.path.substr(start));
      break;
    }
    segs.push_back(c.path.substr(start, dot - start));
    start = dot + 1;
  }
  const std::optional<json> v = resolve(doc, segs, 0);
  if (!v) {
    r.got = "missing";
    return r;
  }
  r.found = true;
  r.got = v->dump();
  if (r.got.size() > 200) r.got = r.got.substr(0, 200) + "...";
  const json value = to_json(c.value);
  if (c.op == "has" || c.op == "lacks") {
    if (!v->is_array()) return r;
    const bool found = std::any_of(v->begin(), v->end(), [&](const json& x) { return equal(x, value); });
    r.held = c.op == "has" ? found : !found;
    return r;
  }
  if (c.op == "==") {
    r.held = equal(*v, value);
    return r;
  }
  if (c.op == "!=") {
    r.held = !equal(*v, value);
    return r;
  }
  const auto x = number(*v), y = number(value);
  if (!x || !y) return r;
  if (c.op == "<") r.held = *x < *y;
  else if (c.op == "<=") r.held = *x <= *y;
  else if (c.op == ">") r.held = *x > *y;
  else if (c.op == ">=") r.held = *x >= *y;
  return r;
}

}  // namespace

std::string Check::text() const { return path + " " + op + " " + to_json(value).dump(); }

bool is_check_operator(std::string_view op) {
  static constexpr std::string_view ops[] = {"==", "!=", "<", "<=", ">", ">=", "has", "lacks"};
  return std::find(std::begin(ops), std::end(ops), op) != std::end(ops);
}

std::optional<std::vector<CheckResult>> evaluate_checks(const std::vector<Check>& checks, std::string_view json_text) {
  const json doc = json::parse(json_text.begin(), json_text.end(), nullptr, false);
  if (doc.is_discarded()) return std::nullopt;
  std::vector<CheckResult> out;
  for (const Check& c : checks) out.push_back(evaluate(c, doc));
  return out;
}

std::optional<CheckResult> evaluate_check(const Check& check, std::string_view json_text) {
  auto r = evaluate_checks({check}, json_text);
  if (!r) return std::nullopt;
  return r->front();
}

}  // namespace bouncer
