// bouncer bifurcation: sweep one parameter (a, eps or c); at each value follow an orbit for
// N transient steps and record the next M (paper sec. IV.B: N = 5000, M = 500; run/
// bifurcation.hpp). Output: CSV rows (param, n, theta, v, sticking), a density image of theta
// (or v) against the parameter with the sticking releases marked in red at theta = 1/2 as in
// the paper, and a JSON summary. Each parameter value is one grid item (independent unless
// --carry). --certify: each column also gets a certified answer for the exact orbit at the
// exact double value of the parameter and double's class of the same orbit.
// This file reads the options, runs the library's BifurcationGrid through the tiles, and writes.
#include "bouncer/run/bifurcation.hpp"
#include "bouncer/io/requests/grids.hpp"
#include "commands.hpp"
#include "picture_common.hpp"

namespace bouncer::cli {

namespace {

void write_bifurcation(const BifurcationResult& res, const BifurcationOptions& b, const RunFlags& f, const Provenance& prov) {
  const BifurcationRequest& r = res.request;
  const std::string vary = name(r.vary);
  std::string csv = vary + ",n,theta,v,sticking\n";
  long rows = 0, undecided = 0, sticking_samples = 0, sticking_events = 0, differs = 0, agrees = 0, open = 0;
  nlohmann::ordered_json columns = nlohmann::ordered_json::array();
  for (const BifurcationColumn& c : res.columns) {
    bool stuck = false;
    for (const BifurcationPoint& p : c.points) {
      csv += c.value.digits + ',' + std::to_string(p.n) + ',' + p.theta.digits + ',' + p.v.digits + ',' + (p.sticking ? "1" : "0") + '\n';
      stuck = stuck || p.sticking;
      sticking_events += p.sticking;
    }
    rows += static_cast<long>(c.points.size());
    sticking_samples += stuck;
    if (c.undecided_step) {
      csv += "# undecided: " + vary + "=" + c.value.digits + " step " + std::to_string(*c.undecided_step) + ": " + c.undecided_reason + "\n";
      ++undecided;
    }
    if (c.certified) {
      const CertifiedCell& k = *c.certified;
      csv += "# certified: " + *c.exact_value + ',' + encode(k) + '\n';
      agrees += k.agreement == Agreement::agrees;
      differs += k.agreement == Agreement::differs;
      open += k.agreement == Agreement::undecided;
      columns.push_back({{vary, *c.exact_value}, {"class", name(k.cls)}, {"period", k.period}, {"certified_steps", k.certified_steps},
                         {"scalar", k.scalar}, {"double_class", name(k.double_class)}, {"double_period", k.double_period},
                         {"agreement", name(k.agreement)}});
    }
  }
  ImageFigure fig = bifurcation_figure(res, b.show_theta, b.bins, f.picture.palette);
  fig.metadata = png_metadata(prov, fig.title);
  nlohmann::ordered_json s;
  s["command"] = "bifurcation";
  s["vary"] = vary;
  s["range"] = {r.lo.text(), r.hi.text()};
  s["samples"] = r.samples;
  s["transient"] = r.transient;
  s["record"] = r.record;
  s["rows"] = rows;
  s["samples_with_sticking"] = sticking_samples;
  s["sticking_events"] = sticking_events;
  s["undecided_samples"] = undecided;
  s["precision"] = r.precision.text();
  if (r.certify) {
    s["certified"] = true;
    s["max_steps"] = r.cert.max_steps;
    s["schedule"] = "interval:double, then MPFI at 64, 128, ... up to " + std::to_string(r.cert.max_bits) + " bits";
    s["double_vs_certified"] = {{"agrees", agrees}, {"differs", differs}, {"undecided", open}};
    s["columns"] = columns;
  }
  write_outputs(f, prov, csv, [&](std::ostream& out, ImageFormat fmt) { write_figure(out, fig, fmt, f.picture.render); }, s);
}

}  // namespace

const std::set<std::string>& bifurcation_keys() {
  static const std::set<std::string> keys = [] {
    std::set<std::string> k = model_keys();
    k.insert({"vary", "range", "samples", "transient", "record", "theta", "v", "carry", "precision", "show", "bins",
              "certify", "max-bits"});
    k.insert(run_keys().begin(), run_keys().end());
    k.insert(picture_keys().begin(), picture_keys().end());
    return k;
  }();
  return keys;
}

int run_bifurcation(const Options& o, const RunFlags& f) {
  const BifurcationOptions b = bifurcation_options(o);
  BifurcationGrid grid(b.request);  // validates the request
  const Provenance prov = provenance_for("bifurcation", job_options(o), b.request.precision, f.invocation);
  if (const auto columns = run_cells<BifurcationColumn>("bifurcation", o, f, grid, grid.item_bytes(), "samples"))
    write_bifurcation({grid.request(), *columns}, b, f, prov);
  return 0;
}

CommandRunner setup_bifurcation(CLI::App* sub) {
  auto opts = std::make_shared<OptionSet>(sub);
  auto scene = std::make_shared<std::string>();
  sub->add_option("--scene", *scene, "TOML scene file with the same options (command line overrides)");
  add_model_options(*opts);
  opts->add("vary", "Parameter to sweep: a (default) | eps (constant model) | c (veldep model)");
  opts->add("range", "Sweep range LO:HI (decimals, LO < HI), LO and HI included");
  opts->add("samples", "Number of parameter values K, 1..100000 (default 200)");
  opts->add("transient", "Steps discarded at each value, N (default 5000, as in the paper)");
  opts->add("record", "Steps recorded at each value, M >= 1 (default 500, as in the paper)");
  opts->add_list("theta", "Initial phase in [0, 1)");
  opts->add_list("v", "Initial velocity after impact, >= the wall velocity at theta");
  opts->add("precision", kPointPrecisionHelp);
  opts->add("show", "Picture: theta (default) or v against the parameter");
  opts->add("bins", "Rows of the density image, 10..4000 (default 400)");
  opts->add("max-bits", "With --certify: the last MPFI precision of the schedule interval:double, 64, 128, ..., 64..4096 (default 256)");
  opts->add_flag("carry", "Start each value from the last state of the previous one (one worker)");
  opts->add_flag("certify",
                "Certify each column (constant, elastic, or veldep without collapse): the exact orbit at the exact double value of the parameter; shade the "
                "columns where double's class is refuted or nothing is certified");
  auto flags = add_run_options(sub, *opts);
  auto run = [opts, scene, flags](const std::string& argv_text) {
    const Options o = merge(scene->empty() ? Options{} : load_scene(*scene, "bifurcation", bifurcation_keys()), opts->collected());
    return run_bifurcation(o, run_flags_from(o, *flags, argv_text));
  };
  return run;
}

}  // namespace bouncer::cli
