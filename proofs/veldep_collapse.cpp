// Proof: inelastic collapse in the velocity-dependent model (paper sec. II.B.6).
//
// Paper: with eps(w) = exp(-(w/c)^(3/5)) the time for infinitely many collisions is
// infinite, because prod_{j<=n} eps_j -> 1 (the relative speeds tend to 0, so eps_j -> 1),
// hence sum_n prod_j eps_j diverges: no sticking (no inelastic collapse) in this model.
//
// Refutation (by hand; see lib/include/bouncer/model/veldep_collapse.hpp). In the wall frame
// the relative speeds of a chatter sequence are w_{n+1} = w_n exp(-(w_n/c)^(3/5)) and the
// total time is T(w_0) = (2/a) sum_n w_n. With x_n = (w_n/c)^(3/5), 1/x_{n+1} >= 1/x_n + 3/5,
// so w_n <= c (1/x_0 + 3n/5)^(-5/3) and
//     T(w_0) <= B(w_0) = (2/a) [ w_0 + (5/2) c^(3/5) w_0^(2/5) ]  < infinity.
// The products prod_{j<n} eps_j = w_n/w_0 <= (c/w_0)(1/x_0 + 3n/5)^(-5/3) tend to 0: the
// paper's "products tend to 1" confuses eps_j -> 1 with the product of the eps_j -> 1.
// Consequence: a chatter that starts with relative speed w on a segment with more than
// B(w) time left collapses there (infinitely many impacts, finite time): the particle
// sticks, so sticking solutions DO exist in the velocity-dependent model.
//
// Computation (rigorous, MPFI): for concrete (w_0, c, a), the sequence w_n is iterated in
// interval arithmetic for N terms; every w_n is certified below the bound
// c(1/x_0 + 3n/5)^(-5/3); the partial sum S_N and the tail bound R_N = B-type bound applied
// at w_N give the certified enclosure T in (2/a)[S_N, S_N + R_N], certified below B(w_0).
#include <string>
#include <vector>

#include "bouncer/model/veldep_collapse.hpp"
#include "certificate.hpp"
#include "proof_util.hpp"

using namespace proofs;

