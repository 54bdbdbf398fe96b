// bouncer lyapunov: leading Lyapunov exponent per collision through the AD tangent map,
// with a transient, renormalisation at every step and a block error estimate.
//
// With --vary a|eps|c --range LO:HI --samples K it draws exponent curves (the paper's fig.
// lyapunov_one): at each value p_k = LO + (HI - LO) k/(K - 1) the same measurement as the
// single-point command (the same function, so a value's exponent is bit for bit that of
// `bouncer lyapunov` at that value) for --ics N initial conditions, each classified by
// bouncer::classify where its measured window ended (run/exponent_curve.hpp). A grid job like
// `bifurcation`: tiles, threads, shards, resume, `bouncer merge`. This file reads the options,
// runs the library's ExponentCurveGrid through the tiles, and writes.
#include <memory>
#include <set>

#include "analysis_common.hpp"
#include "bouncer/analysis/lyapunov.hpp"
#include "bouncer/io/curve_figures.hpp"
#include "bouncer/io/requests/exponent_curve.hpp"
#include "bouncer/run/exponent_curve.hpp"
#include "commands.hpp"
#include "picture_common.hpp"

namespace bouncer::cli {

namespace {

const std::set<std::string>& lyapunov_keys() {
  static const std::set<std::string> keys = [] {
    std::set<std::string> k = model_keys();
    k.insert({"theta", "v", "transient", "steps", "blocks", "precision"});
    return k;
  }();
  return keys;
}

// ---- exponent curves (--vary): run/exponent_curve.hpp ---------------------------------

void write_curve(const ExponentCurveResult& c, const RunFlags& f, const Provenance& prov) {
  const ExponentCurveRequest& r = c.request;
  std::string csv = "value,ic,theta0,v0,lambda,stderr,class,period\n";
  nlohmann::ordered_json per_value = nlohmann::ordered_json::array();
  for (const ExponentColumn& col : c.columns) {
    for (size_t j = 0; j < col.rows.size(); ++j) {
      const ExponentRow& row = col.rows[j];
      csv += col.value.digits + ',' + std::to_string(j) + ',' + c.starts[j].theta.text() + ',' + c.starts[j].v.text() + ',' +
             exponent_text(row.lambda) + ',' + exponent_text(row.stderr_) + ',' + name(row.cls) + ',' +
             std::to_string(row.period) + '\n';
    }
    per_value.push_back({{"value", col.value.digits}, {"max_lambda", json_number(col.max_lambda())},
                         {"mean_lambda", json_number(col.mean_lambda())}});
  }
  Figure fig = exponent_curve_figure(c, f.picture.palette);
  fig.metadata = png_metadata(prov, fig.title);
  nlohmann::ordered_json s;
  s["command"] = "lyapunov";
  s["vary"] = name(r.vary);
  s["range"] = {r.lo.text(), r.hi.text()};
  s["samples"] = r.samples;
  s["ics"] = r.ics;
  nlohmann::ordered_json starts = nlohmann::ordered_json::array();
  for (const InitialCondition& ic : c.starts) starts.push_back({ic.theta.text(), ic.v.text()});
  s["starts"] = starts;
  s["transient"] = r.lyapunov.transient;
  s["steps"] = r.lyapunov.steps;
  s["blocks"] = r.lyapunov.blocks;
  nlohmann::ordered_json classes;
  for (const CurveClassCount& k : exponent_census(c)) classes[name(k.cls)] = k.rows;
  s["classes"] = classes;
  s["values"] = per_value;
  s["precision"] = r.precision.text();
  write_outputs(f, prov, csv, [&](std::ostream& out, ImageFormat fmt) { write_figure(out, fig, fmt, f.picture.render); }, s);
}

template <class T>
nlohmann::ordered_json measure(const ModelSpec& spec, const Precision& prec, const InitialCondition& ic,
                               const LyapunovOptions& lo) {
  const Model<T> m = make_model<T>(spec, prec.bits);
  const LyapunovResult r = lyapunov(m, make_state<T>(ic, prec.bits), lo);
  nlohmann::ordered_json j;
  j["lambda"] = json_number(r.lambda);
  j["stderr"] = json_number(r.stderr_);
  j["steps"] = r.steps;
  j["transient"] = lo.transient;
  j["blocks"] = r.blocks;
  j["contracted"] = r.contracted;
  j["unbounded"] = r.unbounded;
  j["growth_alpha"] = json_number(r.alpha);
  j["v_max"] = json_number(r.v_max);
  j["undecided"] = r.undecided;
  j["note"] = r.note;
  return j;
}

}  // namespace

const std::set<std::string>& lyapunov_curve_keys() {
  static const std::set<std::string> keys = [] {
    std::set<std::string> k = lyapunov_keys();
    k.insert({"vary", "range", "samples", "ics", "max-period", "recheck-factor"});
    k.insert(run_keys().begin(), run_keys().end());
    k.insert(picture_keys().begin(), picture_keys().end());
    return k;
  }();
  return keys;
}

int run_lyapunov_curve(const Options& o, const RunFlags& f) {
  const ExponentCurveGrid grid(exponent_curve_request(o));  // validates the request, computes the starts
  const Provenance prov = provenance_for("lyapunov", job_options(o), grid.request().precision, f.invocation);
  if (const auto columns = run_cells<ExponentColumn>("lyapunov", o, f, grid, grid.item_bytes(), "samples"))
    write_curve(grid.result(*columns), f, prov);
  return 0;
}

CommandRunner setup_lyapunov(CLI::App* sub) {
  auto opts = std::make_shared<OptionSet>(sub);
  auto scene = std::make_shared<std::string>();
  sub->add_option("--scene", *scene, "TOML scene file with the same options (command line overrides)");
  add_model_options(*opts);
  add_start_options(*opts);
  opts->add("transient", "Steps discarded first, integer in [0, 1e12] (default 1000; at most 1e9 with --vary)");
  opts->add("steps", "Steps measured, integer in [1, 1e12] (default 10000)");
  opts->add("blocks", "Blocks for the error estimate, integer in [1, 10000] (default 20)");
  opts->add("precision", kPointPrecisionHelp);
  opts->add("vary", "Exponent curve: the parameter to sweep, a | eps (constant model) | c (veldep model)");
  opts->add("range", "With --vary: LO:HI (decimals, LO < HI, both inside the model's range), both included");
  opts->add("samples", "With --vary: number of values K, 1..100000 (default 100)");
  opts->add("ics", "With --vary: starts per value N, 1..1000 (default 1): --theta/--v (default 0.1, wall speed + 2), "
                   "then an R2 low-discrepancy spread in the trapping region");
  add_classify_period_options(*opts);  // with --vary: the classifier of each row (steps = 500 there)
  auto flags = add_run_options(sub, *opts);
  auto json = std::shared_ptr<bool>(flags, &flags->json);

  auto run = [opts, scene, json, flags](const std::string& argv_text) {
    Options o = merge(scene->empty() ? Options{} : load_scene(*scene, "lyapunov", lyapunov_curve_keys()), opts->collected());
    if (o.has("vary")) return run_lyapunov_curve(o, run_flags_from(o, *flags, argv_text));
    for (const char* k : {"range", "samples", "ics", "max-period", "recheck-factor", "shard", "out", "threads"})
      if (o.has(k)) throw InputError(k, "belongs to an exponent curve: give --vary a|eps|c with --range LO:HI");
    if (flags->quiet || flags->keep_tiles || flags->force)
      throw InputError("vary", "--quiet/--keep-tiles/--force belong to an exponent curve (--vary)");
    const ModelSpec spec = model_from(o);
    const InitialCondition ic = start_from(o, spec);
    const LyapunovOptions lo = lyapunov_options_from(o);
    const Precision prec = analysis_precision(o, "lyapunov");
    const Provenance p = provenance_for("lyapunov", o, prec, argv_text);
    const nlohmann::ordered_json body = with_point_scalar(
        prec, [&](auto tag) { return measure<typename decltype(tag)::type>(spec, prec, ic, lo); });
    print_summary(p, body, *json);
    if (!body["note"].get<std::string>().empty()) std::cerr << "bouncer lyapunov: " << body["note"].get<std::string>() << "\n";
    return 0;
  };
  return run;
}

}  // namespace bouncer::cli
