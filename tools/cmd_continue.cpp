// bouncer continue: follow a period-q orbit (Newton) in a, eps or c in both directions from
// the guess's parameter value, locate where the branch ends (border collision, grazing,
// touchdown, sticking threshold, fold, the period doubling it is born from) and the smooth bifurcations on the way (period
// doubling, Neimark-Sacker), and classify what the map does just beyond each end.
// Outputs: PREFIX.csv (one row per branch point), PREFIX.json (branch summary), PREFIX.png
// (branch diagram); without --out a text summary, or the JSON summary with --json.
#include <memory>

#include "bouncer/io/reports/continue.hpp"
#include "bouncer/io/requests/continue.hpp"
#include "bouncer/verify/branch_end.hpp"
#include "cli_common.hpp"
#include "commands.hpp"

namespace bouncer::cli {

namespace {

const std::set<std::string>& continue_keys() {
  static const std::set<std::string> keys = [] {
    std::set<std::string> k = model_keys();
    k.insert({"period", "guess", "vary", "range", "precision", "step", "max-points", "max-iter", "beyond", "show",
              "transient", "steps", "max-period", "out", "certify"});
    k.insert(picture_keys().begin(), picture_keys().end());
    return k;
  }();
  return keys;
}

// The science inputs are the library's request (io/requests/continue.hpp); the picture's
// options and --out are the command's.
struct Request {
  ContinueRequest science;
  std::string show = "v";
  std::optional<std::string> out;
  Presentation picture;  // --format, --size, --dpi, --palette
};

Request request_from(const Options& o) {
  Request r;
  r.science = continue_request(o);
  r.show = o.get_or("show", "v");
  if (r.show != "theta" && r.show != "v") throw InputError("show", "must be theta or v (got '" + r.show + "')");
  if (o.has("out")) {
    r.out = o.get("out");
    check_prefix("out", *r.out, ".json");
  }
  r.picture = presentation_from(o);
  if (r.out) check_figure_font();  // an output failure, found before the work
  return r;
}

template <class T>
int run_typed(const Request& req, const Provenance& prov, bool print_json, OutputSet& outputs) {
  using Tr = ScalarTraits<T>;
  const ContinueRequest& r = req.science;
  const long bits = r.precision.bits;
  const Model<T> m = make_model<T>(r.model, bits);
  const T lo = Tr::from_decimal(r.lo.text(), bits), hi = Tr::from_decimal(r.hi.text(), bits);
  Branch<T> b = continue_branch(m, r.vary, r.period, make_state<T>(r.guess, bits), lo, hi, r.opt);
  if (!b.started) throw InputError("guess", b.note);
  // The digits of each located end that an error estimate backs (analysis/end_estimate.hpp).
  estimate_end_accuracy(r.model, b, r.opt);
  // --certify: Krawczyk on the branch side of each border end (verify/branch_end.hpp).
  // --certify: also every period doubling and fold, on the branch or at an end (a doubling
  // end: the period-q/2 orbit's period doubling).
  CertifiedBranchEnds certified = r.certify ? certify_branch_ends(r.model, r.vary, r.period, b, bits) : CertifiedBranchEnds{};
  if (r.certify) certify_smooth_events(r.model, r.vary, r.period, b, bits, certified);
  const std::string doc = branch_json(r, m, b, certified, prov);
  if (req.out) {
    const Figure fig = branch_figure(r, m, b, req.show == "theta", prov);
    std::vector<OutputFile> files{{*req.out + ".csv", [&](std::ostream& f) { f << prov.as_comment_lines() << branch_csv(b, r.vary); }}};
    for (OutputFile& pic : picture_files(*req.out, req.picture, [&](std::ostream& out, ImageFormat fmt) {
           write_figure(out, fig, fmt, req.picture.render);
         }))
      files.push_back(std::move(pic));
    files.push_back({*req.out + ".json", [&](std::ostream& f) { f << doc; }});
    write_output_set(files, &outputs);
  }
  command_out() << (print_json ? doc : branch_text(r, b, certified, prov));
  return 0;
}

}  // namespace

CommandRunner setup_continue(CLI::App* sub) {
  auto opts = std::make_shared<OptionSet>(sub);
  auto scene = std::make_shared<std::string>();
  auto json_flag = std::make_shared<bool>(false);
  sub->add_option("--scene", *scene, "TOML scene file with the same options (command line overrides)");
  add_model_options(*opts);
  opts->add("period", "Period q, integer in [1, " + std::to_string(kMaxBranchPeriod) + "] (required)");
  opts->add_list("guess", "Starting point theta,v near the orbit at the start value (required)");
  opts->add("vary", "Parameter to continue in: a (default) | eps (constant model) | c (veldep model)");
  opts->add("range", "Interval LO:HI of the parameter (required); the start is the model's value (default LO)");
  opts->add("precision", "double (default) | long | dd | quad | mpfr:BITS (16 <= BITS <= 1048576)");
  opts->add("step", "First continuation step, decimal in (0, HI - LO] (default (HI - LO)/100)");
  opts->add("max-points", "Most branch points, both directions together, integer in [2, 100000] (default 2000)");
  opts->add("max-iter", "Newton iterations per corrector run, integer in [1, 10000] (default 30)");
  opts->add("beyond", "Classify at a* + BEYOND*max(1,|a*|) past each end, decimal in (0, 0.1] (default 1e-6)");
  opts->add("show", "Picture: v (default) or theta of every orbit point against the parameter");
  add_classify_options(*opts);
  opts->add("out", "Write PREFIX.csv, PREFIX.json and the pictures PREFIX.png/.pdf/.svg of --format");
  add_picture_options(*opts);
  sub->add_flag("--json", *json_flag, "Print the JSON summary on stdout");
  // Accepted like the grid commands' --quiet (reproduce passes it to every panel); continue
  // draws no progress bar, so it changes nothing.
  auto quiet = std::make_shared<bool>(false);
  sub->add_flag("--quiet", *quiet, "Accepted like the picture commands (continue prints no progress)");
  opts->add_flag("certify",
                 "Krawczyk proofs: each border end's a* enclosed on both sides (and a one-sided bound from the branch side), each period doubling and fold enclosed");
  // The lambda holds every flag's storage: CLI11 writes through the references after
  // add_continue has returned.
  auto run = [opts, scene, json_flag, quiet](const std::string& argv_text) {
    const Options o = merge(scene->empty() ? Options{} : load_scene(*scene, "continue", continue_keys()), opts->collected());
    const Request req = request_from(o);
    const Provenance prov = provenance_for("continue", o, req.science.precision, argv_text);
    OutputSet outputs;  // reserved before the work: a path that cannot be written is found at once
    if (req.out)
      for (const std::string& path : output_paths(*req.out, req.picture)) outputs.reserve("out", path);
    return with_point_scalar(req.science.precision, [&](auto tag) {
      return run_typed<typename decltype(tag)::type>(req, prov, *json_flag, outputs);
    });
  };
  return run;
}

}  // namespace bouncer::cli
