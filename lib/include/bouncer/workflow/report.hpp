// reproduce's reports, from its result (workflow/reproduce.hpp): report.md and report.html
// (every panel beside the paper's caption, the claims table, provenance per item; times only
// in the "Times" section) and claims.json (per claim: expected verdict, this run's verdict,
// checks; per panel and picture: status and files; times only under "times").
#pragma once

#include <string>

#include "bouncer/workflow/manifest.hpp"
#include "bouncer/workflow/reproduce.hpp"

namespace bouncer {

// The paper's LaTeX (a figure caption: "$a=19.0$", "$c\sim 1000$", "Fig.~\ref{fig:x}") as plain
// Unicode text for the reports ("a = 19.0", "c ∼ 1000", "Fig. x"): math delimiters dropped,
// Greek letters and relations as their characters, _n and ^2 as sub- and superscripts where
// Unicode has them, \ref{kind:label} as its label, ~ as a space, braces dropped.
std::string latex_text(const std::string& latex);

// The README's Markdown claims table (| # | Claim (paper) | Verdict | Evidence | Rerun |).
std::string claims_table(const Manifest& manifest);

std::string report_markdown(const ReproduceResult& result);
std::string report_html(const ReproduceResult& result);
std::string claims_json(const ReproduceResult& result);

// DIR/report.md, DIR/report.html and DIR/claims.json, written all or none (base/output.hpp).
void write_reports(const ReproduceResult& result);

}  // namespace bouncer
