// bouncer-fuzz-step: random states and parameters through ImpactMap<T>::step, in every
// collision model, each step checked against invariants computed independently of the map.
//
// Each step is checked against the invariants of tests/fuzz_step/step_invariants.hpp (tau > 0, theta in
// [0, 1), v >= the wall's velocity, no penetration, impact on the wall, the collision law),
// computed in MPFR from the exact model; the libFuzzer target tests/fuzz/fuzz_step.cpp checks
// the same invariants on steps decoded from its bytes.
// Each random start is followed for --chain steps, so post-impact, sticking and release
// states (exact knots) are checked too. Deterministic for a given --seed.
// Exit status: 0 no violation, 1 a violation (the first one is printed, with the state in
// round-trip digits and the parameters as exact decimals, and a command reproducing it),
// 2 bad options.
#include <CLI/CLI.hpp>

#include <algorithm>
#include <chrono>
#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <map>
#include <optional>
#include <random>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "bouncer/model/impact_map.hpp"
#include "bouncer/scalar/precision.hpp"
#include "bouncer/scalar/thread_caches.hpp"
#include "step_invariants.hpp"

namespace {

using namespace bouncer;
using namespace bouncer::step_check;

// ---- random parameters and starts ----------------------------------------------------
struct Choice {
  std::string model = "all", wall = "all";
};

ModelSpec random_spec(Rng& rng, const Choice& ch) {
  ModelSpec m;
  static const char* laws[] = {"elastic", "constant", "veldep"};
  const std::string law = ch.model == "all" ? laws[rng.below(3)] : ch.model;
  m.law = parse_law("model", law);
  const double pa = rng.u01();
  if (pa < 0.1) {
    static const char* special[] = {"24", "1e9", "0.01", "0.5", "28.82", "8"};
    m.a = dec(special[rng.below(6)]);
  } else if (pa < 0.5) {
    m.a = dec(decimal_text(1 + 49 * rng.u01(), 1 + static_cast<int>(rng.below(17))));
  } else {
    m.a = dec(decimal_text(rng.log_uniform(0.01, 1e6), 1 + static_cast<int>(rng.below(17))));
  }
  if (m.law == Law::constant) {
    const double pe = rng.u01();
    if (pe < 0.25) {
      static const char* special[] = {"0", "1", "0.5", "1e-9", "0.999999999", "0.9", "0.96", "0.25"};
      m.eps = dec(special[rng.below(8)]);
    } else {
      m.eps = dec(decimal_text(rng.u01(), 1 + static_cast<int>(rng.below(17))));
    }
  }
  if (m.law == Law::veldep) {
    m.c = dec(decimal_text(rng.log_uniform(1e-3, 1e7), 1 + static_cast<int>(rng.below(17))));
    m.veldep_collapse = rng.chance(0.5);
  }
  m.downward = rng.chance(0.5) ? DownwardSticking::paper : DownwardSticking::impact;
  static const char* walls[] = {"triangle", "sawtooth", "asymmetric", "knots"};
  const std::string w = ch.wall == "all" ? walls[rng.below(4)] : ch.wall;
  if (w == "triangle" || w == "sawtooth") {
    m.wall = parse_wall("wall", w);
  } else if (w == "asymmetric") {
    std::string r;
    do r = decimal_text(0.01 + 0.98 * rng.u01(), 1 + static_cast<int>(rng.below(6)));
    while (!(dec(r) > Decimal::from_int(0) && dec(r) < Decimal::from_int(1)));
    m.wall = parse_wall("wall", "asymmetric:" + r);
  } else {
    // 2..6 knots at distinct 3-digit phases, heights in [-3, 3] (not all equal).
    for (;;) {
      const size_t n = 2 + rng.below(5);
      std::vector<int> s{0};
      while (s.size() < n) {
        const int k = 1 + static_cast<int>(rng.below(999));
        if (std::find(s.begin(), s.end(), k) == s.end()) s.push_back(k);
      }
      std::sort(s.begin(), s.end());
      std::string text = "knots:";
      for (size_t j = 0; j < n; ++j) {
        const int h = static_cast<int>(rng.below(601)) - 300;
        text += (j ? "," : "") + decimal_text(s[j] / 1000.0, 3) + ":" + decimal_text(h / 100.0, 3);
      }
      m.wall = parse_wall("wall", text);
      try {
        validate(m);
        break;
      } catch (const InputError&) {  // flat: draw again
      }
    }
  }
  validate(m);
  return m;
}

InitialCondition random_start(Rng& rng, const ModelSpec& m) {
  InitialCondition ic;
  const size_t n = m.wall.knots.size();
  const double pt = rng.u01();
  if (pt < 0.2) {
    ic.theta = m.wall.knots[rng.below(n)];  // exactly at a knot
  } else {
    std::string t;
    do t = decimal_text(rng.u01(), 1 + static_cast<int>(rng.below(17)));
    while (!(dec(t) < Decimal::from_int(1)));
    ic.theta = dec(t);
  }
  const mpq_class u = wall_velocity_exact(m.wall, ic.theta.value());
  const double pv = rng.u01();
  double delta;
  if (pv < 0.1) {
    delta = 0;  // moving with the wall: ride, or sticking at once
  } else if (pv < 0.15) {
    // A release-like start: at a knot with the previous segment's (larger) velocity.
    ic.theta = m.wall.knots[rng.below(n)];
    const int j = wall_segment_exact(m.wall, ic.theta.value());
    const int prev = j == 0 ? static_cast<int>(n) - 1 : j - 1;
    const mpq_class up = wall_velocity_exact(m.wall, m.wall.knots[static_cast<size_t>(prev)].value());
    const mpq_class uj = wall_velocity_exact(m.wall, ic.theta.value());
    ic.v = decimal_at_least(up > uj ? up : uj);
    return ic;
  } else if (pv < 0.4) {
    delta = rng.log_uniform(1e-12, 1e-2);
  } else if (pv < 0.95) {
    delta = rng.log_uniform(1e-2, 1e3);
  } else {
    delta = rng.log_uniform(1e3, 1e12);
  }
  const Decimal ud = decimal_at_least(u);
  if (delta == 0) {
    ic.v = ud;
  } else {
    const Decimal v = dec(decimal_text(u.get_d() + delta, 1 + static_cast<int>(rng.below(17))));
    ic.v = v < ud ? ud : v;
  }
  if (ic.v > dec("1e15")) ic.v = dec("1e15");
  return ic;
}


struct Counts {
  long long starts = 0, skipped = 0, steps = 0;
  std::map<std::string, long long> kinds, undecided;
  long long violations[kInvariants] = {};
  long long unchecked = 0;
  std::vector<std::pair<long long, std::string>> reports;  // (start, text): the first, or all