namespace {

const char* const kClaim =
    "sec. II.B.6: for eps(w) = exp(-|w/c|^(3/5)) the time for an infinite number of collisions is infinite, since "
    "prod_j eps_j -> 1 and sum_n prod_{j<=n} eps_j diverges: no sticking solutions in the velocity-dependent model";
const char* const kMethod =
    "analytic comparison bound 1/x_{n+1} >= 1/x_n + 3/5 (x = (w/c)^(3/5)) and integral tail; MPFI iteration of "
    "w_{n+1} = w_n exp(-(w_n/c)^(3/5)) checking the per-term bound (every term up to n = 100, then every 97th; the time bound does not rest on it) and enclosing the total time";
const char* const kConclusion =
    "Velocity-dependent chatter collapses in finite time T(w) <= (2/a)(w + 2.5 c^(3/5) w^(2/5)); "
    "w_n <= c (1/x_0 + 3n/5)^(-5/3), so the products of the eps_j tend to 0, not 1.";

struct Case { const char* w0; const char* c; const char* a; };
const std::vector<Case> kCases = {{"1", "1000", "25"}, {"8", "1000", "25"}, {"0.5", "1", "25"}, {"3", "10", "19"}};

// One chatter sequence w_0, ..., w_N enclosed in MPFI, with the total time it takes.
struct Chatter {
  Case k;
  Mpfi w0, wN;           // first and N-th relative speed
  Mpfi T_lo, T_hi;       // T in [T_lo, T_hi]: the N terms plus the analytic tail
  Mpfi B;                // the closed-form bound B(w_0)
  Mpfi prod;             // prod_{j<N} eps_j = w_N / w_0
  long checked = 0;      // terms compared with the per-term bound
  bool certified = false;
};

// Iterates w_{n+1} = w_n exp(-(w_n/c)^(3/5)) for N terms in interval arithmetic, checking the
// per-term bound w_n <= c(1/x_0 + 3n/5)^(-5/3) (every term up to 100, then a sample), and
// encloses T = (2/a) sum_n w_n by the partial sum plus the tail bound
// sum_{n>=N} w_n <= w_N + (5/2) c^(3/5) w_N^(2/5) = (a/2) B(w_N). Certified when the sampled
// terms are below the bound, T <= B(w_0), and the product of the eps_j is <= 1/10.
Chatter enclose_chatter(const Case& k, long N, long bits) {
  Chatter r{k, dec(k.w0, bits), Mpfi(bits), Mpfi(bits), Mpfi(bits), Mpfi(bits), Mpfi(bits)};
  const Mpfi c = dec(k.c, bits), a = dec(k.a, bits);
  r.B = bouncer::collapse_time_upper_bound(r.w0, a, c);
  Mpfi w = r.w0, S(0, bits);
  bool below = true;
  for (long n = 0; n < N; ++n) {
    if (n % 97 == 0 || n < 100) {  // the per-term bound (every term up to 100, then a sample)
      const Mpfi bn = bouncer::chatter_speed_upper_bound(r.w0, c, n);
      if (!le(w, bn)) below = false;
      ++r.checked;
    }
    S += w;
    w = w * exp(-Tr::pow_3_5(w / c));
  }
  const Mpfi R = bouncer::collapse_time_upper_bound(w, a, c) * a / 2;
  r.wN = w;
  r.T_lo = 2 * S / a;
  r.T_hi = 2 * (S + R) / a;
  r.prod = w / r.w0;
  r.certified = below && le(r.T_hi, r.B) && !w.has_nan() && le(r.prod, Mpfi(1, bits) / 10);
  return r;
}

bool all_certified(const std::vector<Chatter>& runs) {
  for (const Chatter& r : runs)
    if (!r.certified) return false;
  return true;
}

// Refutes "infinite collapse time": every enclosed total time is finite and below the
// closed-form bound B(w_0), which holds for every w_0 by the comparison argument above; a
// chatter with more than B(w) time left on its segment therefore collapses (sticks).
void check_finite_collapse_time(SubClaim& sub, const std::vector<Chatter>& runs) {
  for (const Chatter& r : runs) {
    sub.evidence.push_back("w0=" + std::string(r.k.w0) + " c=" + r.k.c + " a=" + r.k.a + ": total collapse time T in [" +
                           Tr::lower_string(r.T_lo) + ", " + Tr::upper_string(r.T_hi) + "] <= B(w0) = " +
                           Tr::upper_string(r.B) + " (" + std::to_string(r.checked) +
                           " terms certified below c(1/x0+3n/5)^(-5/3); w_N in " + s(r.wN) + ")" +
                           (r.certified ? "" : " NOT CERTIFIED"));
  }
  if (all_certified(runs))
    sub.settle(Verdict::refuted,
               "the collapse completes in finite time: T(w) <= (2/a)[w + (5/2) c^(3/5) w^(2/5)] "
               "(bouncer::collapse_time_upper_bound); a chatter starting with relative speed w on a segment with more "
               "than that time left sticks, so sticking solutions exist in the velocity-dependent model");
}

// Refutes "prod_j eps_j -> 1": the product is w_N/w_0, which the comparison bound sends to 0;
// the enclosures show it small (<= 1/10) after N terms in every case.
void check_products_tend_to_zero(SubClaim& sub, const std::vector<Chatter>& runs, long N) {
  for (const Chatter& r : runs)
    sub.evidence.push_back("w0=" + std::string(r.k.w0) + " c=" + r.k.c + ": prod_{j<" + std::to_string(N) +
                           "} eps_j = w_N/w_0 in " + s(r.prod));
  if (all_certified(runs))
    sub.settle(Verdict::refuted,
               "prod_{j<n} eps_j = w_n/w_0 <= (c/w_0)(1/x_0 + 3n/5)^(-5/3) -> 0 (each eps_j -> 1, the products do not)");
}

}  // namespace

int main(int argc, char** argv) {
  Certificate cert("veldep_collapse", kClaim, kMethod, 128, argc, argv);
  const long N = cert.full() ? 500000 : 20000;
  cert.note("terms iterated per case: N = " + std::to_string(N));
  SubClaim& time = cert.add("collapse-time", "sum_i Delta t_i = (2/a)(v_0-4)[1 + sum_n prod_{j<=n} eps_j] diverges (infinite collapse time)");
  SubClaim& products = cert.add("products", "prod_{j=1}^n eps_j -> 1 as n -> infinity");

  // Enclose each case's chatter once; both sub-claims are read off the same enclosures.
  std::vector<Chatter> runs;
  for (const Case& k : kCases) runs.push_back(enclose_chatter(k, N, cert.bits()));
  check_finite_collapse_time(time, runs);
  check_products_tend_to_zero(products, runs, N);

  cert.conclude(Verdict::refuted, kConclusion);
  return cert.finish();
}
