// bouncer portrait: phase portraits (theta_n, v_n) of several orbits, one colour each;
// --polar draws (phi = 2 pi theta, radius v), where the elastic model's branched Fermi
// acceleration (paper sec. III, a = 19) shows as straight branches.
#include <cmath>
#include <memory>
#include <sstream>

#include "bouncer/model/impact_map.hpp"
#include "commands.hpp"
#include "picture_common.hpp"

namespace bouncer::cli {

namespace {

struct PortraitRequest {
  ModelSpec model;
  std::vector<InitialCondition> initial;
  long steps = 1000, transient = 0;
  bool polar = false;
  Precision precision;
};

PortraitRequest portrait_request(const Options& o) {
  PortraitRequest r;
  r.model = model_from(o);
  r.initial = initial_conditions_from(o, r.model);
  if (r.initial.size() > 1000) throw InputError("theta", "at most 1000 initial conditions");
  r.steps = integer_from(o, "steps", 1, 10000000, 1000);
  r.transient = integer_from(o, "transient", 0, 100000000, 0);
  if (static_cast<double>(r.steps) * static_cast<double>(r.initial.size()) > 2e7)
    throw InputError("steps", "orbits x steps must be at most 2e7 points");
  const std::string polar = o.get_or("polar", "false");
  if (polar != "true" && polar != "false") throw InputError("polar", "must be true or false");
  r.polar = polar == "true";
  r.precision = point_precision(o);
  return r;
}

template <class T>
std::string orbit_rows(const PortraitRequest& r, const ImpactMap<T>& map, long k) {
  using Tr = ScalarTraits<T>;
  State<T> s = make_state<T>(r.initial[static_cast<size_t>(k)], r.precision.bits);
  std::ostringstream out;
  long n = 0;
  try {
    for (; n < r.transient; ++n) s = map.step(s).next;
    if (r.transient == 0) out << k << ",0," << Tr::to_string(s.theta) << ',' << Tr::to_string(s.v) << ",start\n";
    for (long m = 0; m < r.steps; ++m, ++n) {
      const StepResult<T> st = map.step(s);
      s = st.next;
      out << k << ',' << n + 1 << ',' << Tr::to_string(s.theta) << ',' << Tr::to_string(s.v) << ',' << name(st.kind) << '\n';
    }
  } catch (const Undecided& u) {
    out << "# undecided: orbit " << k << " step " << n + 1 << ": " << u.what() << "\n";
  }
  return out.str();
}

void finish(const PortraitRequest& r, const std::vector<std::string>& items, const RunFlags& f, const Provenance& prov) {
  std::string csv = "orbit,n,theta,v,event\n";
  Figure fig;
  long points = 0, undecided = 0;
  double vmax = 0;
  const double two_pi = 2 * std::acos(-1.0);
  for (size_t k = 0; k < items.size(); ++k) {
    csv += items[k];
    Series s;
    s.color = items.size() == 1 ? Rgb{20, 20, 20} : category_color(static_cast<int>(k));
    s.marker_size = r.steps * items.size() > 20000 ? 0 : 1;
    if (k < 12) s.label = "θ0 = " + r.initial[k].theta.text() + ", v0 = " + r.initial[k].v.text();
    std::istringstream in(items[k]);
    std::string line;
    while (std::getline(in, line)) {
      if (line.empty()) continue;
      if (line[0] == '#') { ++undecided; continue; }
      std::istringstream ls(line);
      std::string cell[5];
      for (auto& c : cell) std::getline(ls, c, ',');
      const double th = std::strtod(cell[2].c_str(), nullptr), v = std::strtod(cell[3].c_str(), nullptr);
      vmax = std::max(vmax, v);
      if (r.polar) {
        s.x.push_back(v * std::cos(two_pi * th));
        s.y.push_back(v * std::sin(two_pi * th));
      } else {
        s.x.push_back(th);
        s.y.push_back(v);
      }
      ++points;
    }
    fig.series.push_back(std::move(s));
  }
  if (items.size() > 12) {
    Series more;
    more.label = "... " + std::to_string(items.size() - 12) + " more orbits";
    more.color = Rgb{160, 160, 160};
    fig.series.push_back(more);
  }
  fig.title = std::string(r.polar ? "Polar phase portrait, " : "Phase portrait, ") + name(r.model.law) + " model";
  std::string par = "a = " + r.model.a.text();
  if (r.model.law == Law::constant) par += ", ε = " + r.model.eps.text();
  if (r.model.law == Law::veldep) par += ", c = " + r.model.c.text();
  fig.subtitle = par + "; " + std::to_string(items.size()) + (items.size() == 1 ? " orbit, " : " orbits, ") +
                 std::to_string(r.steps) + " steps" + (r.transient ? " after " + std::to_string(r.transient) : "") + ", " +
                 r.precision.text();
  if (r.polar) {
    fig.xlabel = "v cos(2πθ)";
    fig.ylabel = "v sin(2πθ)";
    fig.equal_aspect = true;
    fig.height = 800;
    fig.width = 1000;
  } else {
    fig.xlabel = "θ (phase of impact)";
    fig.ylabel = "v (velocity after impact)";
    fig.x_min = 0;
    fig.x_max = 1;
  }
  fig.metadata = png_metadata(prov, fig.title);
  nlohmann::ordered_json s;
  s["command"] = "portrait";
  s["orbits"] = items.size();
  s["points"] = points;
  s["undecided_orbits"] = undecided;
  s["max_v"] = vmax;
  s["polar"] = r.polar;
  s["precision"] = r.precision.text();
  write_outputs(f, prov, csv, [&](const std::string& path) { write_png(path, fig); }, s);
}

}  // namespace

const std::set<std::string>& portrait_keys() {
  static const std::set<std::string> keys = [] {
    std::set<std::string> k = model_keys();
    k.insert({"theta", "v", "steps", "transient", "polar", "precision"});
    k.insert(run_keys().begin(), run_keys().end());
    return k;
  }();
  return keys;
}

int run_portrait(const Options& o, const RunFlags& f) {
  const PortraitRequest req = portrait_request(o);
  PictureJob job;
  job.command = "portrait";
  job.job = job_options(o);
  job.plan.items = static_cast<long>(req.initial.size());
  job.plan.tile_items = 1;
  const Provenance prov = provenance_for("portrait", job.job, req.precision, f.invocation);
  return with_scalar(req.precision, [&](auto tag) -> int {
    using T = typename decltype(tag)::type;
    if constexpr (ScalarTraits<T>::is_interval) {
      throw InputError("precision", "interval precision is not supported here");
    } else {
      auto map = std::make_shared<ImpactMap<T>>(make_model<T>(req.model, req.precision.bits));
      job.item = [map, &req](long k) { return orbit_rows<T>(req, *map, k); };
      const auto items = run_job(job, f);
      if (items) finish(req, *items, f, prov);
      return 0;
    }
  });
}

Command add_portrait(CLI::App& app) {
  CLI::App* sub = app.add_subcommand("portrait", "Phase portrait (theta, v) of several orbits; --polar for Fermi acceleration");
  auto opts = std::make_shared<OptionSet>(sub);
  auto scene = std::make_shared<std::string>();
  auto polar = std::make_shared<bool>(false);
  sub->add_option("--scene", *scene, "TOML scene file with the same options (command line overrides)");
  add_model_options(*opts);
  opts->add_list("theta", "Initial phases in [0, 1), a comma list (one orbit each)");
  opts->add_list("v", "Initial velocities, as many as theta, each >= the wall velocity at its theta");
  opts->add("steps", "Steps drawn per orbit (default 1000)");
  opts->add("transient", "Steps discarded first (default 0)");
  opts->add("precision", kPointPrecisionHelp);
  sub->add_flag("--polar", *polar, "Polar picture: angle 2 pi theta, radius v");
  auto flags = add_run_options(sub, *opts);
  auto run = [opts, scene, polar, flags](const std::string& argv_text) {
    Options cl = opts->collected();
    if (*polar) cl.set("polar", "true");
    const Options o = merge(scene->empty() ? Options{} : load_scene(*scene, "portrait", portrait_keys()), cl);
    return run_portrait(o, run_flags_from(o, *flags, argv_text));
  };
  return {sub, run};
}

}  // namespace bouncer::cli
