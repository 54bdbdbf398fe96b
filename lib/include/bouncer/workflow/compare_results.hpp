// Two results of the same command compared as audit compares them (workflow/audit.hpp): a
// result file and its rerun, or an item of a reproduce directory and the same item rerun.
//
// Compared: everything, numbers as the exact text they hold (not as parsed doubles: an edit
// of the 17th digit of a 20-digit number is a difference), except these volatile fields:
//   * timings: JSON keys named "seconds" (at any depth); text lines starting "# time:";
//   * the invocation (binary path and command line): JSON provenance.invocation, text
//     line "# invocation:";
//   * the output location: JSON provenance.inputs.out and the top-level "files" of a
//     PREFIX.json, "out=..." in the text "# inputs:" line (a rerun writes elsewhere).
// The version, commit, compiler, flags and library versions ARE compared: a result of
// another build differs (in that field) even if its numbers agree. JSON objects compare by
// their keys, whatever their order.
#pragma once

#include <string>

namespace bouncer {

// The first difference between a result and its rerun, or none.
struct Comparison {
  bool identical = true;
  // Where the first difference is: a JSON path ("rows[0].leaves_enclosure_at"; "(root)" for
  // the whole document), or for text "line N", N counting the lines compared (volatile
  // lines skipped). Empty when identical.
  std::string path;
  // JSON: what differs there, file first ("655 vs 654", "present in the file, missing in the
  // rerun", "3 vs 4 elements"; long values cut at 200 characters). Text: empty.
  std::string detail;
  // Text: the two lines at `path` as compared ("<end of file>" / "<end of output>" past
  // either end). JSON: empty.
  std::string file_line, rerun_line;
};

// JSON results. A text that is not JSON differs at "(root)", with the detail "the file is
// not JSON" or "the rerun's output is not JSON".
Comparison compare_json_results(const std::string& file, const std::string& rerun);

// Text and CSV results with "# " provenance lines, line by line.
Comparison compare_text_results(const std::string& file, const std::string& rerun);

}  // namespace bouncer
