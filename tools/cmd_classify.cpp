// bouncer classify: the long-term behaviour of one orbit (attractor type) with evidence, and
// whether a higher precision agrees (analysis/classify.hpp classify_checked): an answer that
// holds only in the run's precision is named an artefact.
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
    k.insert({"theta", "v", "transient", "steps", "max-period", "recheck-factor", "precision", "confirm-bits", "no-confirm"});
    return k;
  }();
  return keys;
}

nlohmann::ordered_json classification_json(const Classification& c) {
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
  return j;
}

nlohmann::ordered_json precision_check_json(const CheckedClassification& r) {
  nlohmann::ordered_json j;
  j["verdict"] = name(r.verdict);
  j["summary"] = r.summary;
  j["checks"] = nlohmann::ordered_json::array();
  for (const PrecisionCheck& c : r.checks) {
    nlohmann::ordered_json one;
    one["precision"] = c.precision.text();
    const nlohmann::ordered_json fields = classification_json(c.result);  // (items() does not keep a temporary alive)
    for (const auto& [k, v] : fields.items()) one[k] = v;
    j["checks"].push_back(one);
  }
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
  opts->add("confirm-bits", "Classify the start again at mpfr:B, B = max(BITS, 2 x the run's bits), and at 2B if the two "
                            "differ, and say whether the run's class is an artefact; BITS in [64, 1048576] (default 256)");
  opts->add_flag("no-confirm", "Do not classify again at a higher precision");
  sub->add_flag("--json", *json, "Print the summary as JSON on stdout");

  auto run = [opts, scene, json](const std::string& argv_text) {
    Options o = merge(scene->empty() ? Options{} : load_scene(*scene, "classify", classify_keys()), opts->collected());
    const ModelSpec spec = model_from(o);
    const InitialCondition ic = start_from(o, spec);
    const ClassifyOptions co = classify_options_from(o);
    const Precision prec = analysis_precision(o, "classify");
    const Provenance p = provenance_for("classify", o, prec, argv_text);
    const long confirm_bits = integer_from(o, "confirm-bits", 64, kMaxBits, 256);
    nlohmann::ordered_json body;
    if (flag_from(o, "no-confirm")) {
      body = classification_json(classify_start(spec, prec, ic, co));
    } else {
      const CheckedClassification r = classify_checked(spec, prec, ic, co, confirm_bits);
      body = classification_json(r.result);
      // The text summary gives the sentence; JSON the checks too.
      body["precision_check"] = *json ? precision_check_json(r) : nlohmann::ordered_json(r.summary);
    }
    body["transient"] = co.transient;
    body["steps"] = co.steps;
    body["max_period"] = co.max_period;
    body["recheck_factor"] = co.recheck_factor;
    print_summary(p, body, *json);
    return 0;
  };
  return run;
}

}  // namespace bouncer::cli
