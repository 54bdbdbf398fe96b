// bouncer audit as a library call: rerun a recorded result from its provenance and say
// whether the new result is identical (compared as workflow/compare_results.hpp says).
//
// A result is a JSON output with "provenance": {"command", "inputs", ...} (orbit --format
// json, certify-sticking --json, sweep PREFIX.json) or a text/CSV output whose first line is
// "# bouncer VERSION (commit C) COMMAND" with an "# inputs: k=v ..." line (orbit csv and
// table, certify-sticking text, sweep PREFIX.csv; continue PREFIX.json and PREFIX.csv). The
// command is rerun with exactly the recorded inputs by the given bouncer executable, in a
// private temporary directory (mkdtemp, mode 0700, removed at the end), and the two outputs
// are compared. Pictures (PNG, PDF, SVG) and proof certificates are refused, naming what to
// audit or rerun instead. A `bouncer reproduce` directory (or its claims.json) is rerun as a
// whole and compared item by item.
//
// The trust boundary (README, "Security"): audit runs only what bouncer itself writes, a
// computing command (workflow/commands.hpp) with its recorded inputs as options, never a
// program or a file a result names, and writes only into its temporary directory.
#pragma once

#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "bouncer/workflow/compare_results.hpp"

namespace bouncer {

// What a result records of the run that wrote it.
struct RecordedRun {
  bool is_json = false;  // JSON provenance (else the text form's "# " lines)
  std::string command;
  std::vector<std::pair<std::string, std::string>> inputs;  // as recorded, in order
};

// The provenance of a result's text, JSON or text form; nothing if it has none (or a
// malformed one: a non-string input, an "# inputs:" line that is not k=v words).
std::optional<RecordedRun> read_provenance(const std::string& text);

// What audit reruns for a result file.
struct AuditPlan {
  std::string command;             // a computing command (workflow/commands.hpp)
  std::vector<std::string> argv;   // argv[0] is `self`; any --out points into `dir`
  std::string compare_path;        // where the rerun's result will be, to compare with the file
  bool is_json = false;            // the file is JSON (else text/CSV with "# " provenance lines)
  // An npy orbit (`orbit --format npy --out PATH`): the file audited is its provenance
  // PATH.json, compared as JSON, and its data PATH (named by the audited file's own path,
  // never by its content) is compared byte for byte with the rerun's `rerun_data_path`.
  // Both empty for every other result.
  std::string data_path;
  std::string rerun_data_path;
};

// Reads the provenance of a result file's `text` (named `path` in messages) and builds the
// rerun into the directory `dir`, without running anything. Throws InputError("file", ...)
// for a picture, a proof certificate, an npy orbit's data (its PATH.json is audited) or
// provenance not named PATH.json, a file without provenance, or a file that records what
// bouncer never records: a command that is not a computing command (reproduce, audit, merge)
// or an input that names tiles, scenes or manifests to read. A reproduce directory's
// claims.json is audited by its directory, not here.
AuditPlan plan_rerun(const std::string& path, const std::string& text, const std::string& dir, const std::string& self);

struct AuditRequest {
  std::string file;             // a result file, a reproduce directory or its claims.json
  bool trust_manifest = false;  // rerun a reproduce directory made from another manifest
  std::string executable;       // the bouncer that reruns (the command line: itself)
  // The command line's own check of a rebuilt command (words[0] is "bouncer"), run before
  // the rerun starts: a message refuses the file ("records inputs that bouncer refuses:
  // MESSAGE"). Unset: no check.
  std::function<std::optional<std::string>(const std::vector<std::string>& words)> check_command;
  // Told the rerun of a single result, as shown (the temporary directory as "<tmp>"), when
  // it starts: "bouncer orbit --a=24 ... --json".
  std::function<void(const std::string& shown)> on_rerun;
};

enum class AuditVerdict {
  identical,     // exit status 0
  different,     // 1: `first` (a result) or `differences` (a reproduce directory)
  rerun_failed,  // 1: `message` says how
  not_a_result,  // 2: not a result audit reruns, or unreadable, or refused: `message`
};

struct AuditResult {
  AuditVerdict verdict = AuditVerdict::identical;
  bool reproduce_directory = false;  // a reproduce directory was audited (else one result)
  bool is_json = false;              // one result: it is JSON (else text/CSV)
  std::string rerun;                 // one result: the rerun, as on_rerun shows it
  Comparison first;                  // one result, different: the first difference
  std::string data_file;             // one result, an npy orbit: its data file, compared too
  // A reproduce directory: its path, every difference ("claim ID: verdict: ...",
  // "panels/x.csv: rows differ"), and what was compared.
  std::string directory;
  std::vector<std::string> differences;
  std::size_t claims_compared = 0, outputs_compared = 0;
  // rerun_failed: "the rerun failed (exit status 3)", "the rerun wrote no result", "the
  // rerun's output is not JSON", "the rerun of reproduce failed (exit status 3)".
  // not_a_result: why, in one line, about the field "file" ("'x.png' is a picture; ...").
  std::string message;
  int rerun_status = 0;  // the rerun's exit status (-1: it did not exit)
  // Wall-clock seconds of the rerun (a reproduce directory: the whole reproduce) and of the
  // comparison after it (reading and parsing both sides): audit costs the run it checks plus
  // compare_seconds (README, "bouncer audit FILE"; tools/bench/bench_audit.py measures both).
  double rerun_seconds = 0, compare_seconds = 0;
};

// Audits request.file. Throws OutputError if the temporary directory cannot be made.
AuditResult audit(const AuditRequest& request);

}  // namespace bouncer
