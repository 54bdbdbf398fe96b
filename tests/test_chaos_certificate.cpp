// Chaos certificates (verify/chaos_certificate.hpp, io/chaos_certificate.hpp): the Arb replay
// against independent truth, tampered certificates, and the file form against hostile text.
//
// 1. The Henon map at a = 6, b = 3/10 has a full horseshoe (Devaney and Nitecki 1979;
//    tests/test_covering.cpp case 3): the strips N_+ and N_- cover each other and themselves,
//    h_top = log 2. A certificate made by bouncer's MPFI checks (check_horseshoe) must replay
//    as valid in Arb, with the stated bound within 1e-12 of log 2.
// 2. Tampering: a corner moved (one h-set shifted), a covering removed (the stated quotient 2
//    is then above rho = (1 + sqrt 5)/2 of what is left), a covering added that does not hold,
//    a stated bound raised above log 2, h-sets made to overlap: each must be rejected, saying
//    which check failed.
// 3. The spectral-radius test alone, exact: the golden-mean matrix has rho = 1.6180339887...;
//    the quotients 1.618 and (exactly) rho's rational lower neighbours pass, 1.6181 fails.
// 4. The replay's impact map (written again from docs/model.md, over Arb) against bouncer's
//    (MPFI, model/): at random states of the three restitution laws, including flights over
//    several wall segments, both enclosures must meet (each contains the true value), and be
//    narrow.
// 5. The bouncer: the veldep period-2 saddle's h-set (test_covering.cpp case 6) covers itself
//    under F^2 in the replay too, thin or not; with its frame's columns swapped it does not.
// 6. The file form: a round trip keeps every number exactly; malformed, hostile or
//    inconsistent text is refused with an InputError naming the field.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <regex>

#include "bouncer/base/error.hpp"
#include "bouncer/io/chaos_certificate.hpp"
#include "bouncer/model/model.hpp"
#include "bouncer/verify/chaos_certificate.hpp"
#include "bouncer/verify/covering.hpp"
#include "bouncer/verify/covering_impact.hpp"
#include "bouncer/verify/enclosure.hpp"
#include "test_support.hpp"

