// bouncer audit's trust boundary as a function (tools/cmd_audit.cpp), so that it can be
// tested and fuzzed without running anything.
#pragma once

#include <string>
#include <vector>

namespace bouncer::cli {

// What audit reruns for a result file.
struct AuditPlan {
  std::string command;             // a computing command (workflow/commands.hpp)
  std::vector<std::string> argv;   // argv[0] is `self`; any --out points into `dir`
  std::string compare_path;        // where the rerun's result will be, to compare with the file
  bool is_json = false;            // the file is JSON (else text/CSV with "# " provenance lines)
};

// Reads the provenance of a result file's `text` (named `path` in messages) and builds the
// rerun into the directory `dir`, without running anything. Throws InputError("file", ...)
// for a picture, a proof certificate, a file without provenance, or a file that records what
// bouncer never records: a command that is not a computing command (reproduce, audit, merge)
// or an input that names tiles, scenes or manifests to read. A reproduce directory's
// claims.json is audited by its directory, not here.
AuditPlan plan_rerun(const std::string& path, const std::string& text, const std::string& dir, const std::string& self);

}  // namespace bouncer::cli
