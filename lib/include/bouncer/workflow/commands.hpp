// The table of bouncer's commands: each one's name, one-line summary and kind, in the order
// `bouncer --help` lists them. The command line (tools/run_command.cpp) builds its
// subcommands from this table; reproduce's manifests and audit's result files may name only
// its computing commands; the man pages and the docs list it. A command's options are its
// own (tools/cmd_NAME.cpp), bound to its name in tools/commands.cpp.
#pragma once

#include <span>
#include <string_view>

namespace bouncer {

enum class CommandKind {
  computing,  // computes a result from its options (a manifest may run it, audit may rerun it)
  workflow,   // runs, joins or checks other commands' work: reproduce, audit, merge, check-certificate
              // (never in a manifest, never rerun by audit: a file names none of them)
};

struct CommandInfo {
  std::string_view name;
  std::string_view summary;
  CommandKind kind;
};

// Every command, once.
std::span<const CommandInfo> command_table();

// The entry named `name`, or nullptr.
const CommandInfo* find_command(std::string_view name);

// True for a computing command's name: the only commands a manifest may run and audit may
// rerun (never reproduce, audit or merge, which start processes or read prefixes of their own).
bool is_computing_command(std::string_view name);

}  // namespace bouncer
