// bench_border: the cost of a certified two-sided border collision (issue 23: < 1 s at
// mpfr:128), of long periods (11, 66, 100), a period doubling and a fold. For each case: the
// double continuation that locates the end (not timed), then certify_border_collision in
// both formulations (composed: the first point unknown; shooting: all Q points; period 1
// composed only) at 128 (and 256) bits, wall-clock, best of three (a proof that fails runs
// once); a table with the enclosure's width and the double bracket's distance to it. The
// trade it measures: composed is quicker for short periods, and fails for long ones where
// the interval steps' wrapping grows like 2^Q. Timings are printed, never checked.
//
// Usage: bench_border [--quick] [--json FILE]   (--quick: one run per case, 128 bits only)
//        bench_border --columns   (the tables' columns as JSON, nothing run; bench_record.hpp)
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "bench_record.hpp"
#include "bouncer/analysis/continuation.hpp"
#include "bouncer/verify/border_collision.hpp"

using namespace bouncer;

namespace {

ModelSpec spec(Law law, const char* a, const char* eps, const char* c) {
  ModelSpec m;
  m.law = law;
  m.a = *Decimal::parse(a);
  if (law == Law::constant) m.eps = *Decimal::parse(eps);
  m.c = *Decimal::parse(c);
  m.wall = parse_wall("wall", "triangle");
  return m;
}

struct Case {
  const char* name;
  ModelSpec model;
  long period;
  double theta, v, lo, hi;
  bool high;  // which end of the continued branch
};

double distance(double blo, double bhi, const BorderCollisionCertificate& c) {
  const mpq_class lo(blo), hi(bhi);
  if (hi < c.lo) return mpq_class(c.lo - hi).get_d();
  if (c.hi < lo) return mpq_class(lo - c.hi).get_d();
  return 0;
}

// The two tables: their columns (and text widths) in one place, for the text and the JSON.
struct Tables {
  bench::Table border{"border", "certified border collisions, period doubling and fold: best wall-clock seconds",
                      {"end", "form", "bits", "seconds", "width", "double off", "margin"}, {-44, -9, 5, 10, 12, 12, -1}, {}, {}};
  bench::Table enclosures{"enclosures", "the enclosures of a* at 128 bits, and double's bracket",
                          {"end", "form", "a* in", "double bracket", "double bracket vs a*"}, {-44, -9, -1, -1, -1}, {}, {}};
  std::vector<const bench::Table*> all() const { return {&border, &enclosures}; }
};

// Whether double's bracket [blo, bhi] contains the enclosure's a*, or how far it misses it.
std::string versus(double off) { return off == 0 ? "contains a*" : "misses it by " + bench::fmt("%.2g", off); }

// The 256-bit enclosures against the 128-bit ones of the same end and formulation.
struct Nesting {
  int compared = 0, inside = 0;
  void check(const mpq_class& lo128, const mpq_class& hi128, const mpq_class& lo, const mpq_class& hi) {
    ++compared;
    if (lo128 <= lo && hi <= hi128) ++inside;
  }
};

std::string bracket(double lo, double hi) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "[%.17g, %.17g]", lo, hi);
  return buf;
}

}  // namespace

