// bouncer sweep: one orbit question in every precision (double, long double, quad, MPFR at
// 64 ... 4096 bits) against a certified interval reference: where each leaves the
// enclosure, what it answers, and the Lyapunov exponent the divergence steps imply.
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iomanip>
#include <memory>
#include <set>
#include <sstream>

#include "bouncer/io/plot.hpp"
#include "bouncer/verify/sweep.hpp"
#include "cli_common.hpp"
#include "commands.hpp"

namespace bouncer::cli {

namespace {

using json = nlohmann::ordered_json;

const std::set<std::string>& sweep_keys() {
  static const std::set<std::string> keys = [] {
    std::set<std::string> k = model_keys();
    k.insert({"theta", "v", "steps", "tolerance", "reference-max-bits", "method", "classify-steps", "json", "out"});
    k.insert(picture_keys().begin(), picture_keys().end());
    return k;
  }();
  return keys;
}

struct Request {
  SweepQuestion q;
  bool json = false;
  std::optional<std::string> prefix;
  Presentation picture;  // --format, --size, --dpi, --palette
};

Request request_from(const Options& o) {
  Request r;
  r.q.model = model_from(o);
  const std::vector<InitialCondition> ic = initial_conditions_from(o, r.q.model);
  if (ic.size() != 1) throw InputError("theta", "takes one initial condition");
  r.q.start = ic[0];
  r.q.steps = integer_from(o, "steps", 1, 1000000, 1000);
  if (o.has("tolerance")) {
    const Decimal t = parse_decimal("tolerance", o.get("tolerance"));
    if (!(Decimal::from_int(0) <= t) || t > Decimal::from_int(1))
      throw InputError("tolerance", "must be a decimal in [0, 1] (got " + o.get("tolerance") + ")");
    r.q.tolerance = t.approx();
  }
  r.q.reference.max_bits = integer_from(o, "reference-max-bits", 64, kMaxBits, 16384);
  r.q.method = parse_enclosure_method("method", o.get_or("method", "lohner"));
  r.q.classify_steps = integer_from(o, "classify-steps", 8, 1000000, 500);
  r.json = o.get_or("json", "false") == "true";
  if (o.has("out")) {
    r.prefix = o.get("out");
    check_prefix("out", *r.prefix, ".json");
  }
  r.picture = presentation_from(o);
  if (r.prefix) check_figure_font();  // an output failure, found before the work
  return r;
}

// A CSV field in double quotes, inner quotes doubled (RFC 4180): answers carry commas and
// classify's evidence.
std::string csv_quoted(const std::string& text) {
  std::string q = "\"";
  for (char ch : text) {
    if (ch == '"') q += '"';
    q += ch;
  }
  q += '"';
  return q;
}

json null_or(const std::optional<long long>& x) { return x ? json(*x) : json(nullptr); }

json report_json(const Request& r, const SweepReport& rep, const Provenance& p) {
  json j;
  j["provenance"] = json::parse(p.as_json());
  j["note"] = "Decimal inputs are enclosed exactly in the certified reference (MPFI, outward rounding); each plain "
              "precision rounds them to its own format, which is part of what the sweep measures.";
  j["inputs"] = {{"model", name(r.q.model.law)}, {"a", r.q.model.a.text()}, {"eps", r.q.model.eps.text()},
                 {"c", r.q.model.c.text()}, {"wall", r.q.model.wall.text}, {"theta", r.q.start.theta.text()},
                 {"v", r.q.start.v.text()}, {"steps", r.q.steps}};
  j["tolerance"] = r.q.tolerance;
  j["leaves_definition"] =
      "first step whose state is farther than `tolerance` from the certified enclosure (theta on the circle), or "
      "whose event differs from the certified event, or that fails";
  json ref;
  ref["method"] = name(r.q.method);
  ref["bits"] = rep.reference_bits;
  ref["steps"] = rep.reference_steps;
  ref["status"] = rep.reference_status;
  ref["answer"] = rep.reference_answer;
  json att = json::array();
  for (const Attempt& a : rep.reference_attempts)
    att.push_back({{"bits", a.bits}, {"decided", a.decided}, {"steps", a.steps}, {"reason", a.reason}, {"seconds", a.seconds}});
  ref["attempts"] = att;
  j["reference"] = ref;
  json rows = json::array();
  for (const SweepRow& row : rep.rows) {
    const std::optional<Classification>& c = row.classification;
    rows.push_back({{"precision", row.precision}, {"bits", row.bits}, {"leaves_enclosure_at", null_or(row.leaves_at)},
                    {"answer", row.answer}, {"why", row.why}, {"sticking_period", null_or(row.sticking_period)},
                    {"class", c ? json(name(c->cls)) : json(nullptr)},
                    {"class_evidence", c ? json(c->evidence) : json(nullptr)},
                    {"lambda", c && std::isfinite(c->lambda) ? json(c->lambda) : json(nullptr)}});
  }
  j["rows"] = rows;
  j["slope_steps_per_bit"] = rep.slope ? json(*rep.slope) : json(nullptr);
  j["implied_lyapunov"] = rep.implied_lyapunov ? json(*rep.implied_lyapunov) : json(nullptr);
  j["implied_lyapunov_note"] = "lambda = ln 2 / slope per step, slope = least-squares steps per bit of the rows that left";
  j["seconds"] = rep.seconds;
  return j;
}

std::string text_table(const SweepReport& rep, long long steps) {
  std::ostringstream o;
  o << "reference: " << rep.reference_answer << " (" << rep.reference_bits << " bits; " << rep.reference_status << ")\n";
  o << std::left << std::setw(12) << "precision" << std::setw(7) << "bits" << std::setw(12) << "leaves_at"
    << "answer\n";
  for (const SweepRow& r : rep.rows) {
    o << std::left << std::setw(12) << r.precision << std::setw(7) << r.bits << std::setw(12)
      << (r.leaves_at ? std::to_string(*r.leaves_at) : std::string("-")) << r.answer << "\n";
  }
  o << "('-': stays within the enclosure for all " << std::min<long long>(steps, rep.reference_steps)
    << " certified steps)\n";
  if (rep.implied_lyapunov) {
    o << "implied_lyapunov: " << *rep.implied_lyapunov << " per step (slope " << *rep.slope << " steps per bit)\n";
  } else {
    o << "implied_lyapunov: none (fewer than two precisions left the enclosure, or no positive slope)\n";
  }
  return o.str();
}

std::string csv_text(const SweepReport& rep, const Provenance& p) {
  std::ostringstream o;
  o << p.as_comment_lines();
  o << "# reference: " << rep.reference_answer << " (" << rep.reference_bits << " bits; " << rep.reference_status << ")\n";
  o << "# implied_lyapunov: " << (rep.implied_lyapunov ? std::to_string(*rep.implied_lyapunov) : "none") << "\n";
  o << "precision,bits,leaves_enclosure_at,answer\n";
  for (const SweepRow& r : rep.rows)
    o << r.precision << "," << r.bits << "," << (r.leaves_at ? std::to_string(*r.leaves_at) : "") << ","
      << csv_quoted(r.answer) << "\n";
  return o.str();
}

Figure divergence_figure(const SweepReport& rep, const Provenance& p, long long steps) {
  Figure f;
  f.title = "Precision sweep: first step outside the certified enclosure";
  f.xlabel = "significand bits";
  f.log_x = true;  // 24 ... 4096 bits: powers of two are evenly spaced
  f.log_x_base = 2;
  f.ylabel = "step";
  Series left{"leaves the enclosure", {}, {}, Rgb{213, 94, 0}, false, true, 3};
  Series stays{"stays within all " + std::to_string(std::min<long long>(steps, rep.reference_steps)) + " steps", {}, {},
               Rgb{0, 114, 178}, false, true, 3};
  for (const SweepRow& r : rep.rows) {
    if (r.leaves_at) {
      left.x.push_back(static_cast<double>(r.bits));
      left.y.push_back(static_cast<double>(*r.leaves_at));
    } else {
      stays.x.push_back(static_cast<double>(r.bits));
      stays.y.push_back(static_cast<double>(std::min<long long>(steps, rep.reference_steps)));
    }
  }
  if (!left.x.empty()) f.series.push_back(left);
  if (!stays.x.empty()) f.series.push_back(stays);
  if (rep.slope && left.x.size() >= 2) {
    double mx = 0, my = 0;
    for (size_t i = 0; i < left.x.size(); ++i) { mx += left.x[i]; my += left.y[i]; }
    mx /= left.x.size();
    my /= left.y.size();
    char lambda[64];
    std::snprintf(lambda, sizeof lambda, "%.4g", rep.implied_lyapunov.value_or(0));
    Series fit{std::string("least-squares fit: λ = ") + lambda + " per step", {}, {}, Rgb{0, 0, 0},
               true, false};
    // Linear in bits, so a curve on the log2 axis: sampled finely.
    const double xa = *std::min_element(left.x.begin(), left.x.end()), xb = *std::max_element(left.x.begin(), left.x.end());
    for (int k = 0; k <= 64; ++k) {
      const double x = xa * std::pow(xb / xa, k / 64.0);
      fit.x.push_back(x);
      fit.y.push_back(my + *rep.slope * (x - mx));
    }
    f.series.push_back(fit);
  }
  f.metadata = {{"Title", f.title}, {"provenance", p.as_json()}};
  return f;
}

}  // namespace

CommandRunner setup_sweep(CLI::App* sub) {
  auto opts = std::make_shared<OptionSet>(sub);
  auto scene = std::make_shared<std::string>();
  auto as_json = std::make_shared<bool>(false);
  sub->add_option("--scene", *scene, "TOML scene file with the same options (command line overrides)");
  add_model_options(*opts);
  add_start_options(*opts);
  opts->add("steps", "Number of steps N, integer in [1, 1000000] (default 1000)");
  opts->add("tolerance", "Distance from the enclosure that counts as leaving it, decimal in [0, 1] (default 2^-20)");
  opts->add("reference-max-bits", "Largest precision of the certified reference's escalation (default 16384)");
  opts->add("method", "Reference enclosure: lohner (default) | naive");
  opts->add("classify-steps", "Rows with neither sticking nor a period are classified over this many more steps, "
                              "integer in [8, 1000000] (default 500)");
  opts->add("out", "PREFIX: write PREFIX.json, PREFIX.csv and the pictures PREFIX.png/.pdf/.svg of --format (atomically)");
  add_picture_options(*opts);
  sub->add_flag("--json", *as_json, "JSON on stdout instead of the text table");

  auto run = [opts, scene, as_json](const std::string& argv_text) {
    Options o = merge(scene->empty() ? Options{} : load_scene(*scene, "sweep", sweep_keys()), opts->collected());
    if (*as_json) o.set("json", "true");
    const Request r = request_from(o);
    OutputSet outputs;  // reserved before the work: a path that cannot be written is found at once
    if (r.prefix)
      for (const std::string& path : output_paths(*r.prefix, r.picture)) outputs.reserve("out", path);
    Provenance p = provenance_for("sweep", o, Precision{Precision::Kind::interval, r.q.reference.max_bits}, argv_text);
    p.precision = "double, long, dd, quad, mpfr:64..4096 against interval (escalated " + r.q.reference.text() + ")";
    const SweepReport rep = precision_sweep(r.q);
    p.bits = rep.reference_bits;
    const json j = report_json(r, rep, p);
    if (r.prefix) {
      const Figure fig = divergence_figure(rep, p, r.q.steps);
      std::vector<OutputFile> files{{*r.prefix + ".json", [&](std::ostream& s) { s << j.dump(1) << "\n"; }},
                                    {*r.prefix + ".csv", [&](std::ostream& s) { s << csv_text(rep, p); }}};
      for (OutputFile& pic : picture_files(*r.prefix, r.picture, [&](std::ostream& out, ImageFormat fmt) {
             write_figure(out, fig, fmt, r.picture.render);
           }))
        files.push_back(std::move(pic));
      write_output_set(files, &outputs);
    }
    if (r.json) command_out() << j.dump(1) << "\n";
    else command_out() << p.as_comment_lines() << text_table(rep, r.q.steps);
    return 0;
  };
  return run;
}

}  // namespace bouncer::cli
