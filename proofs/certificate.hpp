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

#include <chrono>
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

  // Prints the certificate and returns the process exit status (0 iff certified).
  int finish() {
    const double secs =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    bool ok = overall_ != Verdict::not_proved;
    for (const auto& s : subs_) ok = ok && s.verdict != Verdict::not_proved;
    const Verdict v = ok ? overall_ : Verdict::not_proved;
    if (json_) print_json(v, secs);
    else print_text(v, secs);
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

  static std::string esc(const std::string& s) {
    std::string r;
    for (char ch : s) {
      switch (ch) {
        case '"': r += "\\\""; break;
        case '\\': r += "\\\\"; break;
        case '\n': r += "\\n"; break;
        case '\t': r += "\\t"; break;
        default:
          if (static_cast<unsigned char>(ch) < 0x20) {
            char b[8];
            std::snprintf(b, sizeof b, "\\u%04x", ch);
            r += b;
          } else {
            r += ch;
          }
      }
    }
    return r;
  }
  static std::string str(const std::string& s) {
    std::string r(1, '"');  // appended, not "..." + string (avoids a GCC 12 -Wrestrict false positive)
    r += esc(s);
    r += '"';
    return r;
  }

  void print_json(Verdict v, double secs) const {
    std::ostringstream o;
    o << "{\n  \"proof\": " << str(id_) << ",\n  \"claim\": " << str(claim_)
      << ",\n  \"method\": " << str(method_) << ",\n  \"bits\": " << bits_
      << ",\n  \"mode\": " << str(mode()) << ",\n  \"notes\": [";
    for (size_t i = 0; i < notes_.size(); ++i) o << (i ? ", " : "") << str(notes_[i]);
    o << "],\n  \"subclaims\": [";
    for (size_t i = 0; i < subs_.size(); ++i) {
      const auto& s = subs_[i];
      o << (i ? "," : "") << "\n    {\"name\": " << str(s.name) << ", \"paper\": " << str(s.paper)
        << ", \"verdict\": " << str(verdict_name(s.verdict)) << ", \"statement\": "
        << str(s.statement) << ", \"evidence\": [";
      for (size_t k = 0; k < s.evidence.size(); ++k) o << (k ? ", " : "") << str(s.evidence[k]);
      o << "]}";
    }
    char t[64];
    std::snprintf(t, sizeof t, "%.3f", secs);
    o << "\n  ],\n  \"seconds\": " << t << ",\n  \"verdict\": "
      << str(v == Verdict::not_proved ? "not proved at " + std::to_string(bits_) + " bits"
                                      : std::string(verdict_name(v)))
      << ",\n  \"statement\": " << str(overall_statement_) << "\n}\n";
    std::cout << o.str() << std::flush;
  }
};

}  // namespace proofs
