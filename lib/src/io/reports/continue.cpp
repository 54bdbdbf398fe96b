#include "bouncer/io/reports/continue.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "bouncer/base/text.hpp"
#include "bouncer/io/grid_figures.hpp"
#include "bouncer/scalar/decimal.hpp"
#include "json.hpp"

namespace bouncer {

namespace {

using reports::json;
using reports::json_number;

std::string num(double x) {
  if (std::isnan(x)) return "nan";
  if (std::isinf(x)) return x > 0 ? "inf" : "-inf";
  return ScalarTraits<double>::to_string(x);
}

// Zoomed axes (AxisZoom in io/plot.hpp) place values exactly: the rational of a number as
// the branch prints it, a decimal with the digits of its precision (Mpfr: enough to read
// back the same value), so a window 1e-20 wide at mpfr:256 keeps its detail.
template <class T>
mpq_class exact_value(const T& x) {
  const std::string text = ScalarTraits<T>::to_string(x);
  const auto d = Decimal::parse(text);
  if (!d) throw std::runtime_error("not a finite decimal: '" + text + "'");
  return d->value();
}

// How far `param` (the computed a*, round trip in T) can be trusted (analysis/end_estimate.hpp):
// its kind, and for an estimate the digits it backs and the widened bracket.
void add_accuracy(json& j, const EndEstimate& est) {
  j["accuracy"] = name(est.kind);
  if (est.kind == EndEstimate::Kind::estimate) {
    const BackedDigits d = backed_digits(est.center, est.radius);
    j["a_star_backed"] = d.value;
    j["a_star_plus_minus"] = d.plus_minus;
    j["a_star_digits"] = d.digits;
    j["bracket_estimate"] = {d.lo, d.hi};
    j["error_estimate"] = json_number(est.error);
    j["refined_param"] = est.refined;
    j["refined_bits"] = est.bits;
  } else if (est.kind == EndEstimate::Kind::not_estimated && !est.note.empty()) {
    j["accuracy_note"] = est.note;
  }
}

template <class T>
json end_json(const Branch<T>& b, const BranchEnd<T>& e, Parameter vary, const Wall<T>& wall) {
  using Tr = ScalarTraits<T>;
  json j;
  j["reason"] = name(e.reason);
  j["param"] = Tr::to_string(e.param);
  j["bracket"] = {Tr::to_string(e.bracket_lo), Tr::to_string(e.bracket_hi)};
  j["margin"] = e.margin >= 0 ? json(name(static_cast<Margin>(e.margin))) : json(nullptr);
  j["impact"] = e.impact >= 0 ? json(e.impact + 1) : json(nullptr);
  j["knot"] = e.knot >= 0 ? json(wall.knot_exact[e.knot].get_str()) : json(nullptr);
  if (!std::isnan(e.graze_theta)) j["graze_theta"] = e.graze_theta;  // a smooth wall's grazing phase
  j["detail"] = e.detail;
  if (e.reason == EndReason::doubling) j["mother_period"] = e.mother_period;
  add_accuracy(j, e.estimate);
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
  j["sentence"] = branch_end_sentence(b, e, vary);
  return j;
}

// Whether the error estimate's widened bracket contains the certified enclosure of a*: the
// estimate checked against a proof, where both exist.
std::optional<bool> estimate_contains(const CertifiedBranchEnd& c, const EndEstimate& e) {
  if (!c.two_sided.certified || e.kind != EndEstimate::Kind::estimate) return std::nullopt;
  return e.lo <= c.two_sided.lo && c.two_sided.hi <= e.hi;
}

json certified_json(const CertifiedBranchEnd& c, const EndEstimate& est, long period, Parameter vary) {
  const BranchEndCertificate& ce = c.certificate;
  json cj;
  cj["range"] = {c.lo, c.hi};
  cj["certified_range"] = ce.certified ? json{exact_decimal(ce.from), exact_decimal(ce.to)} : json(nullptr);
  cj["certified_to"] = ce.certified ? json(exact_decimal(ce.bound)) : json(nullptr);
  if (ce.certified) cj["events"] = ce.events;
  cj["theorem"] = ce.theorem;
  cj["pieces"] = ce.pieces;
  cj["statement"] = certified_end_statement(c, period, vary);
  const BorderCollisionCertificate& bc = c.two_sided;
  json two;
  two["certified"] = bc.certified;
  two["bits"] = bc.bits;
  two["enclosure"] = bc.certified ? json{bc.parameter.lo, bc.parameter.hi} : json(nullptr);
  two["width"] = bc.certified ? json(bc.width) : json(nullptr);
  two["margin"] = name(bc.margin);
  two["margin_text"] = bc.margin_text;
  two["events"] = bc.events;
  // Which unknowns the proof used (verify/border_collision.hpp Formulation).
  two["formulation"] = bc.certified ? json(bc.shooting ? "shooting" : "composed") : json(nullptr);
  two["proof_interval"] = bc.certified ? json{exact_decimal(bc.z_lo), exact_decimal(bc.z_hi)} : json(nullptr);
  two["bracket_contains"] = c.bracket_contains;
  const std::optional<bool> widened = estimate_contains(c, est);
  two["estimate_contains"] = widened ? json(*widened) : json(nullptr);
  two["statement"] = bc.statement;
  if (!bc.certified) two["reason"] = bc.reason;
  cj["two_sided"] = two;
  return cj;
}

// A period doubling's or fold's certificate (--certify): the enclosure of p*, the
// multipliers there, the theorem, and whether the estimate's widened bracket contains it.
json smooth_json(const PeriodDoublingCertificate& c, const EndEstimate& est) {
  json j;
  j["certified"] = c.certified;
  j["bits"] = c.bits;
  j["enclosure"] = c.certified ? json{c.parameter.lo, c.parameter.hi} : json(nullptr);
  j["width"] = c.certified ? json(c.width) : json(nullptr);
  j["other_multiplier"] = c.certified ? json{c.other.lo, c.other.hi} : json(nullptr);
  j["events"] = c.events;
  j["estimate_contains"] = c.certified && est.kind == EndEstimate::Kind::estimate ? json(est.lo <= c.lo && c.hi <= est.hi) : json(nullptr);
  j["statement"] = c.statement;
  if (!c.certified) j["reason"] = c.reason;
  return j;
}

}  // namespace

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
    case EndReason::doubling: return "the period doubling it is born from";
    case EndReason::event_change: return "a change of the event sequence";
    case EndReason::period_collapse: return "a period collapse";
    case EndReason::lost: return "loss of the corrector";
    default: return "";
  }
}

