// bouncer periodic: find a period-q orbit by damped Newton on P^q(x) - x (theta compared
// modulo 1), with its stability multipliers from the AD Jacobian.
#include <memory>
#include <set>

#include "analysis_common.hpp"
#include "bouncer/analysis/periodic.hpp"
#include "bouncer/io/requests/guess.hpp"
#include "commands.hpp"

namespace bouncer::cli {

namespace {

const std::set<std::string>& periodic_keys() {
  static const std::set<std::string> keys = [] {
    std::set<std::string> k = model_keys();
    k.insert({"period", "guess", "precision", "max-iter", "grid"});
    return k;
  }();
  return keys;
}

template <class T>
nlohmann::ordered_json solve(const ModelSpec& spec, const Precision& prec, long q,
                             const std::optional<InitialCondition>& guess, const NewtonOptions& no) {
  using Tr = ScalarTraits<T>;
  const Model<T> m = make_model<T>(spec, prec.bits);
  PeriodicOrbit<T> o = guess ? find_periodic(m, q, make_state<T>(*guess, prec.bits), no) : search_periodic(m, q, no);
  nlohmann::ordered_json j;
  j["converged"] = o.converged;
  j["period"] = q;
  j["minimal_period"] = o.minimal_period;
  nlohmann::ordered_json pts = nlohmann::ordered_json::array();
  for (const State<T>& s : o.points) pts.push_back({Tr::to_string(s.theta), Tr::to_string(s.v)});
  j["points"] = pts;
  // Multipliers and events belong to an orbit: null and empty where Newton found none.
  nlohmann::ordered_json mu = nlohmann::ordered_json::array();
  for (int i = 0; i < 2; ++i) mu.push_back({Tr::to_string(o.multipliers.re[i]), Tr::to_string(o.multipliers.im[i])});
  j["multipliers"] = o.converged ? mu : nlohmann::ordered_json();  // [re, im] pairs, largest modulus first
  j["multiplier_moduli"] = o.converged ? nlohmann::ordered_json{json_number(o.multipliers.modulus(0)), json_number(o.multipliers.modulus(1))}
                                       : nlohmann::ordered_json();
  j["complex_pair"] = o.converged ? nlohmann::ordered_json(o.multipliers.complex) : nlohmann::ordered_json();
  j["marginal"] = o.converged ? nlohmann::ordered_json(o.marginal) : nlohmann::ordered_json();
  j["stability"] = stability_of(o);
  nlohmann::ordered_json kinds = nlohmann::ordered_json::array();
  if (o.converged)
    for (EventKind k : o.kinds) kinds.push_back(name(k));
  j["events"] = kinds;
  j["wall_periods"] = o.converged ? o.wall_periods : std::vector<long long>{};
  j["residual"] = json_number(o.residual);
  j["tolerance"] = json_number(o.tolerance);
  j["iterations"] = o.iterations;
  j["note"] = o.note;
  return j;
}

}  // namespace

CommandRunner setup_periodic(CLI::App* sub) {
  auto opts = std::make_shared<OptionSet>(sub);
  auto scene = std::make_shared<std::string>();
  auto json = std::make_shared<bool>(false);
  sub->add_option("--scene", *scene, "TOML scene file with the same options (command line overrides)");
  add_model_options(*opts);
  opts->add("period", "Period q, integer in [1, 100]");
  opts->add_list("guess", "Starting point theta,v (default: a grid of guesses in the trapping region)");
  opts->add("precision", kPointPrecisionHelp);
  opts->add("max-iter", "Newton iterations per guess, integer in [1, 10000] (default 60)");
  opts->add("grid", "Guesses per axis without --guess, integer in [1, 64] (default 8)");
  sub->add_flag("--json", *json, "Print the summary as JSON on stdout");

  auto run = [opts, scene, json](const std::string& argv_text) {
    Options o = merge(scene->empty() ? Options{} : load_scene(*scene, "periodic", periodic_keys()), opts->collected());
    const ModelSpec spec = model_from(o);
    const long q = periodic_period_from(o);
    const NewtonOptions no = periodic_newton_from(o);
    const std::optional<InitialCondition> guess = guess_from(o, spec);
    const Precision prec = analysis_precision(o, "periodic");
    const Provenance p = provenance_for("periodic", o, prec, argv_text);
    const nlohmann::ordered_json body = with_point_scalar(
        prec, [&](auto tag) { return solve<typename decltype(tag)::type>(spec, prec, q, guess, no); });
    print_summary(p, body, *json);
    if (!body["converged"].get<bool>())
      std::cerr << "bouncer periodic: no period-" << q << " orbit converged: " << body["note"].get<std::string>() << "\n";
    return 0;
  };
  return run;
}

}  // namespace bouncer::cli
