// bouncer certify-chaos: a computer-assisted proof that the impact map has positive
// topological entropy (a horseshoe of covering relations, verify/chaos.hpp), replayed at once
// by the second interval library (Arb, verify/chaos_certificate.hpp); --out PREFIX writes the
// certificate PREFIX.json (for `bouncer check-certificate`), PREFIX.csv (its h-sets in
// doubles), PREFIX.png (the h-sets over an orbit) and PREFIX-covering.png (the covering that closes the horseshoe, in its target's
// local coordinates).
#include <chrono>
#include <cstdio>
#include <memory>
#include <optional>
#include <set>

#include "bouncer/io/chaos_certificate.hpp"
#include "bouncer/io/reports/certify_chaos.hpp"
#include "bouncer/io/requests/certify_chaos.hpp"
#include "bouncer/run/portrait.hpp"
#include "cli_common.hpp"
#include "commands.hpp"

namespace bouncer::cli {

namespace {

const std::set<std::string>& certify_chaos_keys() {
  static const std::set<std::string> keys = [] {
    std::set<std::string> k = model_keys();
    k.insert({"bits", "replay-bits", "max-period", "max-pieces", "json", "out"});
    return k;
  }();
  return keys;
}

// The covering drawn: the one into N_0 from the last h-set of the chain (the return), else
// the first.
std::size_t drawn_covering(const ChaosCertificate& c) {
  for (std::size_t i = 0; i < c.coverings.size(); ++i)
    if (c.coverings[i].to == 0 && c.coverings[i].from == int(c.sets.size()) - 1) return i;
  return 0;
}

}  // namespace

CommandRunner setup_certify_chaos(CLI::App* sub) {
  auto opts = std::make_shared<OptionSet>(sub);
  auto scene = std::make_shared<std::string>();
  auto as_json = std::make_shared<bool>(false);
  sub->add_option("--scene", *scene, "TOML scene file with the same options (command line overrides)");
  add_model_options(*opts);
  opts->add("bits", "MPFI precision of the covering checks, integer in [32, 4096] (default 128)");
  opts->add("replay-bits", "Arb precision of the certificate's replay, integer in [32, 65536] (default 256)");
  opts->add("max-period", "Search saddles of period 1..Q, integer in [1, 8] (default 4)");
  opts->add("max-pieces", "Finest subdivision of an h-set per side, integer in [1, 1024] (default 64)");
  opts->add("out", "Also write PREFIX.json (the certificate), PREFIX.csv (its h-sets), PREFIX.png (the h-sets "
                   "over an orbit) and PREFIX-covering.png (the closing covering), all or none");
  sub->add_flag("--json", *as_json, "JSON output");
  auto quiet = std::make_shared<bool>(false);
  sub->add_flag("--quiet", *quiet, "Accepted like the picture commands (certify-chaos prints no progress)");

  // quiet is captured so that the flag's target lives as long as the command (CLI11 writes it).
  auto run = [opts, scene, as_json, quiet](const std::string& argv_text) {
    Options o = merge(scene->empty() ? Options{} : load_scene(*scene, "certify-chaos", certify_chaos_keys()),
                      opts->collected());
    if (*as_json) o.set("json", "true");
    const CertifyChaosRequest req = certify_chaos_request(o);
    const bool json = o.get_or("json", "false") == "true";
    std::optional<std::string> prefix;
    if (o.has("out")) prefix = o.get("out");
    OutputSet outputs;  // reserved before the work: a path that cannot be written is found at once
    if (prefix) {
      check_prefix("out", *prefix, "-covering.png");
      for (const char* suffix : {".json", ".csv", ".png", "-covering.png"}) outputs.reserve("out", *prefix + suffix);
    }
    // --out is where, not what: not an input (audit reruns into its own directory).
    Options inputs = o;
    inputs.values.erase("out");
    Provenance p = provenance_for("certify-chaos", inputs, Precision{Precision::Kind::interval, req.search.bits}, argv_text);
    p.precision = "interval (MPFI " + std::to_string(req.search.bits) + " bits; replay: Arb " +
                  std::to_string(req.replay_bits) + " bits)";
    const ChaosSearchResult r = certify_chaos(req.model, req.search);  // its made_by names bouncer and the commit
    std::optional<ReplayResult> replay;
    double replay_seconds = 0;
    if (r.proved) {
      const auto t0 = std::chrono::steady_clock::now();
      replay = replay_certificate(r.certificate, req.replay_bits);
      replay_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    }
    if (prefix && r.proved) {
      // An orbit under the h-sets: 20000 points of the orbit from the last h-set's centre
      // (next to the saddle; it leaves along the unstable manifold), after 1000 steps.
      PortraitRequest orbit;
      orbit.model = req.model;
      const auto decimal = [](const mpq_class& q) {
        char text[40];
        std::snprintf(text, sizeof text, "%.17g", q.get_d());
        return *Decimal::parse(text);
      };
      orbit.starts = {{decimal(r.certificate.sets.back().c[0]), decimal(r.certificate.sets.back().c[1])}};
      orbit.steps = 20000;
      orbit.transient = 1000;
      std::vector<std::pair<double, double>> points;
      const PortraitResult traced = portrait(orbit);  // named: the loop must not outlive it
      for (const PortraitPoint& q : traced.orbits.at(0).points) points.emplace_back(q.theta.value, q.v.value);
      Figure sets = horseshoe_figure(r.certificate, points);
      sets.metadata = png_metadata(p, sets.title);
      Figure cover = covering_figure(r.certificate, drawn_covering(r.certificate));
      cover.metadata = png_metadata(p, cover.title);
      write_output_set({{*prefix + ".json",
                         [&](std::ostream& s) {
                           s << certificate_json(r.certificate, p.as_json(),
                                                 {{"json", *prefix + ".json"}, {"csv", *prefix + ".csv"}, {"png", *prefix + ".png"},
                                                  {"covering_png", *prefix + "-covering.png"}});
                         }},
                        {*prefix + ".csv", [&](std::ostream& s) { write_hsets_csv(s, r.certificate, p.as_comment_lines()); }},
                        {*prefix + ".png", [&](std::ostream& s) { write_figure(s, sets, ImageFormat::png); }},
                        {*prefix + "-covering.png", [&](std::ostream& s) { write_figure(s, cover, ImageFormat::png); }}},
                       &outputs);
    }
    write_atomically(std::nullopt, [&](std::ostream& s) { write_certify_chaos(s, json, p, r, replay, replay_seconds); });
    return 0;
  };
  return run;
}

}  // namespace bouncer::cli