template <class T>
std::string branch_end_sentence(const Branch<T>& b, const BranchEnd<T>& e, Parameter vary) {
  using Tr = ScalarTraits<T>;
  const std::string par = name(vary);
  const std::string q = "period " + std::to_string(b.period);
  if (e.reason == EndReason::range_end) return q + " reaches the range end " + par + " = " + Tr::to_string(e.param);
  if (e.reason == EndReason::max_points) return q + " stops at " + par + " = " + Tr::to_string(e.param) + " (--max-points)";
  std::string s = q + " ends at " + par + "* = " + end_value_text(e.estimate, Tr::to_string(e.param)) + " by " + cause_words(e.reason, e.margin) + " (" +
                  e.detail + ")";
  if (e.beyond_done) {
    s += "; beyond it the orbit goes to " + class_words(e.beyond);
    if (!e.beyond_orbit.empty())
      s += "; Newton finds a period-" + std::to_string(b.period) + " orbit there with events " + e.beyond_orbit +
           (e.beyond_orbit_period != b.period ? " (minimal period " + std::to_string(e.beyond_orbit_period) + ")" : "") +
           (e.beyond_relation == BeyondRelation::mother         ? ", the orbit the branch is born from"
            : e.beyond_relation == BeyondRelation::continuation ? ", the branch's continuation"
            : e.beyond_relation == BeyondRelation::other_branch ? ", another orbit, which already exists before a* (not a continuation)"
            : e.beyond_relation == BeyondRelation::unrelated    ? ", not the branch's continuation (away from it; not found before a*)"
                                                                : "");
  } else if (!e.beyond_note.empty()) {
    s += "; " + e.beyond_note;
  }
  return s;
}

