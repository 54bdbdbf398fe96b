// Private to audit (workflow/audit.hpp): the JSON form of the comparison
// (compare_results.cpp), the rerun's private directory and process (audit.cpp), shared with
// the audit of a reproduce directory (audit_reproduce.cpp). Not installed: nlohmann-json is a
// private dependency of the library.
#pragma once

#include <nlohmann/json.hpp>

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "bouncer/workflow/audit.hpp"

namespace bouncer::audit_detail {

using json = nlohmann::ordered_json;

// The "# inputs:" line's k=v words (after "# inputs:"); a value may be quoted
// (provenance's quote_input). Nothing on a malformed line.
std::optional<std::vector<std::pair<std::string, std::string>>> input_tokens(const std::string& line);

// The JSON text parsed with every number held as its exact text (discarded if not JSON).
json parse_exact(const std::string& text);

// Removes the volatile fields (compare_results.hpp) of a result's JSON (`top`: the document).
void strip_volatile(json& j, bool top);

// A value for a message: numbers shown as their text, cut at 200 characters.
std::string short_dump(const json& j);

// The first difference of two documents parsed by parse_exact (their volatile fields
// already stripped).
Comparison first_difference(const json& file, const json& rerun);

// The lines of a text result as compared: volatile lines skipped, "out=" dropped from the
// "# inputs:" line.
std::vector<std::string> normalized_lines(const std::string& text);

// A file of the audited result or of the rerun (bounded, never a FIFO or device: a result
// file may come from a stranger); nothing when it cannot be read.
std::optional<std::string> read_result(const std::string& path);

// Runs argv in the directory `cwd` (audit's private directory: a relative path in the
// command resolves there) with stdout into `out_path` (created there) and stderr discarded;
// returns the exit status (or -1). The child ends if audit is killed.
int run_to_file(const std::vector<std::string>& argv, const std::string& out_path, const std::string& cwd);

// audit's private temporary directory (mkdtemp: mode 0700, a new name), removed with all it
// holds when audit ends. Reruns write only here. Throws OutputError if it cannot be made.
struct PrivateDir {
  std::string path;
  PrivateDir();
  ~PrivateDir();
  PrivateDir(const PrivateDir&) = delete;
  PrivateDir& operator=(const PrivateDir&) = delete;
};

// The audit of a `bouncer reproduce` directory (audit_reproduce.cpp). Throws InputError
// ("file") for a directory that is not one, or one made from another manifest without
// request.trust_manifest.
AuditResult audit_reproduce(const std::string& dir, const AuditRequest& request);

}  // namespace bouncer::audit_detail