int main(int argc, char** argv) {
  const bench::Run run = bench::Run::start("bench_border", argc, argv);
  Tables t;
  if (run.columns_only) return run.print_columns(t.all());
  const bool quick = argc > 1 && std::strcmp(argv[1], "--quick") == 0;
  if (argc > 2 || (argc > 1 && !quick)) {
    std::printf("usage: bench_border [--quick] [--json FILE]\n       bench_border --columns\n");
    return argc > 1 && std::strcmp(argv[1], "--help") == 0 ? 0 : 2;
  }
  run.print_provenance();
  Nesting nesting;
  const std::vector<Case> cases = {
      {"sticking threshold 200/9 (release, eps 1/4)", spec(Law::constant, "24", "0.25", "1000"), 1, 0.5, 4, 20, 31, false},
      {"knot theta = 0 at 32 (release, eps 1/4)", spec(Law::constant, "26", "0.25", "1000"), 1, 0.5, 4, 24, 33.5, true},
      {"veldep c 1000 P7 low end (knot 1/2)", spec(Law::veldep, "28", "1", "1000"), 7, 0.19204436106841707, 26.916257785320354, 27, 29, false},
      {"veldep c 1000 P7 high end (knot 0)", spec(Law::veldep, "28", "1", "1000"), 7, 0.19204436106841707, 26.916257785320354, 27, 29, true},
      {"veldep c 1000 unstable P7 (grazing 1/2)", spec(Law::veldep, "25", "1", "1000"), 7, 0.016124178545083214, 10.063538832537404, 22, 28, false},
      {"veldep c 1000 P11 high end (knot 1/2)", spec(Law::veldep, "24.5", "1", "1000"), 11, 0.01685443925323413, 25.227892214860187, 24, 25, true},
      {"veldep c 1000 P66 low end (knot 1/2)", spec(Law::veldep, "15.2", "1", "1000"), 66, 0.007894477576029256, 43.635535422440235, 15, 15.5, false},
      {"veldep c 1000 P100 low end (knot 0)", spec(Law::veldep, "19.5", "1", "1000"), 100, 0.014057849515324, 23.970073801684368, 19.45, 19.55, false},
      {"veldep c 1000 P100 high end (knot 1/2)", spec(Law::veldep, "19.5", "1", "1000"), 100, 0.014057849515324, 23.970073801684368, 19.45, 19.55, true},
  };
  t.border.print_header();
  for (const Case& k : cases) {
    const Model<double> m = make_model<double>(k.model, 53);
    const Branch<double> b = continue_branch(m, Parameter::a, k.period, State<double>{k.theta, k.v}, k.lo, k.hi);
    const BranchEnd<double>& end = k.high ? b.high : b.low;
    if (end.reason != EndReason::border) {
      t.border.add_and_print({k.name, "-", "-", "-", "-", "-", "continuation did not end by a border collision: " + end.detail});
      continue;
    }
    BorderCollisionQuestion q;
    q.end.model = k.model;
    q.end.vary = Parameter::a;
    q.end.period = k.period;
    q.end.last_point = {*Decimal::parse(ScalarTraits<double>::to_string(end.last_point.theta)),
                        *Decimal::parse(ScalarTraits<double>::to_string(end.last_point.v))};
    const auto [lo, hi] = branch_end_interval<double>(end.bracket_lo, end.bracket_hi, k.high, 53);
    q.end.lo = *Decimal::parse(lo);
    q.end.hi = *Decimal::parse(hi);
    q.end.high_end = k.high;
    if (end.margin >= 0) q.margin = static_cast<Margin>(end.margin);
    for (const Formulation form : {Formulation::composed, Formulation::shooting}) {
      if (form == Formulation::shooting && k.period == 1) continue;
      const char* form_name = form == Formulation::composed ? "composed" : "shooting";
      q.formulation = form;
      std::optional<std::pair<mpq_class, mpq_class>> at128;  // the 128-bit enclosure, for the 256-bit one
      for (long bits : quick ? std::vector<long>{128} : std::vector<long>{128, 256}) {
        q.bits = bits;
        double best = 1e300;
        BorderCollisionCertificate c;
        for (int run = 0; run < (quick ? 1 : 3); ++run) {
          const auto t0 = std::chrono::steady_clock::now();
          c = certify_border_collision(q);
          best = std::min(best, std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
          if (!c.certified) break;
        }
        if (!c.certified) {
          t.border.add_and_print({k.name, form_name, std::to_string(bits), bench::fmt("%.4f", best), "-", "-",
                                  "NOT CERTIFIED: " + c.reason.substr(0, 150)});
          continue;
        }
        const double off = distance(end.bracket_lo, end.bracket_hi, c);
        t.border.add_and_print({k.name, form_name, std::to_string(bits), bench::fmt("%.4f", best), bench::fmt("%.3g", c.width),
                                bench::fmt("%.3g", off), c.margin_text});
        if (bits == 128) {
          t.enclosures.add({k.name, form_name, "[" + c.parameter.lo + ", " + c.parameter.hi + "]",
                            bracket(end.bracket_lo, end.bracket_hi), versus(off)});
          at128.emplace(c.lo, c.hi);
        } else if (at128) {
          nesting.check(at128->first, at128->second, c.lo, c.hi);
        }
      }
    }
  }
  // Smooth ends: a period doubling (eps = 0.9 period 2) and a fold (eps = 0.9 period 11),
  // the same construction on det(DP^Q +- I).
  auto smooth = [&](const char* name, const PeriodDoublingQuestion& q0, double blo_d, double bhi_d, auto certify) {
    PeriodDoublingQuestion q = q0;
    std::optional<std::pair<mpq_class, mpq_class>> at128;
    for (long bits : quick ? std::vector<long>{128} : std::vector<long>{128, 256}) {
      q.bits = bits;
      double best = 1e300;
      PeriodDoublingCertificate c;
      for (int run = 0; run < (quick ? 1 : 3); ++run) {
        const auto t0 = std::chrono::steady_clock::now();
        c = certify(q);
        best = std::min(best, std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
      }
      if (!c.certified) {
        t.border.add_and_print({name, "composed", std::to_string(bits), bench::fmt("%.4f", best), "-", "-",
                                "NOT CERTIFIED: " + c.reason.substr(0, 150)});
        continue;
      }
      const mpq_class blo(blo_d), bhi(bhi_d);
      const double off = bhi < c.lo ? mpq_class(c.lo - bhi).get_d() : c.hi < blo ? mpq_class(blo - c.hi).get_d() : 0.0;
      t.border.add_and_print({name, "composed", std::to_string(bits), bench::fmt("%.4f", best), bench::fmt("%.3g", c.width),
                              bench::fmt("%.3g", off), "other multiplier [" + c.other.lo + ", " + c.other.hi + "]"});
      if (bits == 128) {
        t.enclosures.add({name, "composed", "[" + c.parameter.lo + ", " + c.parameter.hi + "]", bracket(blo_d, bhi_d), versus(off)});
        at128.emplace(c.lo, c.hi);
      } else if (at128) {
        nesting.check(at128->first, at128->second, c.lo, c.hi);
      }
    }
  };
  auto question = [](const ModelSpec& ms, long period, const State<double>& x, double lo, double hi) {
    PeriodDoublingQuestion q;
    q.model = ms;
    q.period = period;
    q.point = {*Decimal::parse(ScalarTraits<double>::to_string(x.theta)), *Decimal::parse(ScalarTraits<double>::to_string(x.v))};
    q.lo = *Decimal::parse(ScalarTraits<double>::to_string(lo));
    q.hi = *Decimal::parse(ScalarTraits<double>::to_string(hi));
    return q;
  };
  {
    const ModelSpec ms = spec(Law::constant, "19", "0.9", "1000");
    const Branch<double> b = continue_branch(make_model<double>(ms, 53), Parameter::a, 2,
                                             State<double>{0.1678819228862684, 14.143149884133248}, 12.0, 21.0);
    if (!b.bifurcations.empty()) {
      const Bifurcation<double>& pd = b.bifurcations[0];
      const BranchPoint<double>* near = &b.points[0];
      for (const BranchPoint<double>& p : b.points)
        if (std::fabs(p.param - pd.param) < std::fabs(near->param - pd.param)) near = &p;
      smooth("eps 0.9 P2 period doubling (multiplier -1)", question(ms, 2, near->orbit.points[0], pd.bracket_lo, pd.bracket_hi),
             pd.bracket_lo, pd.bracket_hi, [](const PeriodDoublingQuestion& q) { return certify_period_doubling(q); });
    }
  }
  {
    const ModelSpec ms = spec(Law::constant, "12.5", "0.9", "1000");
    const Branch<double> b = continue_branch(make_model<double>(ms, 53), Parameter::a, 11,
                                             State<double>{0.04780185758554826, 34.63889719838767}, 12.0, 13.0);
    if (b.low.reason == EndReason::fold)
      smooth("eps 0.9 P11 fold (multiplier +1)", question(ms, 11, b.low.last_point, b.low.bracket_lo, b.low.bracket_hi),
             b.low.bracket_lo, b.low.bracket_hi, [](const PeriodDoublingQuestion& q) { return certify_fold(q); });
  }
  if (nesting.compared > 0)
    t.border.notes.push_back("At 256 bits, " + std::to_string(nesting.inside) + " of " + std::to_string(nesting.compared) +
                             " enclosures lie inside the 128-bit enclosure of the same end and formulation.");
  for (const std::string& n : t.border.notes) std::printf("%s\n", n.c_str());
  std::printf("\n");
  t.enclosures.print_all();
  return run.finish(t.all()) ? 0 : 1;
}
