#include "bouncer/io/provenance.hpp"

#include "bouncer/verify/chaos_certificate.hpp"

#include <gmp.h>
#include <mpfi.h>
#include <mpfr.h>

#include <boost/version.hpp>
#include <nlohmann/json.hpp>
#include <sstream>

#ifndef BOUNCER_QD_VERSION
#define BOUNCER_QD_VERSION "unknown"
#endif

namespace bouncer {

std::string library_versions() {
  std::ostringstream s;
  s << "boost " << BOOST_VERSION / 100000 << "." << BOOST_VERSION / 100 % 1000 << "." << BOOST_VERSION % 100
    << ", mpfr " << mpfr_get_version() << ", mpfi " << MPFI_VERSION_STRING << ", gmp " << gmp_version << ", qd " << BOUNCER_QD_VERSION
    << ", arb " << arb_library_version();
  return s.str();
}

// An input value on the "# inputs:" line: as it is, or in double quotes (with \" and \\)
// when it holds a space, a quote, a backslash or a control character, or is empty, so that
// `audit` reads back exactly the value given (an --out path with a space, say).
std::string quote_input(const std::string& v) {
  bool plain = !v.empty();
  for (unsigned char c : v) plain = plain && c > ' ' && c != '"' && c != '\\' && c != 0x7f;
  if (plain) return v;
  std::string q = "\"";
  for (char c : v) {
    if (c == '"' || c == '\\') q += '\\';
    q += c;
  }
  return q + "\"";
}

std::string Provenance::as_comment_lines() const {
  const BuildInfo& b = build_info();
  std::ostringstream s;
  s << "# bouncer " << b.version << " (commit " << b.commit << ") " << command << "\n";
  if (!invocation.empty()) s << "# invocation: " << invocation << "\n";
  s << "# inputs:";
  for (const auto& [k, v] : inputs) s << " " << k << "=" << quote_input(v);
  s << "\n# precision: " << precision;
  if (bits > 0) s << " (" << bits << " significand bits)";  // 0: no scalar type (exact rationals)
  s << "\n";
  if (!decimal_note.empty()) s << "# decimals: " << decimal_note << "\n";
  s << "# libraries: " << library_versions() << "\n";
  s << "# compiler: " << b.compiler << " " << b.build_type << " flags: " << b.flags << "\n";
  return s.str();
}

std::string Provenance::as_json() const {
  const BuildInfo& b = build_info();
  nlohmann::ordered_json j;
  j["tool"] = "bouncer";
  j["version"] = b.version;
  j["commit"] = b.commit;
  j["command"] = command;
  nlohmann::ordered_json in = nlohmann::ordered_json::object();
  for (const auto& [k, v] : inputs) in[k] = v;
  j["inputs"] = in;
  j["precision"] = precision;
  j["bits"] = bits;
  j["decimals"] = decimal_note;
  j["invocation"] = invocation;
  j["libraries"] = library_versions();
  j["compiler"] = b.compiler;
  j["build_type"] = b.build_type;
  j["flags"] = b.flags;
  return j.dump();
}

std::vector<std::pair<std::string, std::string>> png_metadata(const Provenance& p, const std::string& title) {
  std::string inputs;
  for (const auto& [k, v] : p.inputs) inputs += (inputs.empty() ? "" : " ") + k + "=" + v;
  return {{"Title", title},
          {"Software", "bouncer " + build_info().version + " (commit " + build_info().commit + ")"},
          {"Source", p.invocation},
          {"bouncer:command", p.command},
          {"bouncer:inputs", inputs},
          {"bouncer:precision", p.precision + " (" + std::to_string(p.bits) + " bits)"},
          {"bouncer:provenance", p.as_json()}};
}

}  // namespace bouncer
