// A result and its rerun compared (workflow/compare_results.hpp).
#include "bouncer/workflow/compare_results.hpp"

#include <algorithm>
#include <cctype>
#include <cstring>
#include <sstream>

#include "audit_internal.hpp"
#include "bouncer/io/provenance.hpp"

namespace bouncer {

namespace audit_detail {

std::optional<std::vector<std::pair<std::string, std::string>>> input_tokens(const std::string& line) {
  std::vector<std::pair<std::string, std::string>> out;
  size_t i = 0;
  while (true) {
    while (i < line.size() && line[i] == ' ') ++i;
    if (i >= line.size()) return out;
    const size_t eq = line.find('=', i);
    if (eq == std::string::npos) return std::nullopt;
    const std::string key = line.substr(i, eq - i);
    if (key.empty() || key.find(' ') != std::string::npos) return std::nullopt;
    i = eq + 1;
    std::string value;
    if (i < line.size() && line[i] == '"') {
      ++i;
      while (i < line.size() && line[i] != '"') {
        if (line[i] == '\\' && i + 1 < line.size()) ++i;
        value += line[i++];
      }
      if (i >= line.size()) return std::nullopt;  // no closing quote
      ++i;
    } else {
      while (i < line.size() && line[i] != ' ') value += line[i++];
    }
    out.emplace_back(key, value);
  }
}

namespace {

// The JSON text with every number token turned into a string holding its exact text (marked
// by a leading U+0001), so that results are compared as the digits they hold: parsed as
// doubles, an edit of the 17th digit of a 20-digit number would compare equal.
std::string numbers_as_text(const std::string& in) {
  std::string out;
  out.reserve(in.size() + in.size() / 8);
  bool in_string = false;
  for (size_t i = 0; i < in.size(); ++i) {
    const char c = in[i];
    if (in_string) {
      out += c;
      if (c == '\\' && i + 1 < in.size()) out += in[++i];
      else if (c == '"') in_string = false;
    } else if (c == '"') {
      in_string = true;
      out += c;
    } else if (c == '-' || (c >= '0' && c <= '9')) {
      size_t j = i;
      while (j < in.size() && (std::isdigit(static_cast<unsigned char>(in[j])) || std::strchr("+-.eE", in[j]))) ++j;
      out += "\"\\u0001" + in.substr(i, j - i) + "\"";
      i = j - 1;
    } else {
      out += c;
    }
  }
  return out;
}

// Path of the first difference, or "" when equal.
std::string first_difference(const json& a, const json& b, const std::string& path, std::string& detail) {
  if (a.type() != b.type()) {
    detail = short_dump(a) + " vs " + short_dump(b);
    return path.empty() ? "(root)" : path;
  }
  if (a.is_object()) {
    for (const auto& [k, v] : a.items()) {
      const std::string p = path.empty() ? k : path + "." + k;
      if (!b.contains(k)) {
        detail = "present in the file, missing in the rerun";
        return p;
      }
      const std::string d = first_difference(v, b[k], p, detail);
      if (!d.empty()) return d;
    }
    for (const auto& [k, v] : b.items())
      if (!a.contains(k)) {
        detail = "missing in the file, present in the rerun";
        return path.empty() ? k : path + "." + k;
      }
    return "";
  }
  if (a.is_array()) {
    for (size_t i = 0; i < std::min(a.size(), b.size()); ++i) {
      const std::string d = first_difference(a[i], b[i], path + "[" + std::to_string(i) + "]", detail);
      if (!d.empty()) return d;
    }
    if (a.size() != b.size()) {
      detail = std::to_string(a.size()) + " vs " + std::to_string(b.size()) + " elements";
      return path;
    }
    return "";
  }
  if (a != b) {
    detail = short_dump(a) + " vs " + short_dump(b);
    return path.empty() ? "(root)" : path;
  }
  return "";
}

}  // namespace

json parse_exact(const std::string& text) { return json::parse(numbers_as_text(text), nullptr, false); }

void strip_volatile(json& j, bool top) {
  if (j.is_object()) {
    j.erase("seconds");
    if (top) j.erase("files");  // where the outputs were written
    if (top && j.contains("provenance") && j["provenance"].is_object()) {
      j["provenance"].erase("invocation");
      if (j["provenance"].contains("inputs") && j["provenance"]["inputs"].is_object()) j["provenance"]["inputs"].erase("out");
    }
    for (auto& [k, v] : j.items()) strip_volatile(v, false);
  } else if (j.is_array()) {
    for (auto& v : j) strip_volatile(v, false);
  }
}

std::string short_dump(const json& j) {
  std::string s = j.dump();
  // Numbers were compared as their text (numbers_as_text): show them as numbers again.
  for (size_t at; (at = s.find("\"\\u0001")) != std::string::npos;) {
    const size_t end = s.find('"', at + 7);
    s = s.substr(0, at) + s.substr(at + 7, end - at - 7) + s.substr(end + 1);
  }
  return s.size() > 200 ? s.substr(0, 200) + "..." : s;
}

Comparison first_difference(const json& file, const json& rerun) {
  Comparison c;
  c.path = first_difference(file, rerun, "", c.detail);
  c.identical = c.path.empty();
  return c;
}

std::vector<std::string> normalized_lines(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind("# invocation:", 0) == 0 || line.rfind("# time:", 0) == 0) continue;
    if (line.rfind("# inputs:", 0) == 0) {
      std::string kept = "# inputs:";
      for (const auto& [k, v] : input_tokens(line.substr(9)).value_or(std::vector<std::pair<std::string, std::string>>{}))
        if (k != "out") kept += " " + k + "=" + quote_input(v);
      line = kept;
    }
    out.push_back(line);
  }
  return out;
}

}  // namespace audit_detail

Comparison compare_json_results(const std::string& file, const std::string& rerun) {
  using namespace audit_detail;
  json a = parse_exact(file), b = parse_exact(rerun);
  if (a.is_discarded() || b.is_discarded())
    return {false, "(root)", a.is_discarded() ? "the file is not JSON" : "the rerun's output is not JSON", "", ""};
  strip_volatile(a, true);
  strip_volatile(b, true);
  return first_difference(a, b);
}

Comparison compare_text_results(const std::string& file, const std::string& rerun) {
  const std::vector<std::string> a = audit_detail::normalized_lines(file), b = audit_detail::normalized_lines(rerun);
  for (size_t i = 0; i < std::max(a.size(), b.size()); ++i)
    if (i >= a.size() || i >= b.size() || a[i] != b[i])
      return {false, "line " + std::to_string(i + 1), "", i < a.size() ? a[i] : "<end of file>",
              i < b.size() ? b[i] : "<end of output>"};
  return {};
}

}  // namespace bouncer