  void add(const Counts& o) {
    starts += o.starts;
    skipped += o.skipped;
    steps += o.steps;
    for (const auto& [k, n] : o.kinds) kinds[k] += n;
    for (const auto& [k, n] : o.undecided) undecided[k] += n;
    for (int i = 0; i < kInvariants; ++i) violations[i] += o.violations[i];
    unchecked += o.unchecked;
    reports.insert(reports.end(), o.reports.begin(), o.reports.end());
  }
};

// Start i draws from its own generator, seeded from (seed, i): a start is reproduced alone
// with --first-start i --states 1, and threads split the starts without changing them.
uint64_t start_seed(uint64_t seed, long long i) {
  uint64_t z = seed * 0x9e3779b97f4a7c15ULL + static_cast<uint64_t>(i) + 1;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

template <class T>
void run(const Precision& prec, long long first, long long last, long long stride, uint64_t seed, int chain,
         const Choice& ch, bool verbose, Counts& c) {
  using Tr = ScalarTraits<T>;
  const long hp_bits = std::max<long>(256, 2 * prec.bits + 64);
  for (long long i = first; i < last; i += stride) {
    Rng rng(start_seed(seed, i));
    const ModelSpec spec = random_spec(rng, ch);
    const InitialCondition ic = random_start(rng, spec);
    ++c.starts;
    try {
      validate(spec, ic, "theta", "v");
    } catch (const InputError& e) {
      ++c.skipped;  // the generator drew an invalid start (should not happen)
      continue;
    }
    const Model<T> model = make_model<T>(spec, prec.bits);
    const ImpactMap<T> map(model);
    State<T> s;
    try {
      s = make_state(model, ic);
    } catch (const InputError&) {
      ++c.skipped;  // theta rounds to 1 at this precision
      continue;
    }
    Checker<T> checker(spec, model, hp_bits, rng);
    for (int k = 0; k < chain; ++k) {
      std::optional<Violation> bad;
      StepResult<T> r;
      try {
        r = map.step(s);
        ++c.steps;
        ++c.kinds[name(r.kind)];
        bad = checker.check(s, r);
      } catch (const Undecided& e) {
        ++c.undecided[describe(e.reason)];
        break;
      } catch (const std::exception& e) {
        bad = Violation{kException, e.what()};
      }
      if (bad) {
        ++c.violations[bad->what];
        if (c.reports.empty() || verbose) {
          std::ostringstream o;
          o << "counterexample (--seed " << seed << " --first-start " << i << ", step " << k + 1 << " of its chain): "
            << kInvariantNames[bad->what] << ": " << bad->detail << "\n"
            << "  state: theta " << Tr::to_string(s.theta) << " v " << Tr::to_string(s.v)
            << (s.knot >= 0 ? " (at knot " + std::to_string(s.knot) + ")" : std::string()) << "\n"
            << "  parameters: " << spec_options(spec) << " --precision " << prec.text() << "\n"
            << "  reproduce: bouncer orbit " << spec_options(spec) << " --precision " << prec.text()
            << " --theta " << Tr::to_string(s.theta) << " --v " << Tr::to_string(s.v) << " --steps 1\n";
          c.reports.emplace_back(i, o.str());
        }
        break;
      }
      s = r.next;
    }
    c.unchecked += checker.unchecked;
  }
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"bouncer-fuzz-step: random states and parameters through the impact map, checked against "
               "invariants (tau > 0, theta in [0,1), v >= wall velocity, no penetration, impact on the wall, "
               "collision law). Exit 1 on a violation."};
  long long states = 10000;
  uint64_t seed = 1;
  int chain = 4;
  Choice ch;
  std::string precision_text = "double";
  bool verbose = false;
  long long first_start = 0;
  int threads = 1;
  app.add_option("--states", states, "Random starts, integer >= 1 (default 10000)")->check(CLI::Range(1LL, 1000000000000LL));
  app.add_option("--seed", seed, "Seed of the random draws (default 1)");
  app.add_option("--chain", chain, "Steps followed from each start, integer in [1, 1000] (default 4)")
      ->check(CLI::Range(1, 1000));
  app.add_option("--model", ch.model, "elastic | constant | veldep | all (default all)")
      ->check(CLI::IsMember({"elastic", "constant", "veldep", "all"}));
  app.add_option("--wall", ch.wall, "triangle | sawtooth | asymmetric | knots | all (default all)")
      ->check(CLI::IsMember({"triangle", "sawtooth", "asymmetric", "knots", "all"}));
  app.add_option("--precision", precision_text, "double (default) | long | dd | quad | mpfr:BITS");
  app.add_option("--first-start", first_start, "Index of the first start (default 0): --first-start I --states 1 "
                                               "re-runs start I of a seed alone")
      ->check(CLI::Range(0LL, 1000000000000LL));
  app.add_option("--threads", threads, "Threads, integer in [1, 256] (default 1); the starts do not depend on it")
      ->check(CLI::Range(1, 256));
  app.add_flag("--verbose", verbose, "Print every violation, not only the first");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e);
    std::cerr << "bouncer-fuzz-step: " << e.what() << "\n";
    return 2;
  }
  Precision prec;
  try {
    prec = parse_precision("precision", precision_text);
    if (prec.is_interval()) throw InputError("precision", "interval precisions are not fuzzed (point types only)");
  } catch (const InputError& e) {
    std::cerr << "bouncer-fuzz-step: " << e.what() << "\n";
    return 2;
  }
  const auto t0 = std::chrono::steady_clock::now();
  std::vector<Counts> parts(static_cast<size_t>(threads));
  {
    std::vector<std::thread> pool;
    for (int t = 0; t < threads; ++t)
      pool.emplace_back([&, t] {
        const MpfrThreadCaches caches;  // freed when this thread ends
        with_point_scalar(prec, [&](auto tag) {
          using T = typename decltype(tag)::type;
          run<T>(prec, first_start + t, first_start + states, threads, seed, chain, ch, verbose, parts[t]);
        });
      });
    for (auto& th : pool) th.join();
  }
  Counts c;
  for (const Counts& p : parts) c.add(p);
  std::sort(c.reports.begin(), c.reports.end());
  const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  long long total = 0;
  for (long long v : c.violations) total += v;
  std::cout << "bouncer-fuzz-step: precision " << prec.text() << ", seed " << seed << ", model " << ch.model
            << ", wall " << ch.wall << ", " << c.starts << " starts x up to " << chain << " steps, "
            << secs << " s\n";
  std::cout << "steps checked: " << c.steps;
  for (const auto& [k, n] : c.kinds) std::cout << ", " << k << " " << n;
  std::cout << "\nstarts skipped (theta rounds to 1): " << c.skipped << "\n";
  std::cout << "undecided steps:";
  if (c.undecided.empty()) std::cout << " none";
  for (const auto& [k, n] : c.undecided) std::cout << " [" << k << "] " << n;
  std::cout << "\nlong flights not checked knot by knot or period by period: " << c.unchecked << "\n";
  for (int i = 0; i < kInvariants; ++i)
    std::cout << "  " << kInvariantNames[i] << ": " << c.violations[i] << " violations\n";
  if (verbose) {
    for (const auto& [i, text] : c.reports) std::cout << text;
  } else if (!c.reports.empty()) {
    std::cout << "first " << c.reports.front().second;
  }
  std::cout << (total ? "FAIL" : "OK") << ": " << total << " violations\n";
  return total ? 1 : 0;
}
