// bouncer continue: follow a period-q orbit (Newton) in a, eps or c in both directions from
// the guess's parameter value, locate where the branch ends (border collision, grazing,
// touchdown, sticking threshold, fold) and the smooth bifurcations on the way (period
// doubling, Neimark-Sacker), and classify what the map does just beyond each end.
// Outputs: PREFIX.csv (one row per branch point), PREFIX.json (branch summary), PREFIX.png
// (branch diagram); without --out a text summary, or the JSON summary with --json.
#include <cmath>
#include <memory>
#include <sstream>
#include <tuple>

#include "analysis_common.hpp"
#include "bouncer/io/requests/continue.hpp"
#include "bouncer/verify/branch_end.hpp"
#include "commands.hpp"
#include "picture_common.hpp"

namespace bouncer::cli {

namespace {

using json = nlohmann::ordered_json;

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

std::string num(double x) {
  if (std::isnan(x)) return "nan";
  if (std::isinf(x)) return x > 0 ? "inf" : "-inf";
  return ScalarTraits<double>::to_string(x);
}

// What the map does beyond an end, in words.
std::string class_words(const Classification& c) {
  std::ostringstream s;
  switch (c.cls) {
    case OrbitClass::fixed: s << "a fixed point"; break;
    case OrbitClass::periodic: s << "a periodic orbit of period " << c.period; break;
    case OrbitClass::sticking: s << "a sticking solution (sticking period " << c.period << ")"; break;
    case OrbitClass::quasiperiodic: s << "a quasiperiodic orbit"; break;
    case OrbitClass::chaotic: s << "a chaotic attractor (lambda " << std::setprecision(3) << c.lambda << ")"; break;
    case OrbitClass::transient_chaos:
      s << "transient chaos that settles on " << name(c.settled_class) << (c.period ? " of period " + std::to_string(c.period) : "")
        << (c.settled_at ? " by step " + std::to_string(c.settled_at) : "");
      break;
    case OrbitClass::unbounded: s << "unbounded growth (Fermi acceleration)"; break;
    case OrbitClass::effective_sticking: s << "effective sticking (chatter to the wall's velocity)"; break;
    case OrbitClass::undecided: s << "an undecided orbit (" << c.evidence << ")"; break;
    case OrbitClass::outside: s << "a start outside the phase space"; break;
  }
  return s.str();
}

std::string cause_words(EndReason r, int margin) {
  switch (r) {
    case EndReason::border:
      switch (static_cast<Margin>(margin)) {
        case Margin::knot: return "a border collision";
        case Margin::clearance: return "a grazing";
        case Margin::speed: return "a touchdown";
        case Margin::sticking: return "the sticking threshold";
      }
      return "a border collision";
    case EndReason::fold: return "a fold";
    case EndReason::event_change: return "a change of the event sequence";
    case EndReason::period_collapse: return "a period collapse";
    case EndReason::lost: return "loss of the corrector";
    default: return "";
  }
}

template <class T>
std::string sentence(const Branch<T>& b, const BranchEnd<T>& e, const std::string& par) {
  using Tr = ScalarTraits<T>;
  const std::string q = "period " + std::to_string(b.period);
  if (e.reason == EndReason::range_end) return q + " reaches the range end " + par + " = " + Tr::to_string(e.param);
  if (e.reason == EndReason::max_points) return q + " stops at " + par + " = " + Tr::to_string(e.param) + " (--max-points)";
  std::string s = q + " ends at " + par + "* = " + Tr::to_string(e.param) + " by " + cause_words(e.reason, e.margin) + " (" +
                  e.detail + ")";
  if (e.beyond_done) {
    s += "; beyond it the orbit goes to " + class_words(e.beyond);
    if (!e.beyond_orbit.empty())
      s += "; Newton finds a period-" + std::to_string(b.period) + " orbit there with events " + e.beyond_orbit +
           (e.beyond_orbit_period != b.period ? " (minimal period " + std::to_string(e.beyond_orbit_period) + ")" : "") +
           (e.beyond_relation == BeyondRelation::continuation   ? ", the branch's continuation"
            : e.beyond_relation == BeyondRelation::other_branch ? ", another orbit, which already exists before a* (not a continuation)"
            : e.beyond_relation == BeyondRelation::unrelated    ? ", not the branch's continuation (away from it; not found before a*)"
                                                                : "");
  } else if (!e.beyond_note.empty()) {
    s += "; " + e.beyond_note;
  }
  return s;
}

template <class T>
json end_json(const Branch<T>& b, const BranchEnd<T>& e, const std::string& par, const Wall<T>& wall) {
  using Tr = ScalarTraits<T>;
  json j;
  j["reason"] = name(e.reason);
  j["param"] = Tr::to_string(e.param);
  j["bracket"] = {Tr::to_string(e.bracket_lo), Tr::to_string(e.bracket_hi)};
  j["margin"] = e.margin >= 0 ? json(name(static_cast<Margin>(e.margin))) : json(nullptr);
  j["impact"] = e.impact >= 0 ? json(e.impact + 1) : json(nullptr);
  j["knot"] = e.knot >= 0 ? json(wall.knot_exact[e.knot].get_str()) : json(nullptr);
  j["detail"] = e.detail;
  if (e.beyond_done) {
    json by;
    by["param"] = Tr::to_string(e.beyond_param);
    by["class"] = name(e.beyond.cls);
    by["period"] = e.beyond.period;
    by["lambda"] = json_number(e.beyond.lambda);
    by["evidence"] = e.beyond.evidence;
    by["newton_orbit_events"] = e.beyond_orbit;
    by["newton_orbit_minimal_period"] = e.beyond_orbit_period;
    by["newton_orbit_relation"] = name(e.beyond_relation);
    j["beyond"] = by;
  } else {
    j["beyond"] = nullptr;
    if (!e.beyond_note.empty()) j["beyond_note"] = e.beyond_note;
  }
  j["sentence"] = sentence(b, e, par);
  return j;
}

template <class T>
int run_typed(const Request& req, const Provenance& prov, bool print_json, OutputSet& outputs) {
  using Tr = ScalarTraits<T>;
  const ContinueRequest& r = req.science;
  const long bits = r.precision.bits;
  const Model<T> m = make_model<T>(r.model, bits);
  const T lo = Tr::from_decimal(r.lo.text(), bits), hi = Tr::from_decimal(r.hi.text(), bits);
  const Branch<T> b = continue_branch(m, r.vary, r.period, make_state<T>(r.guess, bits), lo, hi, r.opt);
  const std::string par = name(r.vary);
  if (!b.started) throw InputError("guess", b.note);

  // CSV: one row per branch point.
  std::ostringstream csv;
  csv << par << ",stability,mu1_re,mu1_im,mu1_abs,mu2_re,mu2_im,mu2_abs,events";
  for (int k = 0; k < kMargins; ++k) csv << ',' << name(static_cast<Margin>(k)) << ',' << name(static_cast<Margin>(k)) << "_impact";
  csv << ",residual";
  for (long i = 0; i < r.period; ++i) csv << ",theta_" << i << ",v_" << i;
  csv << "\n";
  for (const BranchPoint<T>& p : b.points) {
    const auto& mu = p.orbit.multipliers;
    csv << Tr::to_string(p.param) << ',' << p.stability;
    for (int i = 0; i < 2; ++i) csv << ',' << Tr::to_string(mu.re[i]) << ',' << Tr::to_string(mu.im[i]) << ',' << num(mu.modulus(i));
    csv << ',' << event_text(p.events);
    for (int k = 0; k < kMargins; ++k) {
      csv << ',' << num(p.min_margin[k]) << ',';
      if (p.min_impact[k] >= 0) csv << p.min_impact[k] + 1;
    }
    csv << ',' << num(p.orbit.residual);
    for (const State<T>& s : p.orbit.points) csv << ',' << Tr::to_string(s.theta) << ',' << Tr::to_string(s.v);
    csv << "\n";
  }

  // JSON summary.
  const BranchPoint<T>& s0 = b.points[b.start];
  json sum;
  sum["command"] = "continue";
  sum["model"] = name(r.model.law);
  sum["vary"] = par;
  sum["period"] = r.period;
  sum["range"] = {r.lo.text(), r.hi.text()};
  sum["precision"] = r.precision.text();
  json start;
  start["param"] = Tr::to_string(s0.param);
  json pts = json::array();
  for (const State<T>& s : s0.orbit.points) pts.push_back({Tr::to_string(s.theta), Tr::to_string(s.v)});
  start["points"] = pts;
  start["events"] = event_text(s0.events);
  start["stability"] = s0.stability;
  start["multiplier_moduli"] = {json_number(s0.orbit.multipliers.modulus(0)), json_number(s0.orbit.multipliers.modulus(1))};
  sum["start"] = start;
  sum["points"] = b.points.size();
  sum["param_min"] = Tr::to_string(b.points.front().param);
  sum["param_max"] = Tr::to_string(b.points.back().param);
  sum["corrector_runs"] = b.corrector_runs;
  json low = end_json(b, b.low, par, m.wall), high = end_json(b, b.high, par, m.wall);
  if (r.certify) {
    // Krawczyk over an interval of width 1e-6 max(1, |a*|) on the branch side of each border
    // end (verify/branch_end.hpp): a certified run of it proves the branch reaches at least
    // its inner end.
    for (const auto& [ej, e, high] : {std::tuple<json*, const BranchEnd<T>*, bool>{&low, &b.low, false},
                                      std::tuple<json*, const BranchEnd<T>*, bool>{&high, &b.high, true}}) {
      if (e->reason != EndReason::border) continue;
      BranchEndQuestion c;
      c.model = r.model;
      c.vary = r.vary;
      c.period = r.period;
      c.last_point = {parse_decimal("certify", Tr::to_string(e->last_point.theta)),
                      parse_decimal("certify", Tr::to_string(e->last_point.v))};
      const auto [lo_text, hi_text] = branch_end_interval(e->bracket_lo, e->bracket_hi, high, bits);
      c.lo = parse_decimal("certify", lo_text);
      c.hi = parse_decimal("certify", hi_text);
      c.high_end = high;
      const BranchEndCertificate ce = certify_branch_end(c);
      json cj;
      cj["range"] = {lo_text, hi_text};
      cj["certified_range"] = ce.certified ? json{exact_decimal(ce.from), exact_decimal(ce.to)} : json(nullptr);
      cj["certified_to"] = ce.certified ? json(exact_decimal(ce.bound)) : json(nullptr);
      if (ce.certified) cj["events"] = ce.events;
      cj["theorem"] = ce.theorem;
      cj["pieces"] = ce.pieces;
      cj["statement"] = ce.certified ? "certified (Krawczyk): the period-" + std::to_string(r.period) + " orbit exists for every " +
                                           par + " in [" + exact_decimal(ce.from) + ", " + exact_decimal(ce.to) + "], so " + par +
                                           "* " + (high ? ">= " : "<= ") + exact_decimal(ce.bound) +
                                           "; the other side of the bracket is numerical only"
                                     : "nothing certified next to " + par + "*";
      (*ej)["certified"] = cj;
    }
  }
  low["events_at_end"] = event_text(b.points.front().events);
  high["events_at_end"] = event_text(b.points.back().events);
  sum["low"] = low;
  sum["high"] = high;
  json bif = json::array();
  for (const Bifurcation<T>& x : b.bifurcations)
    bif.push_back({{"kind", name(x.kind)}, {"param", Tr::to_string(x.param)},
                   {"bracket", {Tr::to_string(x.bracket_lo), Tr::to_string(x.bracket_hi)}}});
  sum["bifurcations"] = bif;

  json doc;
  doc["provenance"] = json::parse(prov.as_json());
  doc["summary"] = sum;

  // Text summary.
  std::ostringstream text;
  text << prov.as_comment_lines();
  text << "period " << r.period << " branch (" << name(r.model.law) << " model) in " << par << ", started at " << par
       << " = " << Tr::to_string(s0.param) << " (" << s0.stability << ", events " << event_text(s0.events) << "): "
       << b.points.size() << " points, " << par << " in [" << Tr::to_string(b.points.front().param) << ", "
       << Tr::to_string(b.points.back().param) << "]\n";
  text << "low end:  " << low["sentence"].get<std::string>() << "\n";
  text << "high end: " << high["sentence"].get<std::string>() << "\n";
  for (const json* e : {&low, &high})
    if (e->contains("certified")) text << (e == &low ? "low end " : "high end ") << (*e)["certified"]["statement"].get<std::string>() << "\n";
  for (const Bifurcation<T>& x : b.bifurcations)
    text << name(x.kind) << " at " << par << "* = " << Tr::to_string(x.param) << "\n";

  if (req.out) {
    // Branch diagram: the shown coordinate of every orbit point against the parameter.
    Figure fig;
    const bool show_theta = req.show == "theta";
    Series st{"stable", {}, {}, Rgb{33, 102, 172}, false, true, 2};
    Series un{"unstable", {}, {}, Rgb{230, 97, 1}, false, true, 2};
    Series mg{"marginal", {}, {}, Rgb{150, 150, 150}, false, true, 1};
    double y0 = show_theta ? 0 : INFINITY, y1 = show_theta ? 1 : -INFINITY;
    // A range a double cannot resolve (a zoom) is drawn relative to an offset, from the
    // exact values; so is v then, whose spread over such a range is as small.
    const AxisZoom zx(r.lo.value(), r.hi.value());
    AxisZoom zy;
    if (zx.active() && !show_theta) {
      const T* lo_v = nullptr;
      const T* hi_v = nullptr;
      for (const BranchPoint<T>& p : b.points)
        for (const State<T>& x : p.orbit.points) {
          if (!lo_v || x.v < *lo_v) lo_v = &x.v;
          if (!hi_v || *hi_v < x.v) hi_v = &x.v;
        }
      const mpq_class v_lo = exact_value(*lo_v), v_hi = exact_value(*hi_v);
      // 6% beyond the data, at least 1e-6 of the range's width (1e-6 for ordinary ranges).
      const mpq_class pad = std::max(mpq_class((v_hi - v_lo) * 6 / 100), mpq_class((r.hi.value() - r.lo.value()) / 1000000));
      zy = AxisZoom(v_lo - pad, v_hi + pad);
      y0 = zy(mpq_class(v_lo - pad));
      y1 = zy(mpq_class(v_hi + pad));
    }
    auto X = [&](const T& p) { return zx.active() ? zx(exact_value(p)) : Tr::to_double(p); };
    auto Y = [&](const T& y) { return zy.active() ? zy(exact_value(y)) : Tr::to_double(y); };
    for (const BranchPoint<T>& p : b.points) {
      Series& s = p.stability == "stable" ? st : p.stability == "unstable" ? un : mg;
      const double x = X(p.param);
      for (const State<T>& pt : p.orbit.points) {
        const double y = Y(show_theta ? pt.theta : pt.v);
        s.x.push_back(x);
        s.y.push_back(y);
        if (!show_theta && !zx.active()) { y0 = std::min(y0, y); y1 = std::max(y1, y); }
      }
    }
    if (!show_theta && !zx.active()) {
      const double pad = std::max(1e-6, (y1 - y0) * 0.06);
      y0 -= pad;
      y1 += pad;
    }
    for (Series* s : {&st, &un, &mg})
      if (!s->x.empty()) fig.series.push_back(*s);
    auto vline = [&](const T& at, const std::string& label, Rgb colour) {
      const double x = X(at);
      fig.series.push_back(Series{label, {x, x}, {y0, y1}, colour, true, false, 0});
    };
    auto short_num = [&](const T& x) {
      // In a zoom: the digits that resolve 1e-4 of the range.
      if (zx.active()) return decimal_rounded(exact_value(x), zx.offset().exponent - 4);
      std::ostringstream s;
      s << std::setprecision(8) << Tr::to_double(x);
      return s.str();
    };
    // Legend labels short enough for one line: the cause and the impact.
    auto end_label = [&](const BranchEnd<T>& e) {
      const std::string i = std::to_string(e.impact + 1);
      const std::string knot = e.knot >= 0 ? m.wall.knot_exact[e.knot].get_str() : "";
      std::string what = cause_words(e.reason, e.margin);
      if (e.reason == EndReason::border) {
        switch (static_cast<Margin>(e.margin)) {
          case Margin::knot: what = "border collision, impact " + i + " at θ = " + knot; break;
          case Margin::clearance: what = "grazing, flight " + i + " at θ = " + knot; break;
          case Margin::speed: what = "touchdown, impact " + i; break;
          case Margin::sticking: what = "sticking threshold, impact " + i; break;
        }
      }
      return par + "* = " + short_num(e.param) + ": " + what;
    };
    for (const BranchEnd<T>* e : {&b.low, &b.high})
      if (e->reason != EndReason::range_end && e->reason != EndReason::max_points)
        vline(e->param, end_label(*e), e->reason == EndReason::fold ? Rgb{118, 42, 131} : Rgb{215, 25, 28});
    for (const Bifurcation<T>& x : b.bifurcations)
      vline(x.param, par + "* = " + short_num(x.param) + ": " +
                         (x.kind == SmoothKind::fold ? "fold (+1)" : x.kind == SmoothKind::period_doubling ? "period doubling (-1)" : "Neimark-Sacker"),
            Rgb{27, 120, 55});
    fig.x_min = zx(r.lo.value());
    fig.x_max = zx(r.hi.value());
    fig.y_min = y0;
    fig.y_max = y1;
    fig.x_offset = zx.offset();
    fig.y_offset = zy.offset();
    fig.legend_below = true;
    fig.title = "Period-" + std::to_string(r.period) + " branch, " + model_title(r.model.law) + " model";
    std::string fixed;
    if (r.vary != Parameter::a) fixed += "a = " + r.model.a.text() + ", ";
    if (r.model.law == Law::constant && r.vary != Parameter::eps) fixed += "ε = " + r.model.eps.text() + ", ";
    if (r.model.law == Law::veldep && r.vary != Parameter::c) fixed += "c = " + r.model.c.text() + ", ";
    fig.subtitle = fixed + "started at " + par + " = " + short_num(s0.param) + "; " + std::to_string(b.points.size()) +
                   " points, " + r.precision.text();
    fig.xlabel = r.vary == Parameter::eps ? "ε" : par;
    fig.ylabel = show_theta ? "θ (phase of impact)" : "v (velocity after impact)";
    fig.metadata = png_metadata(prov, fig.title);
    std::vector<OutputFile> files{{*req.out + ".csv", [&](std::ostream& f) { f << prov.as_comment_lines() << csv.str(); }}};
    for (OutputFile& pic : picture_files(*req.out, req.picture, [&](std::ostream& out, ImageFormat fmt) {
           write_figure(out, fig, fmt, req.picture.render);
         }))
      files.push_back(std::move(pic));
    files.push_back({*req.out + ".json", [&](std::ostream& f) { f << doc.dump(2) << "\n"; }});
    write_output_set(files, &outputs);
  }
  if (print_json) command_out() << doc.dump(2) << "\n";
  else command_out() << text.str();
  return 0;
}

}  // namespace

CommandRunner setup_continue(CLI::App* sub) {
  auto opts = std::make_shared<OptionSet>(sub);
  auto scene = std::make_shared<std::string>();
  auto json_flag = std::make_shared<bool>(false);
  sub->add_option("--scene", *scene, "TOML scene file with the same options (command line overrides)");
  add_model_options(*opts);
  opts->add("period", "Period q, integer in [1, 100] (required)");
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
                 "Krawczyk on the branch side of each border end: a certified one-sided bound on a*");
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