std::string certified_end_statement(const CertifiedBranchEnd& c, long period, Parameter vary) {
  const std::string par = name(vary);
  const BranchEndCertificate& ce = c.certificate;
  if (!ce.certified) return "nothing certified next to " + par + "*";
  return "certified (Krawczyk): the period-" + std::to_string(period) + " orbit exists for every " + par + " in [" +
         exact_decimal(ce.from) + ", " + exact_decimal(ce.to) + "], so " + par + "* " + (c.high_end ? ">= " : "<= ") +
         exact_decimal(ce.bound) + (c.two_sided.certified ? "; a* itself is enclosed on both sides (the two-sided certificate)" : "; the other side of the bracket is numerical only");
}

std::string two_sided_statement(const CertifiedBranchEnd& c) {
  const BorderCollisionCertificate& bc = c.two_sided;
  if (!bc.certified) return bc.statement;
  std::string s = bc.statement;
  while (!s.empty() && (s.back() == '.' || s.back() == ' ')) s.pop_back();
  return s + (c.bracket_contains ? "; the branch's own bracket contains it"
                                            : "; the branch's own bracket does NOT contain it (its last digits are not right)");
}

template <class T>
std::string branch_csv(const Branch<T>& b, Parameter vary) {
  using Tr = ScalarTraits<T>;
  std::ostringstream csv;
  csv << name(vary) << ",stability,mu1_re,mu1_im,mu1_abs,mu2_re,mu2_im,mu2_abs,events";
  for (int k = 0; k < kMargins; ++k) csv << ',' << name(static_cast<Margin>(k)) << ',' << name(static_cast<Margin>(k)) << "_impact";
  csv << ",residual";
  for (long i = 0; i < b.period; ++i) csv << ",theta_" << i << ",v_" << i;
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
  return csv.str();
}

template <class T>
std::string branch_json(const ContinueRequest& r, const Model<T>& m, const Branch<T>& b, const CertifiedBranchEnds& certified,
                        const Provenance& prov) {
  using Tr = ScalarTraits<T>;
  const BranchPoint<T>& s0 = b.points[b.start];
  json sum;
  sum["command"] = "continue";
  sum["model"] = name(r.model.law);
  sum["vary"] = name(r.vary);
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
  json low = end_json(b, b.low, r.vary, m.wall), high = end_json(b, b.high, r.vary, m.wall);
  if (certified.low) low["certified"] = certified_json(*certified.low, b.low.estimate, r.period, r.vary);
  if (certified.high) high["certified"] = certified_json(*certified.high, b.high.estimate, r.period, r.vary);
  if (certified.low_smooth) low["certified"] = smooth_json(*certified.low_smooth, b.low.estimate);
  if (certified.high_smooth) high["certified"] = smooth_json(*certified.high_smooth, b.high.estimate);
  low["events_at_end"] = event_text(b.points.front().events);
  high["events_at_end"] = event_text(b.points.back().events);
  sum["low"] = low;
  sum["high"] = high;
  json bif = json::array();
  for (size_t i = 0; i < b.bifurcations.size(); ++i) {
    const Bifurcation<T>& x = b.bifurcations[i];
    json one{{"kind", name(x.kind)}, {"param", Tr::to_string(x.param)},
             {"bracket", {Tr::to_string(x.bracket_lo), Tr::to_string(x.bracket_hi)}}};
    add_accuracy(one, x.estimate);
    if (i < certified.bifurcations.size()) one["certified"] = smooth_json(certified.bifurcations[i], x.estimate);
    bif.push_back(one);
  }
  sum["bifurcations"] = bif;
  json doc;
  doc["provenance"] = json::parse(prov.as_json());
  doc["summary"] = sum;
  return doc.dump(2) + "\n";
}