namespace bouncer {
namespace {

constexpr long kBits = 128;

mpq_class dec(const char* text) { return Decimal::parse(text)->value(); }

Mpfi q(long num, long den = 1) { return enclose(mpq_class(num, den), mpq_class(num, den), kBits); }

std::optional<Box2> henon(const Box2& p) { return Box2{1 - q(6) * (p[0] * p[0]) + p[1], q(3, 10) * p[0]}; }

std::vector<HSet2> henon_sets() {
  return {hset_rectangle(mpq_class(3, 20), mpq_class(3, 5), mpq_class(-1, 5), mpq_class(1, 5)),
          hset_rectangle(mpq_class(-3, 5), mpq_class(-3, 20), mpq_class(-1, 5), mpq_class(1, 5))};
}

// A certificate from bouncer's own checks (the maker's side), for the Henon horseshoe.
ChaosCertificate henon_certificate() {
  const std::vector<HSet2> sets = henon_sets();
  const HorseshoeResult r = check_horseshoe(henon, sets, 1);
  ChaosCertificate c;
  c.map = ChaosMap::henon;
  c.henon_a = *Decimal::parse("6");
  c.henon_b = *Decimal::parse("0.3");
  c.k = 1;
  c.bits = kBits;
  c.sets = sets;
  for (int i = 0; i < 2; ++i)
    for (int j = 0; j < 2; ++j)
      if (r.coverings[i][j].proved) c.coverings.push_back({i, j, r.coverings[i][j].sign, r.coverings[i][j].pieces, ""});
  c.entropy_bound = r.entropy.bound;
  c.quotient = r.entropy.quotient;
  c.made_by = "test_chaos_certificate";
  return c;
}

bool mentions(const ReplayResult& r, const std::string& what) {
  for (const std::string& p : r.problems)
    if (p.find(what) != std::string::npos) return true;
  return false;
}

std::string all_problems(const ReplayResult& r) {
  std::string s;
  for (const std::string& p : r.problems) s += p + "\n";
  return s;
}

// Case 1.
TEST(ChaosCertificate, HenonHorseshoeReplaysInArb) {
  const ChaosCertificate c = henon_certificate();
  ASSERT_EQ(c.coverings.size(), 4u);
  const ReplayResult r = replay_certificate(c);
  EXPECT_TRUE(r.valid) << all_problems(r);
  EXPECT_TRUE(r.disjoint);
  EXPECT_TRUE(r.bound_holds);
  for (const ReplayedCovering& v : r.coverings) EXPECT_TRUE(v.proved) << v.message;
  // The stated bound: at most log 2, within 1e-12 of it.
  const double bound = std::stod(c.entropy_bound);
  EXPECT_LE(bound, std::log(2.0) + 1e-15);
  EXPECT_GT(bound, std::log(2.0) - 1e-12);
}

// Case 2.
TEST(ChaosCertificate, MovedCornerIsRejected) {
  ChaosCertificate c = henon_certificate();
  // N_+'s centre moved right by 0.2: its left edge now maps to the right of N_- 's... the
  // image of its edges no longer lands outside the strips.
  c.sets[0].c[0] += mpq_class(1, 5);
  const ReplayResult r = replay_certificate(c);
  EXPECT_FALSE(r.valid);
  EXPECT_TRUE(mentions(r, "not proved")) << all_problems(r);
}

TEST(ChaosCertificate, RemovedCoveringIsRejected) {
  ChaosCertificate c = henon_certificate();
  c.coverings.pop_back();  // rho of what is left: the golden mean, below the stated 2
  const ReplayResult r = replay_certificate(c);
  EXPECT_FALSE(r.valid);
  EXPECT_TRUE(mentions(r, "above the spectral radius")) << all_problems(r);
  for (const ReplayedCovering& v : r.coverings) EXPECT_TRUE(v.proved) << v.message;
}

TEST(ChaosCertificate, AddedFalseCoveringIsRejected) {
  ChaosCertificate c = henon_certificate();
  // A third strip far away (disjoint), claimed to be covered by N_+: H maps N_+ near x in
  // [-1.2, 1], nowhere near x = 5.
  c.sets.push_back(hset_rectangle(mpq_class(5), mpq_class(6), mpq_class(-1, 5), mpq_class(1, 5)));
  c.coverings.push_back({0, 2, 1, 4, ""});
  const ReplayResult r = replay_certificate(c);
  EXPECT_FALSE(r.valid);
  EXPECT_TRUE(r.disjoint);
  EXPECT_FALSE(r.coverings.back().proved);
  EXPECT_TRUE(mentions(r, "covering 0 => 2: not proved")) << all_problems(r);
}

TEST(ChaosCertificate, RaisedBoundIsRejected) {
  ChaosCertificate c = henon_certificate();
  c.entropy_bound = "0.6931471805599454";  // log 2 = 0.69314718055994530942... rounded up
  const ReplayResult r = replay_certificate(c);
  EXPECT_FALSE(r.valid);
  EXPECT_FALSE(r.bound_holds);
  c.quotient = 3;  // and a quotient above rho = 2
  EXPECT_TRUE(mentions(replay_certificate(c), "above the spectral radius"));
}

TEST(ChaosCertificate, OverlappingHSetsAreRejected) {
  ChaosCertificate c = henon_certificate();
  c.sets[1] = c.sets[0];
  c.sets[1].c[1] += mpq_class(1, 10);
  const ReplayResult r = replay_certificate(c);
  EXPECT_FALSE(r.valid);
  EXPECT_FALSE(r.disjoint);
  EXPECT_TRUE(mentions(r, "may intersect")) << all_problems(r);
}

// Case 3, through certificates of a map whose coverings all hold: the golden-mean graph
// (N_+ => N_+, N_+ => N_-, N_- => N_+) of the Henon horseshoe.
TEST(ChaosCertificate, SpectralRadiusTestIsExact) {
  ChaosCertificate c = henon_certificate();
  c.coverings.erase(std::remove_if(c.coverings.begin(), c.coverings.end(),
                                   [](const CertifiedCovering& v) { return v.from == 1 && v.to == 1; }),
                    c.coverings.end());
  ASSERT_EQ(c.coverings.size(), 3u);
  c.entropy_bound = "0.48";  // log(1.618) = 0.48119...
  for (const char* ok : {"1.618", "1.6180339887", "1.61803398874989484820"}) {
    c.quotient = dec(ok);
    EXPECT_TRUE(replay_certificate(c).valid) << ok;
  }
  for (const char* bad : {"1.6181", "1.6180339888", "1.61803398874989484821"}) {
    c.quotient = dec(bad);
    EXPECT_TRUE(mentions(replay_certificate(c), "above the spectral radius")) << bad;
  }
}

// Case 4.
TEST(ChaosCertificate, ReplayMapAgreesWithBouncersMap) {
  std::mt19937_64 rng(20261128);
  std::uniform_real_distribution<double> unit(0, 1);
  int compared = 0;
  for (const Law law : {Law::elastic, Law::constant, Law::veldep}) {
    ChaosCertificate c;
    c.map = ChaosMap::impact;
    c.model = test_support::spec(law, law == Law::veldep ? "27" : "24", law == Law::constant ? "0.7" : "1", "1000");
    c.k = 1;
    const Model<Mpfi> model = interval_model(c.model, 256);
    for (int i = 0; i < 60; ++i) {
      // theta in (0, 1), v from the wall's velocity up to 30 (flights of up to ~2 periods).
      const mpq_class theta(long(1 + 998 * unit(rng)), 1000);
      const mpq_class v = wall_velocity_exact(c.model.wall, theta) + mpq_class(long(1 + 30000 * unit(rng)), 1000);
      const auto mine = replay_iterate(c, theta, v, 256);
      State<Mpfi> s{enclose(theta, theta, 256), enclose(v, v, 256)};
      std::optional<State<Mpfi>> theirs;
      try {
        OrbitEnclosure orbit(model, s, EnclosureMethod::naive);
        const EnclosedStep step = orbit.step();
        if (step.event.kind == EventKind::impact) theirs = orbit.box();
      } catch (const Undecided&) {
      }
      // A sticking collapse is bouncer's (the replay refuses it); otherwise both decide.
      if (!theirs) continue;
      ASSERT_TRUE(mine.has_value()) << name(law) << " theta " << theta << " v " << v;
      const Mpfi* t[2] = {&theirs->theta, &theirs->v};
      for (int k = 0; k < 2; ++k) {
        mpq_class lo, hi;
        Mpfr l = t[k]->lower(), h = t[k]->upper();
        mpfr_get_q(lo.get_mpq_t(), l.get());
        mpfr_get_q(hi.get_mpq_t(), h.get());
        EXPECT_LE((*mine)[k][0], hi) << name(law) << " coordinate " << k << " theta " << theta << " v " << v;
        EXPECT_GE((*mine)[k][1], lo) << name(law) << " coordinate " << k << " theta " << theta << " v " << v;
        EXPECT_LT((*mine)[k][1] - (*mine)[k][0], mpq_class(1, 1000000000) / mpq_class("1000000000000000000000000000000"));
      }
      ++compared;
    }
  }
  EXPECT_GT(compared, 150);
}

TEST(ChaosCertificate, ReplayMapRefusesSticking) {
  // Constant eps = 0.5, a = 24: a start with a slow relative velocity just above the wall's
  // on the rising wall collapses (sticks) before the wall turns: bouncer's step sticks, and
  // the replay, which does not model sticking, refuses rather than mapping it as an impact.
  ChaosCertificate c;
  c.map = ChaosMap::impact;
  c.model = test_support::spec(Law::constant, "24", "0.5");
  EXPECT_FALSE(replay_iterate(c, mpq_class(1, 10), mpq_class(4) + mpq_class(1, 100)).has_value());
  EXPECT_TRUE(replay_iterate(c, mpq_class(1, 10), mpq_class(12)).has_value());
}

// Case 5.
HSet2 period2_hset() {
  HSet2 n;
  n.c = {dec("0.0905229578316182"), dec("10.85655768412576")};
  n.B = {{{dec("0.000013129"), dec("0.0000517543")}, {dec("-0.000999914"), dec("-0.00099866")}}};
  return n;
}

ChaosCertificate saddle_certificate(const HSet2& n) {
  ChaosCertificate c;
  c.map = ChaosMap::impact;
  c.model = test_support::spec(Law::veldep, "27", "1", "1000");
  c.k = 2;
  c.sets = {n};
  c.coverings = {{0, 0, -1, 1, "I1+0 I0+1"}};
  c.entropy_bound = "0";
  c.quotient = 1;
  return c;
}

TEST(ChaosCertificate, VeldepSaddleCoversItselfInTheReplay) {
  HSet2 n = period2_hset();
  for (int thin = 0; thin < 2; ++thin) {
    if (thin)
      for (int i = 0; i < 2; ++i) n.B[i][1] /= 1000;
    const ReplayResult r = replay_certificate(saddle_certificate(n));
    ASSERT_EQ(r.coverings.size(), 1u);
    EXPECT_TRUE(r.coverings[0].proved) << r.coverings[0].message;
    // One periodic orbit is no chaos: the certificate claims none, and is not valid.
    EXPECT_FALSE(r.valid);
    EXPECT_TRUE(mentions(r, "quotient is not above 1")) << all_problems(r);
  }
  // The wrong sign, or the frame's columns swapped: not a covering.
  ChaosCertificate c = saddle_certificate(period2_hset());
  c.coverings[0].sign = 1;
  EXPECT_FALSE(replay_certificate(c).coverings[0].proved);
  HSet2 swapped = period2_hset();
  std::swap(swapped.B[0][0], swapped.B[0][1]);
  std::swap(swapped.B[1][0], swapped.B[1][1]);
  EXPECT_FALSE(replay_certificate(saddle_certificate(swapped)).coverings[0].proved);
}

// Case 6.
TEST(ChaosCertificateFile, RoundTripIsExact) {
  ChaosCertificate c = henon_certificate();
  c.sets[0].B[0][1] = mpq_class(-7, 3);
  const ChaosCertificate back = parse_certificate(certificate_json(c));
  EXPECT_EQ(back.map, ChaosMap::henon);
  EXPECT_EQ(back.henon_a.value(), 6);
  EXPECT_EQ(back.henon_b.value(), mpq_class(3, 10));
  EXPECT_EQ(back.k, c.k);
  ASSERT_EQ(back.sets.size(), c.sets.size());
  for (std::size_t i = 0; i < c.sets.size(); ++i)
    for (int r = 0; r < 2; ++r) {
      EXPECT_EQ(back.sets[i].c[r], c.sets[i].c[r]);
      for (int col = 0; col < 2; ++col) EXPECT_EQ(back.sets[i].B[r][col], c.sets[i].B[r][col]);
    }
  ASSERT_EQ(back.coverings.size(), c.coverings.size());
  for (std::size_t i = 0; i < c.coverings.size(); ++i) {
    EXPECT_EQ(back.coverings[i].from, c.coverings[i].from);
    EXPECT_EQ(back.coverings[i].to, c.coverings[i].to);
    EXPECT_EQ(back.coverings[i].sign, c.coverings[i].sign);
    EXPECT_EQ(back.coverings[i].pieces, c.coverings[i].pieces);
  }
  EXPECT_EQ(back.entropy_bound, c.entropy_bound);
  EXPECT_EQ(back.quotient, c.quotient);
  // The model of an impact certificate, through the scene reader's checks.
  const ChaosCertificate s = parse_certificate(certificate_json(saddle_certificate(period2_hset())));
  EXPECT_EQ(s.model.law, Law::veldep);
  EXPECT_EQ(s.model.c.value(), 1000);
  EXPECT_EQ(s.model.a.value(), 27);
}

void expect_refused(const std::string& text, const std::string& field) {
  try {
    parse_certificate(text);
    ADD_FAILURE() << "accepted: " << text.substr(0, 200);
  } catch (const InputError& e) {
    EXPECT_EQ(e.field, field) << e.what();
  }
}

TEST(ChaosCertificateFile, HostileTextIsRefusedNamingTheField) {
  const std::string good = certificate_json(henon_certificate());
  const auto edit = [&](const std::string& from, const std::string& to) {
    std::string s = good;
    const auto at = s.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    return s.replace(at, from.size(), to);
  };
  expect_refused("", "certificate");
  expect_refused("[1, 2]", "certificate");
  expect_refused(good.substr(0, good.size() / 2), "certificate");
  expect_refused(edit("\"bouncer-chaos-certificate\"", "\"other\""), "format");
  expect_refused(edit("\"version\": 1", "\"version\": 2"), "version");
  expect_refused(edit("\"map\": \"henon\"", "\"map\": \"tent\""), "map");
  expect_refused(edit("\"k\": 1", "\"k\": 0"), "k");
  expect_refused(edit("\"k\": 1", "\"k\": 1e400"), "certificate");  // beyond double: not JSON to the parser
  expect_refused(edit("\"k\": 1", "\"k\": 99999999999999999999"), "k");
  expect_refused(edit("\"made_by\"", "\"run_this\": \"rm -rf /\", \"made_by\""), "run_this");
  expect_refused(edit("\"from\": 0", "\"from\": 7"), "coverings[0].from");
  const auto first_field = [&](const std::string& key, const std::string& to) {
    std::string s = good;
    const std::regex field("\"" + key + "\": -?[0-9]+");
    return std::regex_replace(s, field, "\"" + key + "\": " + to, std::regex_constants::format_first_only);
  };
  expect_refused(first_field("sign", "0"), "coverings[0].sign");
  expect_refused(first_field("pieces", "100000"), "coverings[0].pieces");
  // 4096 pieces per side is allowed alone, but one such covering is 4096^2 + 2 4096 > 2^24
  // evaluations of F: more work than a replay will do for a stranger's file.
  expect_refused(first_field("pieces", "4096"), "coverings");
  // hset_rectangle(3/20, 3/5, ...): the frame's first entry is (3/5 - 3/20)/2 = 9/40.
  expect_refused(edit("\"9/40\"", "\"3/0\""), "sets[0].frame[0][0]");
  expect_refused(edit("\"9/40\"", "\"0x10\""), "sets[0].frame[0][0]");
  expect_refused(edit("\"9/40\"", "\"" + std::string(5000, '7') + "\""), "sets[0].frame[0][0]");
  expect_refused(edit("\"quotient\": \"2\"", "\"quotient\": 2"), "entropy.quotient");
  expect_refused(edit("\"bound\": \"", "\"bound\": \"x"), "entropy.bound");
  // A singular frame, a repeated covering, a model out of range.
  expect_refused(edit("\"1/5\"", "\"0\""), "sets[0].frame");
  ChaosCertificate twice = henon_certificate();
  twice.coverings.push_back(twice.coverings[0]);
  expect_refused(certificate_json(twice), "coverings[4]");
  std::string m = certificate_json(saddle_certificate(period2_hset()));
  m.replace(m.find("\"1000\""), 6, "\"-1\"");
  expect_refused(m, "c");
}

}  // namespace
}  // namespace bouncer
