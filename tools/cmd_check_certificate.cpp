// bouncer check-certificate FILE: replays a chaos certificate (written by certify-chaos, or by
// anyone) with the second interval library, Arb (verify/chaos_certificate.hpp says what is
// independent of what), and says whether it proves its stated entropy bound.
//
// Exit status: 0 the certificate is valid, 1 it is not (every failed check printed), 2 the file
// is not a certificate (the field and what was expected named).
#include <memory>
#include <optional>
#include <ostream>
#include <string>

#include "bouncer/base/input.hpp"
#include "bouncer/io/chaos_certificate.hpp"
#include "bouncer/io/provenance.hpp"
#include "cli_common.hpp"
#include "commands.hpp"

namespace bouncer::cli {

namespace {

// Certificates of 1024 h-sets with rationals of 4096 characters fit in 64 MiB.
constexpr std::size_t kMaxCertificateBytes = std::size_t(64) << 20;

}  // namespace

CommandRunner setup_check_certificate(CLI::App* sub) {
  auto file = std::make_shared<std::string>();
  auto opts = std::make_shared<OptionSet>(sub);
  sub->add_option("file", *file, "A chaos certificate (JSON, from certify-chaos --out)")->required();
  opts->add("bits", "Arb precision of the replay, integer in [32, 65536] (default 256)");
  opts->add("png", "Also draw one covering (--covering) in its target's local coordinates to PATH");
  opts->add("covering", "The covering --png draws: its index in the certificate (default 0)");
  auto run = [file, opts](const std::string& argv_text) {
    const Options o = opts->collected();
    const long bits = long(integer_from(o, "bits", 32, 65536, 256));
    OutputSet outputs;  // reserved before the work: a path that cannot be written is found at once
    std::optional<std::string> png;
    if (o.has("png")) outputs.reserve("png", *(png = o.get("png")));
    const ChaosCertificate c = parse_certificate(read_input_file("file", *file, kMaxCertificateBytes));
    const long covering = long(integer_from(o, "covering", 0, long(c.coverings.size()) - 1, 0));
    if (o.has("covering") && !png) throw InputError("covering", "is only used with --png");
    const ReplayResult r = replay_certificate(c, bits);
    if (png) {
      Figure fig = covering_figure(c, std::size_t(covering));
      Provenance p = provenance_for("check-certificate", o, Precision{Precision::Kind::interval, bits}, argv_text);
      fig.metadata = png_metadata(p, fig.title);
      write_output_set({{*png, [&](std::ostream& s) { write_figure(s, fig, ImageFormat::png); }}}, &outputs);
    }
    std::ostream& out = command_out();
    out << "check-certificate: " << (r.valid ? "VALID" : "NOT VALID") << ": " << *file << "\n";
    out << "  map: G = F^" << c.k << " of " << map_text(c) << "\n";
    out << "  replayed in Arb at " << r.bits << " bits (made at " << c.bits << " bits by "
        << (c.made_by.empty() ? std::string("an unnamed maker") : one_line(c.made_by, 200)) << ")\n";
    out << "  h-sets: " << c.sets.size() << (r.disjoint ? ", pairwise disjoint (exact)" : ", NOT shown pairwise disjoint") << "\n";
    for (const ReplayedCovering& v : r.coverings) out << "  " << v.message << "\n";
    if (r.valid) {
      out << "  proved: h_top(F) >= " << c.entropy_bound << " (log of the quotient " << c.quotient.get_str()
          << " <= spectral radius of the coverings, over k = " << c.k << "; Arb: " << r.recomputed_bound << ")\n";
      out << "  on an invariant set inside the h-sets, where every itinerary of the coverings is followed by an orbit;"
             " this does not say that an attractor is that set\n";
    } else {
      for (const std::string& p : r.problems) out << "  problem: " << p << "\n";
    }
    if (!command_capture()) check_stdout();
    return r.valid ? 0 : 1;
  };
  return run;
}

}  // namespace bouncer::cli
