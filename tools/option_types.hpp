// What the value of an option is, for --help (tools/option_types.cpp).
#pragma once

#include <string>

namespace bouncer::cli {

// What the value of option --NAME of `command` is: NUMBER, INT, PATH, PREC, LO:HI, NxM ...;
// "TEXT" for a name the table does not know. (CLI11 adds "..." after a list option's type.)
std::string option_type_name(const std::string& command, const std::string& name);

}  // namespace bouncer::cli
