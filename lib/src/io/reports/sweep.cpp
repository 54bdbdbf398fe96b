#include "bouncer/io/reports/sweep.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iomanip>
#include <sstream>

#include "json.hpp"

namespace bouncer {

using reports::json;
using reports::null_or;

namespace {

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

}  // namespace

std::string sweep_json(const SweepReport& rep, const SweepQuestion& q, const Provenance& p) {
  json j;
  j["provenance"] = json::parse(p.as_json());
  j["note"] = "Decimal inputs are enclosed exactly in the certified reference (MPFI, outward rounding); each plain "
              "precision rounds them to its own format, which is part of what the sweep measures.";
  j["inputs"] = {{"model", name(q.model.law)}, {"a", q.model.a.text()}, {"eps", q.model.eps.text()},
                 {"c", q.model.c.text()}, {"wall", q.model.wall.text}, {"theta", q.start.theta.text()},
                 {"v", q.start.v.text()}, {"steps", q.steps}};
  j["tolerance"] = q.tolerance;
  j["leaves_definition"] =
      "first step whose state is farther than `tolerance` from the certified enclosure (theta on the circle), or "
      "whose event differs from the certified event, or that fails";
  json ref;
  ref["method"] = name(q.method);
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
  return j.dump(1) + "\n";
}

std::string sweep_table(const SweepReport& rep, const SweepQuestion& q) {
  std::ostringstream o;
  o << "reference: " << rep.reference_answer << " (" << rep.reference_bits << " bits; " << rep.reference_status << ")\n";
  o << std::left << std::setw(12) << "precision" << std::setw(7) << "bits" << std::setw(12) << "leaves_at"
    << "answer\n";
  for (const SweepRow& r : rep.rows) {
    o << std::left << std::setw(12) << r.precision << std::setw(7) << r.bits << std::setw(12)
      << (r.leaves_at ? std::to_string(*r.leaves_at) : std::string("-")) << r.answer << "\n";
  }
  o << "('-': stays within the enclosure for all " << std::min<long long>(q.steps, rep.reference_steps)
    << " certified steps)\n";
  if (rep.implied_lyapunov) {
    o << "implied_lyapunov: " << *rep.implied_lyapunov << " per step (slope " << *rep.slope << " steps per bit)\n";
  } else {
    o << "implied_lyapunov: none (fewer than two precisions left the enclosure, or no positive slope)\n";
  }
  return o.str();
}

std::string sweep_csv(const SweepReport& rep, const Provenance& p) {
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

Figure sweep_divergence_figure(const SweepReport& rep, const SweepQuestion& q, const Provenance& p) {
  const long long steps = q.steps;
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
    for (size_t i = 0; i < left.x.size(); ++i) {
      mx += left.x[i];
      my += left.y[i];
    }
    mx /= left.x.size();
    my /= left.y.size();
    char lambda[64];
    std::snprintf(lambda, sizeof lambda, "%.4g", rep.implied_lyapunov.value_or(0));
    Series fit{std::string("least-squares fit: λ = ") + lambda + " per step", {}, {}, Rgb{0, 0, 0}, true, false};
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

}  // namespace bouncer
