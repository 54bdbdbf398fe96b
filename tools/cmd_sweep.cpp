// bouncer sweep: one orbit question in every precision (double, long double, quad, MPFR at
// 64 ... 4096 bits) against a certified interval reference: where each leaves the
// enclosure, what it answers, and the Lyapunov exponent the divergence steps imply.
#include <memory>
#include <set>

#include "bouncer/io/reports/sweep.hpp"
#include "bouncer/verify/sweep.hpp"
#include "cli_common.hpp"
#include "commands.hpp"

namespace bouncer::cli {

namespace {

const std::set<std::string>& sweep_keys() {
  static const std::set<std::string> keys = [] {
    std::set<std::string> k = model_keys();
    k.insert({"theta", "v", "steps", "tolerance", "reference-max-bits", "method", "classify-steps", "json", "out"});
    k.insert(picture_keys().begin(), picture_keys().end());
    return k;
  }();
  return keys;
}

struct Request {
  SweepQuestion q;
  bool json = false;
  std::optional<std::string> prefix;
  Presentation picture;  // --format, --size, --dpi, --palette
};

Request request_from(const Options& o) {
  Request r;
  r.q.model = model_from(o);
  const std::vector<InitialCondition> ic = initial_conditions_from(o, r.q.model);
  if (ic.size() != 1) throw InputError("theta", "takes one initial condition");
  r.q.start = ic[0];
  r.q.steps = integer_from(o, "steps", 1, 1000000, 1000);
  if (o.has("tolerance")) {
    const Decimal t = parse_decimal("tolerance", o.get("tolerance"));
    if (!(Decimal::from_int(0) <= t) || t > Decimal::from_int(1))
      throw InputError("tolerance", "must be a decimal in [0, 1] (got " + o.get("tolerance") + ")");
    r.q.tolerance = t.approx();
  }
  r.q.reference.max_bits = integer_from(o, "reference-max-bits", 64, kMaxBits, 16384);
  r.q.method = parse_enclosure_method("method", o.get_or("method", "lohner"));
  r.q.classify_steps = integer_from(o, "classify-steps", 8, 1000000, 500);
  r.json = o.get_or("json", "false") == "true";
  if (o.has("out")) {
    r.prefix = o.get("out");
    check_prefix("out", *r.prefix, ".json");
  }
  r.picture = presentation_from(o);
  if (r.prefix) check_figure_font();  // an output failure, found before the work
  return r;
}

}  // namespace

CommandRunner setup_sweep(CLI::App* sub) {
  auto opts = std::make_shared<OptionSet>(sub);
  auto scene = std::make_shared<std::string>();
  auto as_json = std::make_shared<bool>(false);
  sub->add_option("--scene", *scene, "TOML scene file with the same options (command line overrides)");
  add_model_options(*opts);
  add_start_options(*opts);
  opts->add("steps", "Number of steps N, integer in [1, 1000000] (default 1000)");
  opts->add("tolerance", "Distance from the enclosure that counts as leaving it, decimal in [0, 1] (default 2^-20)");
  opts->add("reference-max-bits", "Largest precision of the certified reference's escalation (default 16384)");
  opts->add("method", "Reference enclosure: lohner (default) | naive");
  opts->add("classify-steps", "Rows with neither sticking nor a period are classified over this many more steps, "
                              "integer in [8, 1000000] (default 500)");
  opts->add("out", "PREFIX: write PREFIX.json, PREFIX.csv and the pictures PREFIX.png/.pdf/.svg of --format (atomically)");
  add_picture_options(*opts);
  sub->add_flag("--json", *as_json, "JSON on stdout instead of the text table");

  auto run = [opts, scene, as_json](const std::string& argv_text) {
    Options o = merge(scene->empty() ? Options{} : load_scene(*scene, "sweep", sweep_keys()), opts->collected());
    if (*as_json) o.set("json", "true");
    const Request r = request_from(o);
    OutputSet outputs;  // reserved before the work: a path that cannot be written is found at once
    if (r.prefix)
      for (const std::string& path : output_paths(*r.prefix, r.picture)) outputs.reserve("out", path);
    Provenance p = provenance_for("sweep", o, Precision{Precision::Kind::interval, r.q.reference.max_bits}, argv_text);
    p.precision = "double, long, dd, quad, mpfr:64..4096 against interval (escalated " + r.q.reference.text() + ")";
    const SweepReport rep = precision_sweep(r.q);
    p.bits = rep.reference_bits;
    const std::string doc = sweep_json(rep, r.q, p);
    if (r.prefix) {
      const Figure fig = sweep_divergence_figure(rep, r.q, p);
      std::vector<OutputFile> files{{*r.prefix + ".json", [&](std::ostream& s) { s << doc; }},
                                    {*r.prefix + ".csv", [&](std::ostream& s) { s << sweep_csv(rep, p); }}};
      for (OutputFile& pic : picture_files(*r.prefix, r.picture, [&](std::ostream& out, ImageFormat fmt) {
             write_figure(out, fig, fmt, r.picture.render);
           }))
        files.push_back(std::move(pic));
      write_output_set(files, &outputs);
    }
    if (r.json) command_out() << doc;
    else command_out() << p.as_comment_lines() << sweep_table(rep, r.q);
    return 0;
  };
  return run;
}

}  // namespace bouncer::cli