template <class T>
std::string branch_text(const ContinueRequest& r, const Branch<T>& b, const CertifiedBranchEnds& certified,
                        const Provenance& prov) {
  using Tr = ScalarTraits<T>;
  const std::string par = name(r.vary);
  const BranchPoint<T>& s0 = b.points[b.start];
  std::ostringstream text;
  text << prov.as_comment_lines();
  text << "period " << r.period << " branch (" << name(r.model.law) << " model) in " << par << ", started at " << par
       << " = " << Tr::to_string(s0.param) << " (" << s0.stability << ", events " << event_text(s0.events) << "): "
       << b.points.size() << " points, " << par << " in [" << Tr::to_string(b.points.front().param) << ", "
       << Tr::to_string(b.points.back().param) << "]\n";
  text << "low end:  " << branch_end_sentence(b, b.low, r.vary) << "\n";
  text << "high end: " << branch_end_sentence(b, b.high, r.vary) << "\n";
  if (certified.low) text << "low end " << certified_end_statement(*certified.low, r.period, r.vary) << "\n";
  if (certified.high) text << "high end " << certified_end_statement(*certified.high, r.period, r.vary) << "\n";
  for (const auto* c : {&certified.low, &certified.high}) {
    if (!*c) continue;
    const bool low = c == &certified.low;
    const std::optional<bool> widened = estimate_contains(**c, low ? b.low.estimate : b.high.estimate);
    text << (low ? "low end" : "high end") << " two-sided: " << two_sided_statement(**c)
         << (!widened ? "" : *widened ? "; the error estimate's widened bracket contains it"
                                      : "; the error estimate's widened bracket does NOT contain it (the estimate failed)")
         << "\n";
  }
  for (const bool high : {false, true})
    if (const auto& f = high ? certified.high_smooth : certified.low_smooth)
      text << (high ? "high end " : "low end ") << cause_words((high ? b.high : b.low).reason, -1) << ": " << f->statement << "\n";
  for (size_t i = 0; i < b.bifurcations.size(); ++i) {
    const Bifurcation<T>& x = b.bifurcations[i];
    text << name(x.kind) << " at " << par << "* = " << end_value_text(x.estimate, Tr::to_string(x.param)) << "\n";
    if (i < certified.bifurcations.size()) text << "  " << certified.bifurcations[i].statement << "\n";
  }
  return text.str();
}

