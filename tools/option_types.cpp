// What each option's value is, for --help (CLI11 shows the C++ type, and every option of the
// command line is a string, parsed later by the library's readers with their ranges:
// io/options.hpp). One table for every command: an option name means one kind of value
// wherever it appears. tests/cli/help.sh checks that no option is left as TEXT.
#include "option_types.hpp"

#include <array>
#include <string>
#include <string_view>
#include <utility>

namespace bouncer::cli {

namespace {

constexpr std::array<std::pair<std::string_view, std::string_view>, 79> kinds{{
    // decimals (exact: a run encloses or rounds them as its precision says)
    {"a", "NUMBER"}, {"eps", "NUMBER"}, {"c", "NUMBER"}, {"theta", "NUMBER"}, {"v", "NUMBER"},
    {"step", "NUMBER"}, {"beyond", "NUMBER"}, {"tolerance", "NUMBER"}, {"lift", "NUMBER"},
    // integers
    {"steps", "INT"}, {"transient", "INT"}, {"threads", "INT"}, {"recheck-factor", "INT"}, {"recheck", "recurrence|full"},
    {"max-period", "INT"}, {"max-bits", "INT"}, {"samples", "INT"}, {"max-iter", "INT"},
    {"start-bits", "INT"}, {"max-steps", "INT"}, {"max-pieces", "INT"}, {"max-depth", "INT"},
    {"values", "INT"}, {"recurrences", "INT"}, {"p-max", "INT"}, {"max-points", "INT"},
    {"lyapunov-steps", "INT"}, {"lost-steps", "INT"}, {"jobs", "INT"}, {"hits", "INT"},
    {"every", "INT"}, {"confirm-bits", "INT"}, {"classify-steps", "INT"}, {"blocks", "INT"},
    {"bins", "INT"}, {"attractor-steps", "INT"}, {"period", "INT"}, {"dpi", "INT"},
    {"reference-max-bits", "INT"}, {"record", "INT"}, {"ics", "INT"}, {"periods", "INT"}, {"bits", "INT"}, {"replay-bits", "INT"}, {"covering", "INT"},
    {"confirm-sample", "N|all"}, {"confirm", "[BITS]"},
    // files
    {"scene", "PATH"}, {"png", "PATH"}, {"out", "PREFIX"}, {"tiles-from", "PREFIX"},
    // a scalar type
    {"precision", "PREC"},
    // LO:HI
    {"range", "LO:HI"}, {"v-range", "LO:HI"}, {"theta-range", "LO:HI"}, {"a-range", "LO:HI"},
    {"eps-range", "LO:HI"}, {"c-range", "LO:HI"},
    // NxM, WxH, I/N
    {"grid", "NxM"}, {"cells", "NxM"}, {"starts", "NxM"}, {"size", "WxH"}, {"shard", "I/N"},
    // lists
    {"guess", "THETA,V"}, {"format", "LIST"}, {"only", "LIST"},
    // one word of a stated set (the help lists them)
    {"model", "WORD"}, {"wall", "WALL"}, {"veldep-collapse", "on|off"}, {"downward-sticking", "WORD"},
    {"palette", "WORD"}, {"vary", "a|eps|c"}, {"show", "WORD"}, {"method", "WORD"}, {"sampling", "WORD"},
    {"family", "auto|on|off"}, {"formulation", "auto|composed|shooting"}, {"prove-attractor", "on|off"}, {"curves", "WORD"},
}};

}  // namespace

std::string option_type_name(const std::string& command, const std::string& name) {
  if (command == "reproduce" && name == "out") return "DIR";  // a directory of results, not a prefix
  // One file, not a prefix: the text output of orbit and of the two certify commands.
  if ((command == "orbit" || command == "certify-sticking" || command == "certify-periodic") && name == "out") return "PATH";
  for (const auto& [n, kind] : kinds)
    if (n == name) return std::string(kind);
  return "TEXT";
}

}  // namespace bouncer::cli
