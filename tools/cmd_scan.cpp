// bouncer scan: parameter-space scans (paper figs. paramspace1 and paramspace2; run/scan.hpp).
// Over a P x Q grid of (a, eps) (constant model) or (a, c) (velocity-dependent model), K x K
// initial conditions per parameter point (paper: 10 x 10, in the trapping region) are
// classified, and the solution types are counted. The picture shows the fraction of one
// type (--show; default "regular" = fixed + periodic, the paper's "periodic solutions").
// --certify: each parameter point gets the certificate of one exact start.
// This file reads the options, runs the library's ScanGrid through the tiles, and writes.
#include "bouncer/run/scan.hpp"
#include "bouncer/io/requests/grids.hpp"
#include "commands.hpp"
#include "picture_common.hpp"

namespace bouncer::cli {

namespace {

// --confirm: the JSON summary's "confirm" (the artefacts' starts from the grid).
nlohmann::ordered_json confirm_summary(const ScanResult& res, const ScanGrid& grid) {
  const ScanRequest& r = res.request;
  const long stride = grid.confirm_stride();
  const long points = confirm_sample_units(r.p, r.q, stride);
  long n[3] = {0, 0, 0};
  const std::string y = name(res.y);
  nlohmann::ordered_json artefacts = nlohmann::ordered_json::array();
  for (size_t i = 0; i < res.cells.size(); ++i) {
    const ScanCell& c = res.cells[i];
    for (size_t k = 0; k < 3; ++k) n[k] += c.verdicts[k];
    for (long s : c.artefacts) {
      const std::pair<Number, Number> x = grid.start(static_cast<long>(i), s);
      artefacts.push_back({{"a", res.a[i % static_cast<size_t>(r.p)].digits},
                           {y, res.y_values[i / static_cast<size_t>(r.p)].digits},
                           {"theta", x.first.digits},
                           {"v", x.second.digits}});
    }
  }
  return confirm_json(r.precision, r.confirm, r.classify,
                      {{"stride", stride},
                       {"rule", "every start of the parameter point at offset (min(s, n) - 1) / 2 of every s x s block of the "
                                "grid, s = stride"},
                       {"points", points},
                       {"starts", points * r.k * r.k}},
                      n, std::move(artefacts));
}

void write_scan(const ScanResult& res, const ScanGrid& grid, const ScanOptions& so, const RunFlags& f, const Provenance& prov) {
  const ScanRequest& r = res.request;
  const bool confirm = r.confirm.on;
  std::string csv = std::string("a,") + name(res.y);
  for (OrbitClass c : scan_classes()) csv += std::string(",") + name(c);
  csv += confirm ? ",total,confirm_agrees,confirm_artefact,confirm_precision_dependent\n" : ",total\n";
  std::array<long, kOrbitClassCount> totals{};
  for (size_t i = 0; i < res.cells.size(); ++i) {
    const ScanCell& c = res.cells[i];
    csv += res.a[i % static_cast<size_t>(r.p)].digits + ',' + res.y_values[i / static_cast<size_t>(r.p)].digits;
    for (OrbitClass k : scan_classes()) csv += ',' + std::to_string(c[k]);
    csv += ',' + std::to_string(c.total());
    if (confirm)
      csv += c.confirmed ? ',' + std::to_string(c.verdicts[0]) + ',' + std::to_string(c.verdicts[1]) + ',' +
                               std::to_string(c.verdicts[2])
                         : std::string(",,,");
    csv += '\n';
    for (int k = 0; k < kOrbitClassCount; ++k) totals[static_cast<size_t>(k)] += c.count[static_cast<size_t>(k)];
  }
  ImageFigure fig = scan_figure(res, so.show, so.fixed_point_curves, f.picture.palette);
  fig.metadata = png_metadata(prov, fig.title);
  nlohmann::ordered_json s;
  s["command"] = "scan";
  s["grid"] = {r.p, r.q};
  s["initial_conditions"] = r.k * r.k;
  s["show"] = so.show ? name(*so.show) : "regular";
  nlohmann::ordered_json t;
  for (OrbitClass c : scan_classes()) t[name(c)] = totals[static_cast<size_t>(c)];
  s["totals"] = t;
  s["precision"] = r.precision.text();
  s["recheck"] = r.classify.recheck_factor > 0 ? name(r.classify.recheck) : "off";
  std::vector<ExtraFigure> extra;
  if (confirm) {
    s["confirm"] = confirm_summary(res, grid);
    extra.push_back(extra_figure("artefacts", scan_confirm_figure(res, f.picture.palette), prov, f));
  }
  write_outputs(f, prov, csv, [&](std::ostream& out, ImageFormat fmt) { write_figure(out, fig, fmt, f.picture.render); }, s,
                extra);
}

void write_certified_scan(const CertifiedScanResult& res, const RunFlags& f, const Provenance& prov) {
  const ScanRequest& r = res.request;
  nlohmann::ordered_json s;
  s["command"] = "scan";
  s["certified"] = true;
  s["grid"] = {r.p, r.q};
  s["a_range"] = {r.a_lo.text(), r.a_hi.text()};
  s[std::string(name(res.y)) + "_range"] = {r.y_lo.text(), r.y_hi.text()};
  if (r.start_at_release) s["start"] = "release";
  else s["start"] = {r.start.theta.text(), r.start.v.text()};
  write_certified_map(certified_map(res), res.a, res.y_values, res.cells, s, r.precision.text(), f, prov);
}

}  // namespace

const std::set<std::string>& scan_keys() {
  static const std::set<std::string> keys = [] {
    std::set<std::string> k = model_keys();
    k.insert({"a-range", "eps-range", "c-range", "grid", "ics", "theta-range", "v-range", "transient", "steps",
              "max-period", "recheck-factor", "recheck", "precision", "show", "curves", "certify", "max-bits", "theta", "v", "confirm", "confirm-sample"});
    k.insert(run_keys().begin(), run_keys().end());
    k.insert(picture_keys().begin(), picture_keys().end());
    return k;
  }();
  return keys;
}

int run_scan(const Options& o, const RunFlags& f) {
  const ScanOptions so = scan_options(o);
  ScanGrid grid(so.request, so.certify);  // validates the request
  const Provenance prov = provenance_for("scan", job_options(o), so.request.precision, f.invocation);
  if (so.certify) {
    if (const auto cells = run_cells<CertifiedCell>("scan", o, f, grid)) write_certified_scan(grid.certified_result(*cells), f, prov);
  } else if (const auto cells = run_cells<ScanCell>("scan", o, f, grid)) {
    write_scan(grid.result(*cells), grid, so, f, prov);
  }
  return 0;
}

CommandRunner setup_scan(CLI::App* sub) {
  auto opts = std::make_shared<OptionSet>(sub);
  auto scene = std::make_shared<std::string>();
  sub->add_option("--scene", *scene, "TOML scene file with the same options (command line overrides)");
  add_model_options(*opts);
  opts->add("a-range", "A0:A1, the range of a (cell centres of --grid)");
  opts->add("eps-range", "E0:E1 within [0, 1], for --model constant");
  opts->add("c-range", "C0:C1, c > 0, for --model veldep");
  opts->add("grid", "PxQ parameter points (a by eps or c), 1..4096 each (default 20x20)");
  opts->add("ics", "K: K x K initial conditions per parameter point (default 10, as in the paper)");
  opts->add("theta-range", "Initial phases T0:T1 within [0, 1] (default 0:1)");
  opts->add("v-range", "Initial velocities V0:V1 (default: the trapping region of each point, from the wall velocity 4 to its top; README, Claims row 5)");
  add_classify_options(*opts);
  opts->add("recheck", "How the starts of one point re-check their aperiodic labels: recurrence (default: once two whole re-checks "
                       "stayed aperiodic on the same cells, a start whose orbit stays 1000 steps in them is classified there; "
                       "audits and any whole re-check that settles send it back to a whole re-check) | full (every start runs "
                       "the whole re-check, as classify)");
  opts->add("precision", kPointPrecisionHelp);
  opts->add("show", "Picture: fraction of regular (default: fixed + periodic) | fixed | periodic | sticking | chaotic | ...");
  opts->add("curves", "Over the picture: fixed-points (default for --model constant: the paper's eq. 5, "
                      "a = 8(1+eps)/(p(1-eps)), p = 1..10) | none");
  add_grid_confirm_options(*opts, "parameter point (with all its starts)");
  opts->add("theta", "With --certify: the start's phase, an exact decimal (default 0.5, the release state)");
  opts->add("v", "With --certify: the start's velocity (default 4, the release state)");
  opts->add("max-bits", "With --certify: the last MPFI precision of the schedule interval:double, 64, 128, ..., 64..4096 (default 256)");
  opts->add_flag("certify",
                "Certify each parameter point (constant, or veldep without collapse): the exact orbit of --theta, --v at the exact double (a, eps) or (a, c), "
                "with double's answer beside it; also writes PREFIX-artefacts.png, the map of where double is wrong");
  auto flags = add_run_options(sub, *opts);
  auto run = [opts, scene, flags](const std::string& argv_text) {
    Options o = merge(scene->empty() ? Options{} : load_scene(*scene, "scan", scan_keys()), opts->collected());
    // A bare --confirm is recorded as a flag ("true"), so that provenance and audit rerun it.
    if (o.has("confirm") && o.get("confirm").empty()) o.set("confirm", "true");
    return run_scan(o, run_flags_from(o, *flags, argv_text));
  };
  return run;
}

}  // namespace bouncer::cli