template <class T>
Figure branch_figure(const ContinueRequest& r, const Model<T>& m, const Branch<T>& b, bool show_theta, const Provenance& prov) {
  using Tr = ScalarTraits<T>;
  const std::string par = name(r.vary);
  const BranchPoint<T>& s0 = b.points[b.start];
  Figure fig;
  Series st{"stable", {}, {}, Rgb{33, 102, 172}, false, true, 2};
  Series un{"unstable", {}, {}, Rgb{230, 97, 1}, false, true, 2};
  Series mg{"marginal", {}, {}, Rgb{150, 150, 150}, false, true, 1};
  double y0 = show_theta ? 0 : INFINITY, y1 = show_theta ? 1 : -INFINITY;
  // The window in the parameter: the range, or where the branch is when it fills less than
  // 1/20 of the range and both its ends lie inside (a branch 0.02 wide in a range 16 wide is
  // otherwise one vertical line): its points and ends, and a tenth of their spread beyond each.
  mpq_class x_lo = r.lo.value(), x_hi = r.hi.value();
  // An end the branch reached inside the range (drawn as a line), not where it was cut off.
  const auto inside = [](const BranchEnd<T>& e) {
    return e.reason != EndReason::range_end && e.reason != EndReason::max_points;
  };
  bool window = false;
  if (inside(b.low) && inside(b.high)) {
    mpq_class h_lo = exact_value(b.low.param), h_hi = h_lo;
    const auto widen = [&](const T& x) {
      const mpq_class q = exact_value(x);
      if (q < h_lo) h_lo = q;
      if (h_hi < q) h_hi = q;
    };
    widen(b.high.param);
    for (const BranchPoint<T>& p : b.points) widen(p.param);
    const mpq_class spread = h_hi - h_lo;
    if (sgn(spread) > 0 && spread * 20 < x_hi - x_lo) {
      window = true;
      x_lo = std::max(x_lo, mpq_class(h_lo - spread / 10));
      x_hi = std::min(x_hi, mpq_class(h_hi + spread / 10));
    }
  }
  // A window a double cannot resolve (a zoom) is drawn relative to an offset, from the
  // exact values; so is v then, whose spread over such a range is as small.
  const AxisZoom zx(x_lo, x_hi);
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
    // 6% beyond the data, at least 1e-6 of the window's width (1e-6 for ordinary ranges).
    const mpq_class pad = std::max(mpq_class((v_hi - v_lo) * 6 / 100), mpq_class((x_hi - x_lo) / 1000000));
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
      if (!show_theta && !zx.active()) {
        y0 = std::min(y0, y);
        y1 = std::max(y1, y);
      }
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
  // A located value in a label: short_num's digits, or fewer when its error estimate backs
  // fewer (analysis/end_estimate.hpp).
  auto backed_short = [&](const T& x, const EndEstimate& est) {
    if (est.kind == EndEstimate::Kind::estimate && !zx.active()) {
      const BackedDigits d = backed_digits(est.center, est.radius);
      if (d.digits < 8) return d.value;
    }
    return short_num(x);
  };
  // Legend labels short enough for one line: the cause and the impact.
  auto end_label = [&](const BranchEnd<T>& e) {
    const std::string i = std::to_string(e.impact + 1);
    const std::string knot = e.knot >= 0 ? m.wall.knot_exact[e.knot].get_str() : "";
    std::string what = cause_words(e.reason, e.margin);
    if (e.reason == EndReason::doubling) what = "born at the period-" + std::to_string(e.mother_period) + " doubling";
    if (e.reason == EndReason::border) {
      switch (static_cast<Margin>(e.margin)) {
        case Margin::knot: what = "border collision, impact " + i + " at θ = " + knot; break;
        case Margin::clearance:
          what = "grazing, flight " + i + " at θ " + (std::isnan(e.graze_theta) ? "= " + knot : "≈ " + approximate_text(e.graze_theta));
          break;
        case Margin::speed: what = "touchdown, impact " + i; break;
        case Margin::sticking: what = "sticking threshold, impact " + i; break;
      }
    }
    return par + "* = " + backed_short(e.param, e.estimate) + ": " + what;
  };
  for (const BranchEnd<T>* e : {&b.low, &b.high})
    if (inside(*e))
      vline(e->param, end_label(*e), e->reason == EndReason::fold || e->reason == EndReason::doubling ? Rgb{118, 42, 131} : Rgb{215, 25, 28});
  for (const Bifurcation<T>& x : b.bifurcations)
    vline(x.param, par + "* = " + backed_short(x.param, x.estimate) + ": " +
                       (x.kind == SmoothKind::fold ? "fold (+1)" : x.kind == SmoothKind::period_doubling ? "period doubling (-1)" : "Neimark-Sacker"),
          Rgb{27, 120, 55});
  fig.x_min = zx(x_lo);
  fig.x_max = zx(x_hi);
  fig.y_min = y0;
  fig.y_max = y1;
  fig.x_offset = zx.offset();
  fig.y_offset = zy.offset();
  fig.legend_below = true;
  fig.title = "Period-" + std::to_string(r.period) + " branch, " + model_name(r.model);
  std::string fixed;
  if (r.vary != Parameter::a) fixed += "a = " + r.model.a.text() + ", ";
  if (r.model.law == Law::constant && r.vary != Parameter::eps) fixed += "ε = " + r.model.eps.text() + ", ";
  if (r.model.law == Law::veldep && r.vary != Parameter::c) fixed += "c = " + r.model.c.text() + ", ";
  fig.subtitle = fixed + "started at " + par + " = " + short_num(s0.param) + "; " + std::to_string(b.points.size()) + " points, " +
                 r.precision.text();
  if (window) fig.subtitle += "; the branch's part of the range " + r.lo.text() + ":" + r.hi.text();
  fig.xlabel = parameter_label(r.vary);
  fig.ylabel = show_theta ? "θ (phase of impact)" : "v (velocity after impact)";
  fig.metadata = png_metadata(prov, fig.title);
  return fig;
}

#define BOUNCER_CONTINUE_REPORT(T, kind)                                                                                  \
  template std::string branch_end_sentence<T>(const Branch<T>&, const BranchEnd<T>&, Parameter);                      \
  template std::string branch_csv<T>(const Branch<T>&, Parameter);                                                      \
  template std::string branch_json<T>(const ContinueRequest&, const Model<T>&, const Branch<T>&,                        \
                                      const CertifiedBranchEnds&, const Provenance&);                                    \
  template std::string branch_text<T>(const ContinueRequest&, const Branch<T>&, const CertifiedBranchEnds&,             \
                                      const Provenance&);                                                                \
  template Figure branch_figure<T>(const ContinueRequest&, const Model<T>&, const Branch<T>&, bool, const Provenance&);
BOUNCER_FOR_EACH_ANALYSIS_SCALAR(BOUNCER_CONTINUE_REPORT)
#undef BOUNCER_CONTINUE_REPORT

}  // namespace bouncer
