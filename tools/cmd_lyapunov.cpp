// bouncer lyapunov: leading Lyapunov exponent per collision through the AD tangent map,
// with a transient, renormalisation at every step and a block error estimate.
#include <memory>
#include <set>

#include "analysis_common.hpp"
#include "bouncer/analysis/lyapunov.hpp"
#include "commands.hpp"

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

Command add_lyapunov(CLI::App& app) {
  CLI::App* sub = app.add_subcommand("lyapunov", "Leading Lyapunov exponent per collision (AD tangent map)");
  auto opts = std::make_shared<OptionSet>(sub);
  auto scene = std::make_shared<std::string>();
  auto json = std::make_shared<bool>(false);
  sub->add_option("--scene", *scene, "TOML scene file with the same options (command line overrides)");
  add_model_options(*opts);
  add_start_options(*opts);
  opts->add("transient", "Steps discarded first, integer in [0, 1e12] (default 1000)");
  opts->add("steps", "Steps measured, integer in [1, 1e12] (default 10000)");
  opts->add("blocks", "Blocks for the error estimate, integer in [1, 10000] (default 20)");
  opts->add("precision", kPointPrecisionHelp);
  sub->add_flag("--json", *json, "Print the summary as JSON on stdout");

  auto run = [opts, scene, json](const std::string& argv_text) {
    Options o = merge(scene->empty() ? Options{} : load_scene(*scene, "lyapunov", lyapunov_keys()), opts->collected());
    const ModelSpec spec = model_from(o);
    const InitialCondition ic = start_from(o, spec);
    LyapunovOptions lo;
    lo.transient = integer_from(o, "transient", 0, 1000000000000LL, 1000);
    lo.steps = integer_from(o, "steps", 1, 1000000000000LL, 10000);
    lo.blocks = integer_from(o, "blocks", 1, 10000, 20);
    const Precision prec = analysis_precision(o, "lyapunov");
    const Provenance p = provenance_for("lyapunov", o, prec, argv_text);
    const nlohmann::ordered_json body = with_point_scalar(
        prec, [&](auto tag) { return measure<typename decltype(tag)::type>(spec, prec, ic, lo); });
    print_summary(p, body, *json);
    if (!body["note"].get<std::string>().empty()) std::cerr << "bouncer lyapunov: " << body["note"].get<std::string>() << "\n";
    return 0;
  };
  return {sub, run};
}

}  // namespace bouncer::cli
