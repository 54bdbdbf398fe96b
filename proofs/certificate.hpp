// Uniform certificates for the computer-assisted proofs in proofs/*.cpp.
//
// A proof states the paper's claim (with its equation), the method, the precision, and a
// verdict per sub-claim: confirmed, refuted, or corrected (with the corrected statement).
// A sub-claim whose rigorous computation did not succeed is `not_proved`; then the whole
// certificate says "not proved at N bits" and the program exits with status 1, so its
// ctest fails. Nothing is reported as proved that was not.
//
// Options every proof accepts:  --full (longer, finer version), --json (machine-readable
// certificate on stdout instead of text), --bits N (interval precision; default per proof).
#pragma once

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <deque>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

namespace proofs {

enum class Verdict { confirmed, refuted, corrected, not_proved };

inline const char* verdict_name(Verdict v) {
  switch (v) {
    case Verdict::confirmed: return "confirmed";
    case Verdict::refuted: return "refuted";
    case Verdict::corrected: return "corrected";
    case Verdict::not_proved: return "not proved";
  }
  return "?";
}

struct SubClaim {
  std::string name;       // short name, e.g. "eigenvalues"
  std::string paper;      // what the paper says (with equation number)
  Verdict verdict = Verdict::not_proved;
  std::string statement;  // what was proved (the corrected statement when corrected)
  std::vector<std::string> evidence;

  // The check's result: the verdict and what was proved (the corrected statement when
  // corrected). A check that did not succeed leaves the sub-claim `not proved`.
  void settle(Verdict v, std::string proved) {
    verdict = v;
    statement = std::move(proved);
  }
};

class Certificate {
 public:
  Certificate(std::string id, std::string claim, std::string method, long default_bits, int argc,
              char** argv)
      : id_(std::move(id)), claim_(std::move(claim)), method_(std::move(method)),
        bits_(default_bits), start_(std::chrono::steady_clock::now()) {
    // CLI11, so that `--bits abc` or `--bits 5` is refused (exit 2) instead of running at
    // a precision nobody asked for.
    CLI::App app{claim_};
    app.add_flag("--full", full_, "Finer covers, longer run");
    app.add_flag("--json", json_, "Print the certificate as JSON");
    app.add_option("--bits", bits_, "Interval precision in bits, integer in [16, 1048576]")
        ->check(CLI::Range(16L, 1048576L));
    try {
      app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
      if (e.get_exit_code() == 0) std::exit(app.exit(e));
      std::cerr << argv[0] << ": " << e.what() << " (see --help)\n";
      std::exit(2);
    }
  }

  bool full() const { return full_; }
  bool json() const { return json_; }
  long bits() const { return bits_; }

  // A sub-claim (starts as not proved); the reference stays valid.
  SubClaim& add(std::string name, std::string paper) {
    subs_.push_back(SubClaim{std::move(name), std::move(paper), Verdict::not_proved, {}, {}});
    return subs_.back();
  }
  void note(std::string line) { notes_.push_back(std::move(line)); }

  // The overall verdict and, for `corrected`/`refuted`, the corrected statement. If any
  // sub-claim is not proved, the overall verdict is `not proved` whatever is set here.
  void conclude(Verdict v, std::string statement) {
    overall_ = v;
    overall_statement_ = std::move(statement);
  }

  // Prints the certificate and returns the process exit status (0 iff certified and
  // written).
  int finish() {
    const double secs =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    bool ok = overall_ != Verdict::not_proved;
    for (const auto& s : subs_) ok = ok && s.verdict != Verdict::not_proved;
    const Verdict v = ok ? overall_ : Verdict::not_proved;
    if (json_) print_json(v, secs);
    else print_text(v, secs);
    if (!std::cout) {  // e.g. stdout on a full disk: the certificate was not written
      std::cerr << id_ << ": could not write the certificate to stdout\n";
      return 1;
    }
    return ok ? 0 : 1;
  }

 private:
  std::string id_, claim_, method_;
  long bits_;
  bool full_ = false, json_ = false;
  std::chrono::steady_clock::time_point start_;
  std::deque<SubClaim> subs_;  // deque: add() references stay valid
  std::vector<std::string> notes_;
  Verdict overall_ = Verdict::not_proved;
  std::string overall_statement_;

  std::string mode() const { return full_ ? "full" : "default"; }

  void print_text(Verdict v, double secs) const {
    std::ostringstream o;
    o << "==== CERTIFICATE proof." << id_ << " ====\n";
    o << "claim:   " << claim_ << "\n";
    o << "method:  " << method_ << "\n";
    o << "bits:    " << bits_ << " (MPFI intervals, outward rounding)   mode: " << mode() << "\n";
    for (const auto& n : notes_) o << "note:    " << n << "\n";
    for (const auto& s : subs_) {
      o << "-- sub-claim " << s.name << ": " << verdict_name(s.verdict);
      if (s.verdict == Verdict::not_proved) o << " at " << bits_ << " bits";
      o << "\n   paper:  " << s.paper << "\n";
      if (!s.statement.empty()) o << "   proved: " << s.statement << "\n";
      for (const auto& e : s.evidence) o << "   * " << e << "\n";
    }
    char t[64];
    std::snprintf(t, sizeof t, "%.3f s", secs);
    o << "time:    " << t << "\n";
    if (v == Verdict::not_proved) {
      o << "verdict: not proved at " << bits_ << " bits\n";
    } else {
      o << "verdict: " << verdict_name(v) << "\n";
      if (!overall_statement_.empty()) o << "statement: " << overall_statement_ << "\n";
    }
    std::cout << o.str() << std::flush;
  }

  // The certificate as JSON (nlohmann, keys in this order). Enclosures and exact values
  // are inside the text fields (statement, evidence) exactly as printed by MPFI/GMP, so they
  // round-trip as text; only `bits` and `seconds` are JSON numbers.
  nlohmann::ordered_json to_json(Verdict v, double secs) const {
    nlohmann::ordered_json j;
    j["proof"] = id_;
    j["claim"] = claim_;
    j["method"] = method_;
    j["bits"] = bits_;
    j["mode"] = mode();
    j["notes"] = notes_;
    j["subclaims"] = nlohmann::ordered_json::array();
    for (const auto& s : subs_) {
      j["subclaims"].push_back({{"name", s.name},
                                {"paper", s.paper},
                                {"verdict", verdict_name(s.verdict)},
                                {"statement", s.statement},
                                {"evidence", s.evidence}});
    }
    j["seconds"] = std::round(secs * 1000) / 1000;  // milliseconds, as the text certificate
    j["verdict"] = v == Verdict::not_proved ? "not proved at " + std::to_string(bits_) + " bits"
                                            : std::string(verdict_name(v));
    j["statement"] = overall_statement_;
    return j;
  }

  void print_json(Verdict v, double secs) const {
    // Invalid UTF-8 (none is expected: all text is ASCII) is replaced, not thrown.
    std::cout << to_json(v, secs).dump(2, ' ', false, nlohmann::json::error_handler_t::replace) << "\n"
              << std::flush;
  }
};

}  // namespace proofs
