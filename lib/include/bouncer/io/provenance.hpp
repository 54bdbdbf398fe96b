// What every output records so that it can be reproduced: tool version and git commit,
// compiler and flags, library versions, scalar type and bits, exact inputs.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "bouncer/base/build_info.hpp"

namespace bouncer {

std::string library_versions();  // "boost 1.74.0, mpfr 4.2.0, mpfi 1.5.3, gmp 6.2.1, qd 2.3.23, arb 2.23.0"

// An input value as the "# inputs:" line writes it: plain, or quoted ("..." with \" and \\)
// when it holds white space, quotes, backslashes or control characters, or is empty.
std::string quote_input(const std::string& value);

struct Provenance {
  std::string command;                                     // e.g. "orbit"
  std::vector<std::pair<std::string, std::string>> inputs; // exact option texts, in order
  std::string precision;                                   // e.g. "mpfr:256"
  long bits = 0;                                           // significand bits really used
  std::string decimal_note;  // how decimal inputs were converted for this precision
  std::string invocation;    // the command line, for humans

  // "# key: value" lines for CSV and text outputs.
  std::string as_comment_lines() const;
  // A JSON object (serialized) with the same content.
  std::string as_json() const;
};

// PNG metadata from provenance: tEXt chunks (Title, Software, Source, bouncer:command,
// bouncer:inputs, bouncer:precision, bouncer:provenance) a reader finds with any PNG tool.
std::vector<std::pair<std::string, std::string>> png_metadata(const Provenance& p, const std::string& title);

}  // namespace bouncer
