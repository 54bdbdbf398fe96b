// bouncer classify: the long-term behaviour of one orbit (attractor type) with evidence.
#include <memory>
#include <set>

#include "analysis_common.hpp"
#include "bouncer/analysis/classify.hpp"
#include "commands.hpp"

namespace bouncer::cli {

namespace {

const std::set<std::string>& classify_keys() {
  static const std::set<std::string> keys = [] {
    std::set<std::string> k = model_keys();
    k.insert({"theta", "v", "transient", "steps", "max-period", "recheck-factor", "precision"});
    return k;
  }();
  return keys;
}

template <class T>
nlohmann::ordered_json run_classify(const ModelSpec& spec, const Precision& prec, const InitialCondition& ic,
                                    const ClassifyOptions& co) {
  const ImpactMap<T> map(make_model<T>(spec, prec.bits));
  const Classification c = classify<T>(map, make_state<T>(ic, prec.bits), co);
  nlohmann::ordered_json j;
  j["class"] = name(c.cls);
  j["period"] = c.period;
  j["lambda"] = json_number(c.lambda);
  j["evidence"] = c.evidence;
  if (c.cls == OrbitClass::unbounded) {
    j["growth_alpha"] = json_number(c.alpha);
    j["growth_per_step"] = json_number(c.growth_rate);
    j["phase_branches"] = c.branches;
    j["accelerator_period"] = c.accel_period;
    j["accelerator_gain"] = json_number(c.accel_gain);
    j["growth_kind"] = c.growth_kind;
  }
  if (c.cls == OrbitClass::transient_chaos) {
    j["settled_class"] = name(c.settled_class);
    j["settled_at"] = c.settled_at;
  }
  j["transient"] = co.transient;
  j["steps"] = co.steps;
  j["max_period"] = co.max_period;
  j["recheck_factor"] = co.recheck_factor;
  return j;
}

}  // namespace

CommandRunner setup_classify(CLI::App* sub) {
  auto opts = std::make_shared<OptionSet>(sub);
  auto scene = std::make_shared<std::string>();
  auto json = std::make_shared<bool>(false);
  sub->add_option("--scene", *scene, "TOML scene file with the same options (command line overrides)");
  add_model_options(*opts);
  add_start_options(*opts);
  add_classify_options(*opts);
  opts->add("precision", kPointPrecisionHelp);
  sub->add_flag("--json", *json, "Print the summary as JSON on stdout");

  auto run = [opts, scene, json](const std::string& argv_text) {
    Options o = merge(scene->empty() ? Options{} : load_scene(*scene, "classify", classify_keys()), opts->collected());
    const ModelSpec spec = model_from(o);
    const InitialCondition ic = start_from(o, spec);
    const ClassifyOptions co = classify_options_from(o);
    const Precision prec = analysis_precision(o, "classify");
    const Provenance p = provenance_for("classify", o, prec, argv_text);
    const nlohmann::ordered_json body = with_point_scalar(
        prec, [&](auto tag) { return run_classify<typename decltype(tag)::type>(spec, prec, ic, co); });
    print_summary(p, body, *json);
    return 0;
  };
  return run;
}

}  // namespace bouncer::cli
