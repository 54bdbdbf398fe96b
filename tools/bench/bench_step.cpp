// bench_step: nanoseconds per impact-map step, for every scalar type and model, next to
// hand-written floors timed in the same run (issue 2, item 7).
//
//   floors  plain-double: the same algorithm as ImpactMap (same segment walk, same
//           formulas in the same order, same outputs) in plain doubles, no templates, no
//           three-valued predicates; checked bitwise against ImpactMap<double> first.
//           raw-mpfr: the same algorithm on mpfr_t, every temporary allocated once
//           (mpfr_init2 at start-up), the same MPFR calls in the same order; checked
//           bitwise against ImpactMap<Mpfr> first.
//           raw-mpfi: the same on mpfi_t, with ImpactMap<Mpfi>'s mpfi calls and its
//           three-valued decisions (false where ImpactMap throws Undecided); checked bitwise
//           (both interval ends, undecided at the same steps) against ImpactMap<Mpfi> first.
//   rows    ImpactMap<T> for double, long double, quad, DoubleInterval (interval:double, timed
//           against the plain-double floor), DoubleDouble (dd, against ImpactMap<double>:
//           its target is 10x the double step), Mpfr and Mpfi (against raw-mpfi) at several
//           precisions.
//           Each repetition starts at the model's initial condition; the state is reset
//           to it when an interval step is undecided or when v exceeds 1e4.
//
// Timing: thread CPU time (the machine is shared), floors and rows interleaved in rounds,
// paired ratios. Every step function is called, never inlined into the timing loop (as
// ImpactMap<T>::step, which lives in the library).
//
// Usage: bench_step [--quick] [--time SECONDS] [--reps N] [--model SUBSTRING]
//        bench_step --profile KIND [--model SUBSTRING] [--bits B] [--steps N]
// The floors implement the default model options (no --veldep-collapse)
// and must be kept in step with lib/include/bouncer/model/impact_map_impl.hpp: the bitwise
// checks at start-up (exit code 1 on a mismatch) say when they are not.
#include <mpfi.h>
#include <mpfr.h>
#include <unistd.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <fstream>
#include <functional>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <stdexcept>
#include <string_view>
#include <type_traits>
#include <vector>

#include "bench_record.hpp"
#include "bouncer/io/provenance.hpp"
#include "bouncer/model/impact_map.hpp"
#include "bouncer/model/spec.hpp"

using namespace bouncer;
using bench::fmt;


namespace {

// ---------------------------------------------------------------------------------------
// Models benchmarked
// ---------------------------------------------------------------------------------------

struct Case {
  std::string name;
  ModelSpec spec;
  InitialCondition ic;
};

Case make_case(const std::string& name, Law law, const char* a, const char* eps, const char* c,
               const char* theta, const char* v) {
  Case k;
  k.name = name;
  k.spec.law = law;
  k.spec.a = parse_decimal("a", a);
  k.spec.eps = parse_decimal("eps", eps);
  k.spec.c = parse_decimal("c", c);
  k.spec.wall = parse_wall("wall", "triangle");
  k.spec.downward = DownwardSticking::paper;
  validate(k.spec);
  k.ic.theta = parse_decimal("theta", theta);
  k.ic.v = parse_decimal("v", v);
  validate(k.spec, k.ic, "theta", "v");
  return k;
}

std::vector<Case> all_cases() {
  return {
      // Elastic: from (0.1, 5) v stays below ~1e3 over millions of steps (reset at 1e4 anyway).
      make_case("elastic a=19", Law::elastic, "19", "1", "1000", "0.1", "5"),
      // Period-3 orbit with one sticking event (collapse + release) every 3 steps.
      make_case("const e=.5 a=24.7", Law::constant, "24.7", "0.5", "1000", "0.1", "5"),
      // Long-period / chaotic-looking orbit without sticking.
      make_case("const e=.9 a=19", Law::constant, "19", "0.9", "1000", "0.05", "10"),
      make_case("veldep c=1000 a=25", Law::veldep, "25", "1", "1000", "0.1", "5"),
  };
}

constexpr double kVReset = 1e4;  // (the MPFR versions compare with the integer 10000)
inline bool vbig(double v) { return v > kVReset; }
inline bool vbig(long double v) { return v > kVReset; }
inline bool vbig(const Quad& v) { return v > kVReset; }
inline bool vbig(const DoubleDouble& v) { return v > DoubleDouble(kVReset); }
inline bool vbig(const Mpfr& v) { return mpfr_cmp_si(v.get(), 10000) > 0; }
inline bool vbig(const Mpfi& v) { return mpfr_cmp_si(&v.get()->right, 10000) > 0; }
inline bool vbig(const DoubleInterval& v) { return v.upper() > kVReset; }

// ---------------------------------------------------------------------------------------
// Floor 1: plain double
// ---------------------------------------------------------------------------------------

constexpr int kMaxSeg = 8;
constexpr long kWalkLimit = 1L << 24;

struct PlainModel {
  Law law;
  bool paper;  // DownwardSticking::paper
  double a, eps, c, collapse, top;
  int n;
  double start[kMaxSeg], end[kMaxSeg], height[kMaxSeg], vel[kMaxSeg];
  Turn turn[kMaxSeg];
};

// The floors and the experiment implement the default model options only.
template <class T>
void require_default_options(const Model<T>& m) {
  if (m.veldep_collapse) throw std::runtime_error("bench_step: --veldep-collapse is not implemented by the floors");
}

PlainModel plain_model(const Model<double>& m) {
  require_default_options(m);
  PlainModel p{};
  p.law = m.law;
  p.paper = m.downward == DownwardSticking::paper;
  p.a = m.a;
  p.eps = m.eps;
  p.c = m.c;
  p.collapse = m.collapse;
  p.top = m.wall.top;
  p.n = m.wall.segments();
  if (p.n > kMaxSeg) throw std::runtime_error("too many wall segments for the floor");
  for (int j = 0; j < p.n; ++j) {
    p.start[j] = m.wall.start[j];
    p.end[j] = m.wall.end[j];
    p.height[j] = m.wall.height[j];
    p.vel[j] = m.wall.velocity[j];
    p.turn[j] = m.wall.turn[j];
  }
  return p;
}

struct PlainResult {  // the fields of StepResult<double>, flattened
  double theta, v, tau;
  long long periods;
  int segment;
  EventKind kind;
  bool corner;
  Truth indirect;
  int stick_segment;
  bool passed_upward_turn;
  double stuck_theta, stuck_v;
  int phase_bits_lost;
};

struct PlainMap {
  PlainModel m;

  int segment_of(double theta) const {
    int j = m.n - 1;
    while (j > 0 && !(m.start[j] <= theta)) --j;
    return j;
  }
  double clamp(double x, double lo, double hi) const {
    if (x < lo) return lo;
    if (!(x < hi)) return std::nextafter(hi, -HUGE_VAL);
    return x;
  }
  double height_at(int j, double theta) const { return m.height[j] + m.vel[j] * (theta - m.start[j]); }
  int next(int j) const { return j + 1 == m.n ? 0 : j + 1; }

  // Left the collision zone: falling at the impact (v^- = u - q < 0), apex above the top.
  Truth left_zone(double theta0, double v0, int j0, double u, double q) const {
    if (!(u < q)) return Truth::no;
    const double f0 = height_at(j0, theta0);
    return 2 * m.a * (m.top - f0) < v0 * v0 ? Truth::yes : Truth::no;
  }
  void collide(PlainResult& r, int j, double theta, double speed) const {
    double out;
    switch (m.law) {
      case Law::elastic: out = speed; break;
      case Law::constant: out = m.eps * speed; break;
      default: out = std::exp(-std::pow(speed / m.c, 0.6)) * speed; break;
    }
    r.segment = j;
    r.v = m.vel[j] + out;
    if (m.law == Law::constant && out <= m.collapse * (m.end[j] - theta)) {
      if (r.kind != EventKind::sticking) {
        r.kind = EventKind::sticking;
        r.stick_segment = j;
        r.stuck_theta = theta;
        r.stuck_v = r.v;
      }
      ride(r, j, theta);
      return;
    }
    r.theta = theta;
  }

  void ride(PlainResult& r, int j, double pos) const {
    for (;;) {
      r.tau += m.end[j] - pos;
      const int k = next(j);
      if (k == 0) ++r.periods;
      r.segment = j;
      switch (m.turn[j]) {
        case Turn::down:
          r.theta = m.start[k];
          r.v = m.vel[j];
          return;
        case Turn::none:
          break;
        case Turn::up:
          r.passed_upward_turn = true;
          if (m.law == Law::constant && m.paper) break;
          r.corner = true;
          collide(r, k, m.start[k], m.vel[k] - m.vel[j]);
          return;
      }
      j = k;
      pos = m.start[k];
    }
  }

  // noinline everywhere below: ImpactMap<T>::step is compiled in the library and called,
  // never inlined into the caller's loop, so the floors and the experiment are called too.
  [[gnu::noinline]] PlainResult step(double theta0, double v0) const {
    PlainResult r;
    r.tau = 0;
    r.periods = 0;
    r.segment = 0;
    r.kind = EventKind::impact;
    r.corner = false;
    r.indirect = Truth::no;
    r.stick_segment = -1;
    r.passed_upward_turn = false;
    r.phase_bits_lost = 0;
    const double a = m.a;
    int j = segment_of(theta0);
    const int j0 = j;
    const double rel = v0 - m.vel[j];
    if (rel == 0) {
      r.kind = EventKind::ride;
      ride(r, j, theta0);
    } else {
      double pos = theta0, L = m.end[j] - theta0, G = 0, W = rel;
      bool on_wall = true, jumped = false, at_fall = false;
      for (long iter = 0;; ++iter) {
        if (iter > kWalkLimit) throw Undecided(Reason::walk_limit);
        double q, sigma;
        if (on_wall) {
          q = W;
          sigma = 2 * W / a;
        } else {
          double d = W * W + 2 * a * G;
          q = std::sqrt(d < 0 ? 0.0 : d);
          sigma = W < 0 ? 2 * G / (q - W) : (W + q) / a;
        }
        if (sigma < L) {
          r.tau += sigma;
          const double th = clamp(pos + sigma, m.start[j], m.end[j]);
          r.indirect = jumped ? Truth::yes : left_zone(theta0, v0, j0, m.vel[j], q);
          r.corner = at_fall && sigma == 0 && pos == m.start[j];
          collide(r, j, th, q);
          break;
        }
        const int k = next(j);
        r.tau += L;
        if (k == 0) ++r.periods;
        if (!(L < sigma)) {
          const double Wk = W - a * L + m.vel[j] - m.vel[k];
          if (Wk <= 0) {
            r.corner = true;
            r.indirect = jumped ? Truth::yes : left_zone(theta0, v0, j0, m.vel[k], -Wk);
            collide(r, k, m.start[k], -Wk);
            break;
          }
          G = 0;
          W = Wk;
          on_wall = true;
        } else {
          const double gap = on_wall ? a * (sigma - L) * L / 2 : a * (sigma - L) * (L + 2 * G / (a * sigma)) / 2;
          W = W - a * L + m.vel[j] - m.vel[k];
          G = gap < 0 ? 0.0 : gap;
          on_wall = false;
        }
        j = k;
        pos = m.start[k];
        at_fall = false;
        L = m.end[k] - m.start[k];
        if (!jumped && m.top < m.height[j] + G) {
          jumped = true;
          const double f0 = height_at(j0, theta0);
          const double d = v0 * v0 - 2 * a * (m.top - f0);
          const double root = std::sqrt(d < 0 ? 0.0 : d);
          const double tau_fall = (v0 + root) / a;
          const double x = theta0 + tau_fall;
          if (!std::isfinite(x)) throw Undecided(Reason::nonfinite);
          const double whole = std::floor(x);
          r.periods = whole > 9e18 ? static_cast<long long>(9e18) : static_cast<long long>(whole);
          int e;
          std::frexp(x, &e);
          r.phase_bits_lost = std::max(0, e);
          r.tau = tau_fall;
          pos = clamp(x - whole, 0.0, m.end[m.n - 1]);
          at_fall = true;
          j = segment_of(pos);
          L = m.end[j] - pos;
          const double g = m.top - height_at(j, pos);
          G = g < 0 ? 0.0 : g;
          W = -root - m.vel[j];
          on_wall = false;
        }
      }
    }
    if (!std::isfinite(r.theta) || !std::isfinite(r.v)) throw Undecided(Reason::nonfinite);
    return r;
  }
};

// ---------------------------------------------------------------------------------------
// Floor 2: raw MPFR, every temporary allocated once
// ---------------------------------------------------------------------------------------

struct RawResult {
  mpfr_t theta, v, tau, stuck_theta, stuck_v;
  long long periods;
  int segment;
  EventKind kind;
  bool corner;
  Truth indirect;
  int stick_segment;
  bool passed_upward_turn;
  int phase_bits_lost;
};

class RawMpfrMap {
 public:
  RawResult r;

  RawMpfrMap(const Model<Mpfr>& m, long bits) : bits_(bits) {
    require_default_options(m);
    law_ = m.law;
    paper_ = m.downward == DownwardSticking::paper;
    n_ = m.wall.segments();
    if (n_ > kMaxSeg) throw std::runtime_error("too many wall segments for the floor");
    mpfr_t* all[] = {&a_, &eps_, &c_, &collapse_, &top_, &zero_, &pos_, &L_, &G_, &W_, &q_, &sigma_,
                     &t1_, &t2_, &t3_, &th_, &speed_, &speed2_, &out_, &f0_, &root_, &tau_fall_,
                     &x_, &whole_, &r.theta, &r.v, &r.tau, &r.stuck_theta, &r.stuck_v};
    for (mpfr_t* p : all) mpfr_init2(*p, bits);
    for (int j = 0; j < n_; ++j) {
      mpfr_init2(start_[j], bits);
      mpfr_init2(end_[j], bits);
      mpfr_init2(height_[j], bits);
      mpfr_init2(vel_[j], bits);
      mpfr_set(start_[j], m.wall.start[j].get(), MPFR_RNDN);
      mpfr_set(end_[j], m.wall.end[j].get(), MPFR_RNDN);
      mpfr_set(height_[j], m.wall.height[j].get(), MPFR_RNDN);
      mpfr_set(vel_[j], m.wall.velocity[j].get(), MPFR_RNDN);
      turn_[j] = m.wall.turn[j];
    }
    mpfr_set(a_, m.a.get(), MPFR_RNDN);
    mpfr_set(eps_, m.eps.get(), MPFR_RNDN);
    mpfr_set(c_, m.c.get(), MPFR_RNDN);
    mpfr_set(collapse_, m.collapse.get(), MPFR_RNDN);
    mpfr_set(top_, m.wall.top.get(), MPFR_RNDN);
    mpfr_set_zero(zero_, 1);
  }
  RawMpfrMap(const RawMpfrMap&) = delete;
  RawMpfrMap& operator=(const RawMpfrMap&) = delete;
  ~RawMpfrMap() {
    mpfr_t* all[] = {&a_, &eps_, &c_, &collapse_, &top_, &zero_, &pos_, &L_, &G_, &W_, &q_, &sigma_,
                     &t1_, &t2_, &t3_, &th_, &speed_, &speed2_, &out_, &f0_, &root_, &tau_fall_,
                     &x_, &whole_, &r.theta, &r.v, &r.tau, &r.stuck_theta, &r.stuck_v};
    for (mpfr_t* p : all) mpfr_clear(*p);
    for (int j = 0; j < n_; ++j) {
      mpfr_clear(start_[j]);
      mpfr_clear(end_[j]);
      mpfr_clear(height_[j]);
      mpfr_clear(vel_[j]);
    }
  }
  long bits() const { return bits_; }

  // One step from (theta0, v0) into r. theta0 and v0 must not alias r.theta / r.v.
  [[gnu::noinline]] void step(mpfr_srcptr theta0, mpfr_srcptr v0) {
    constexpr mpfr_rnd_t N = MPFR_RNDN;
    r.periods = 0;
    r.segment = 0;
    r.kind = EventKind::impact;
    r.corner = false;
    r.indirect = Truth::no;
    r.stick_segment = -1;
    r.passed_upward_turn = false;
    r.phase_bits_lost = 0;
    mpfr_set_zero(r.tau, 1);
    int j = segment_of(theta0);
    const int j0 = j;
    mpfr_sub(W_, v0, vel_[j], N);  // rel
    if (mpfr_zero_p(W_)) {
      r.kind = EventKind::ride;
      ride(j, theta0);
    } else {
      mpfr_set(pos_, theta0, N);
      mpfr_sub(L_, end_[j], theta0, N);
      mpfr_set_zero(G_, 1);
      bool on_wall = true, jumped = false, at_fall = false;
      for (long iter = 0;; ++iter) {
        if (iter > kWalkLimit) throw Undecided(Reason::walk_limit);
        if (on_wall) {
          mpfr_set(q_, W_, N);
          mpfr_mul_si(t1_, W_, 2, N);
          mpfr_div(sigma_, t1_, a_, N);
        } else {
          mpfr_mul(t1_, W_, W_, N);
          mpfr_mul_si(t2_, a_, 2, N);
          mpfr_mul(t2_, t2_, G_, N);
          mpfr_add(t1_, t1_, t2_, N);
          if (mpfr_sgn(t1_) < 0) mpfr_set_zero(t1_, 1);
          mpfr_sqrt(q_, t1_, N);
          if (mpfr_sgn(W_) < 0) {
            mpfr_mul_si(t1_, G_, 2, N);
            mpfr_sub(t2_, q_, W_, N);
            mpfr_div(sigma_, t1_, t2_, N);
          } else {
            mpfr_add(t1_, W_, q_, N);
            mpfr_div(sigma_, t1_, a_, N);
          }
        }
        if (mpfr_less_p(sigma_, L_)) {
          mpfr_add(r.tau, r.tau, sigma_, N);
          mpfr_add(th_, pos_, sigma_, N);
          clamp(th_, start_[j], end_[j]);
          r.indirect = jumped ? Truth::yes : left_zone(theta0, v0, j0, vel_[j], q_);
          r.corner = at_fall && mpfr_zero_p(sigma_) && mpfr_equal_p(pos_, start_[j]);
          collide(j, th_, q_);
          break;
        }
        const int k = next(j);
        mpfr_add(r.tau, r.tau, L_, N);
        if (k == 0) ++r.periods;
        if (!mpfr_less_p(L_, sigma_)) {
          mpfr_mul(t1_, a_, L_, N);
          mpfr_sub(t3_, W_, t1_, N);  // Wk
          mpfr_add(t3_, t3_, vel_[j], N);
          mpfr_sub(t3_, t3_, vel_[k], N);
          if (mpfr_lessequal_p(t3_, zero_)) {
            r.corner = true;
            mpfr_neg(speed_, t3_, N);
            r.indirect = jumped ? Truth::yes : left_zone(theta0, v0, j0, vel_[k], speed_);
            collide(k, start_[k], speed_);
            break;
          }
          mpfr_set_zero(G_, 1);
          mpfr_swap(W_, t3_);
          on_wall = true;
        } else {
          mpfr_sub(t1_, sigma_, L_, N);
          mpfr_mul(t1_, a_, t1_, N);
          if (on_wall) {
            mpfr_mul(t1_, t1_, L_, N);
          } else {
            mpfr_mul_si(t2_, G_, 2, N);
            mpfr_mul(t3_, a_, sigma_, N);
            mpfr_div(t2_, t2_, t3_, N);
            mpfr_add(t2_, L_, t2_, N);
            mpfr_mul(t1_, t1_, t2_, N);
          }
          mpfr_div_si(t1_, t1_, 2, N);  // gap
          mpfr_mul(t2_, a_, L_, N);
          mpfr_sub(W_, W_, t2_, N);
          mpfr_add(W_, W_, vel_[j], N);
          mpfr_sub(W_, W_, vel_[k], N);
          if (mpfr_sgn(t1_) < 0) mpfr_set_zero(G_, 1); else mpfr_swap(G_, t1_);
          on_wall = false;
        }
        j = k;
        mpfr_set(pos_, start_[k], N);
        at_fall = false;
        mpfr_sub(L_, end_[k], start_[k], N);
        if (!jumped) {
          mpfr_add(t1_, height_[j], G_, N);
          if (mpfr_less_p(top_, t1_)) {
            jumped = true;
            height_at(f0_, j0, theta0);
            mpfr_mul(t1_, v0, v0, N);
            mpfr_mul_si(t2_, a_, 2, N);
            mpfr_sub(t3_, top_, f0_, N);
            mpfr_mul(t2_, t2_, t3_, N);
            mpfr_sub(t1_, t1_, t2_, N);
            if (mpfr_sgn(t1_) < 0) mpfr_set_zero(t1_, 1);
            mpfr_sqrt(root_, t1_, N);
            mpfr_add(t1_, v0, root_, N);
            mpfr_div(tau_fall_, t1_, a_, N);
            mpfr_add(x_, theta0, tau_fall_, N);
            if (!mpfr_number_p(x_)) throw Undecided(Reason::nonfinite);
            mpfr_floor(whole_, x_);
            const double d = mpfr_get_d(whole_, N);
            r.periods = d > 9e18 ? static_cast<long long>(9e18) : static_cast<long long>(d);
            r.phase_bits_lost = std::max(0, mpfr_zero_p(x_) ? 0 : static_cast<int>(mpfr_get_exp(x_)));
            mpfr_set(r.tau, tau_fall_, N);
            mpfr_sub(pos_, x_, whole_, N);
            clamp(pos_, zero_, end_[n_ - 1]);
            at_fall = true;
            j = segment_of(pos_);
            mpfr_sub(L_, end_[j], pos_, N);
            height_at(t1_, j, pos_);
            mpfr_sub(t1_, top_, t1_, N);
            if (mpfr_sgn(t1_) < 0) mpfr_set_zero(G_, 1); else mpfr_swap(G_, t1_);
            mpfr_neg(t2_, root_, N);
            mpfr_sub(W_, t2_, vel_[j], N);
            on_wall = false;
          }
        }
      }
    }
    if (!mpfr_number_p(r.theta) || !mpfr_number_p(r.v)) throw Undecided(Reason::nonfinite);
  }

 private:
  long bits_;
  Law law_;
  bool paper_;
  int n_;
  mpfr_t a_, eps_, c_, collapse_, top_, zero_;
  mpfr_t start_[kMaxSeg], end_[kMaxSeg], height_[kMaxSeg], vel_[kMaxSeg];
  Turn turn_[kMaxSeg];
  mpfr_t pos_, L_, G_, W_, q_, sigma_, t1_, t2_, t3_, th_, speed_, speed2_, out_, f0_, root_, tau_fall_, x_, whole_;

  int next(int j) const { return j + 1 == n_ ? 0 : j + 1; }
  int segment_of(mpfr_srcptr theta) const {
    for (int j = n_ - 1; j > 0; --j) {
      if (mpfr_nan_p(theta)) throw Undecided(Reason::nonfinite);
      if (mpfr_lessequal_p(start_[j], theta)) return j;
    }
    return 0;
  }
  // x := x restricted to [lo, hi) (as clamp_to_segment), in place.
  static void clamp(mpfr_ptr x, mpfr_srcptr lo, mpfr_srcptr hi) {
    if (mpfr_less_p(x, lo)) {
      mpfr_set(x, lo, MPFR_RNDN);
    } else if (!mpfr_less_p(x, hi)) {
      mpfr_set(x, hi, MPFR_RNDN);
      mpfr_nextbelow(x);
    }
  }
  void height_at(mpfr_ptr out, int j, mpfr_srcptr theta) const {
    mpfr_sub(out, theta, start_[j], MPFR_RNDN);
    mpfr_mul(out, vel_[j], out, MPFR_RNDN);
    mpfr_add(out, height_[j], out, MPFR_RNDN);
  }

  // Left the collision zone: falling at the impact (v^- = u - q < 0), apex above the top.
  Truth left_zone(mpfr_srcptr theta0, mpfr_srcptr v0, int j0, mpfr_srcptr u, mpfr_srcptr q) {
    constexpr mpfr_rnd_t N = MPFR_RNDN;
    if (!mpfr_less_p(u, q)) return Truth::no;
    height_at(f0_, j0, theta0);
    mpfr_mul_si(t1_, a_, 2, N);
    mpfr_sub(t2_, top_, f0_, N);
    mpfr_mul(t1_, t1_, t2_, N);
    mpfr_mul(t2_, v0, v0, N);
    return mpfr_less_p(t1_, t2_) ? Truth::yes : Truth::no;
  }
  void collide(int j, mpfr_srcptr theta, mpfr_srcptr speed) {
    constexpr mpfr_rnd_t N = MPFR_RNDN;
    mpfr_srcptr out = out_;
    switch (law_) {
      case Law::elastic: out = speed; break;
      case Law::constant: mpfr_mul(out_, eps_, speed, N); break;
      case Law::veldep:
        mpfr_div(out_, speed, c_, N);
        mpfr_pow_ui(out_, out_, 3, N);
        mpfr_rootn_ui(out_, out_, 5, N);
        mpfr_neg(out_, out_, N);
        mpfr_exp(out_, out_, N);
        mpfr_mul(out_, out_, speed, N);
        break;
    }
    r.segment = j;
    mpfr_add(r.v, vel_[j], out, N);
    if (law_ == Law::constant) {
      mpfr_sub(t2_, end_[j], theta, N);
      mpfr_mul(t2_, collapse_, t2_, N);
      if (mpfr_lessequal_p(out, t2_)) {
        if (r.kind != EventKind::sticking) {
          r.kind = EventKind::sticking;
          r.stick_segment = j;
          mpfr_set(r.stuck_theta, theta, N);
          mpfr_set(r.stuck_v, r.v, N);
        }
        ride(j, theta);
        return;
      }
    }
    mpfr_set(r.theta, theta, N);
  }

  void ride(int j, mpfr_srcptr pos) {
    constexpr mpfr_rnd_t N = MPFR_RNDN;
    for (;;) {
      mpfr_sub(t1_, end_[j], pos, N);
      mpfr_add(r.tau, r.tau, t1_, N);
      const int k = next(j);
      if (k == 0) ++r.periods;
      r.segment = j;
      switch (turn_[j]) {
        case Turn::down:
          mpfr_set(r.theta, start_[k], N);
          mpfr_set(r.v, vel_[j], N);
          return;
        case Turn::none:
          break;
        case Turn::up:
          r.passed_upward_turn = true;
          if (law_ == Law::constant && paper_) break;
          r.corner = true;
          mpfr_sub(speed2_, vel_[k], vel_[j], N);
          collide(k, start_[k], speed2_);
          return;
      }
      j = k;
      pos = start_[k];
    }
  }
};

// ---------------------------------------------------------------------------------------
// Floor 3: raw MPFI, every temporary allocated once
// ---------------------------------------------------------------------------------------
//
// ImpactMap<Mpfi>'s step written against mpfi_t: the same mpfi_* calls on the same operands
// in the same order (so every interval end comes out bit for bit the same), the same
// three-valued decisions, and an undecided branch returns false where ImpactMap throws
// Undecided. What it leaves out is what the wrapper adds: value-returning temporaries,
// copies, out-of-line predicates, exceptions. Where the library gets a value by a detour
// that cannot change its bits, the floor takes the direct way and says so (hull of two
// constants precomputed, nonneg in place, floor_certain without Mpfr copies).

struct RawIntervalResult {
  mpfi_t theta, v, tau, stuck_theta, stuck_v;
  int knot;  // State::knot of the result (-1: not exactly at a knot)
  long long periods;
  int segment;
  EventKind kind;
  bool corner;
  Truth indirect;
  int stick_segment;
  bool passed_upward_turn;
  int phase_bits_lost;
};

// The three-valued predicates of ScalarTraits<Mpfi> (lib/src/scalar/scalar.cpp), inline.
inline bool nan_p(mpfi_srcptr x) { return mpfr_nan_p(&x->left) || mpfr_nan_p(&x->right); }
inline Truth lt(mpfi_srcptr x, mpfi_srcptr y) {
  if (nan_p(x) || nan_p(y)) return Truth::invalid;
  if (mpfr_less_p(&x->right, &y->left)) return Truth::yes;
  if (mpfr_greaterequal_p(&x->left, &y->right)) return Truth::no;
  return Truth::unknown;
}
inline Truth le(mpfi_srcptr x, mpfi_srcptr y) {
  if (nan_p(x) || nan_p(y)) return Truth::invalid;
  if (mpfr_lessequal_p(&x->right, &y->left)) return Truth::yes;
  if (mpfr_greater_p(&x->left, &y->right)) return Truth::no;
  return Truth::unknown;
}
inline Truth is_zero(mpfi_srcptr x) {
  if (nan_p(x)) return Truth::invalid;
  if (mpfr_zero_p(&x->left) && mpfr_zero_p(&x->right)) return Truth::yes;
  if (mpfr_sgn(&x->left) > 0 || mpfr_sgn(&x->right) < 0) return Truth::no;  // !mpfi_has_zero
  return Truth::unknown;
}
// intersect of scalar/mpfi.hpp: mpfi_intersect, an empty result made NaN.
inline void intersect(mpfi_ptr r, mpfi_srcptr x, mpfi_srcptr y) {
  mpfi_intersect(r, x, y);
  if (mpfi_is_empty(r)) {
    mpfr_set_nan(&r->left);
    mpfr_set_nan(&r->right);
  }
}
// Where ImpactMap's decide() would throw.
inline bool open(Truth t) { return t != Truth::yes && t != Truth::no; }
inline Truth both(Truth x, Truth y) {  // detail::both of impact_map_impl.hpp
  if (x == Truth::no || y == Truth::no) return Truth::no;
  if (x == Truth::yes && y == Truth::yes) return Truth::yes;
  return Truth::unknown;
}
inline bool finite(mpfi_srcptr x) { return mpfr_number_p(&x->left) && mpfr_number_p(&x->right); }

class RawMpfiMap {
 public:
  RawIntervalResult r;

  RawMpfiMap(const Model<Mpfi>& m, long bits) : bits_(bits) {
    require_default_options(m);
    law_ = m.law;
    paper_ = m.downward == DownwardSticking::paper;
    n_ = m.wall.segments();
    if (n_ > kMaxSeg) throw std::runtime_error("too many wall segments for the floor");
    for (mpfi_t* p : intervals()) mpfi_init2(*p, bits);
    for (mpfr_t* p : {&mid_, &fr_zero_, &floor_lo_, &floor_hi_}) mpfr_init2(*p, bits);
    for (int j = 0; j < n_; ++j) {
      for (mpfi_t* p : {&start_[j], &end_[j], &height_[j], &vel_[j], &span_[j]}) mpfi_init2(*p, bits);
      mpfi_set(start_[j], m.wall.start[j].get());
      mpfi_set(end_[j], m.wall.end[j].get());
      mpfi_set(height_[j], m.wall.height[j].get());
      mpfi_set(vel_[j], m.wall.velocity[j].get());
      mpfi_union(span_[j], start_[j], end_[j]);  // hull(start, end) of the phase clamp
      turn_[j] = m.wall.turn[j];
    }
    mpfi_set(a_, m.a.get());
    mpfi_set(eps_, m.eps.get());
    mpfi_set(c_, m.c.get());
    mpfi_set(collapse_, m.collapse.get());
    mpfi_set(top_, m.wall.top.get());
    mpfi_set_si(zero_, 0);
    mpfr_set_si(fr_zero_, 0, MPFR_RNDN);
    mpfi_union(phase_span_, zero_, end_[n_ - 1]);  // hull(0, 1) of the clamp after a jump
    mpfi_set_si(three_fifths_, 3);                 // Mpfi(3, bits) / 5 of pow_3_5
    mpfi_div_si(three_fifths_, three_fifths_, 5);
    mpfi_set_si(longest_walk_, 64);                // detail::kLongestWalkedFlight
  }
  RawMpfiMap(const RawMpfiMap&) = delete;
  RawMpfiMap& operator=(const RawMpfiMap&) = delete;
  ~RawMpfiMap() {
    for (mpfi_t* p : intervals()) mpfi_clear(*p);
    for (mpfr_t* p : {&mid_, &fr_zero_, &floor_lo_, &floor_hi_}) mpfr_clear(*p);
    for (int j = 0; j < n_; ++j)
      for (mpfi_t* p : {&start_[j], &end_[j], &height_[j], &vel_[j], &span_[j]}) mpfi_clear(*p);
  }
  long bits() const { return bits_; }

  // One step from (theta0, v0) with State::knot knot0 into r; false where ImpactMap<Mpfi>
  // throws Undecided. theta0 and v0 must not alias r.theta / r.v.
  [[gnu::noinline]] bool step(mpfi_srcptr theta0, mpfi_srcptr v0, int knot0) {
    r.knot = -1;
    r.periods = 0;
    r.segment = 0;
    r.kind = EventKind::impact;
    r.corner = false;
    r.indirect = Truth::no;
    r.stick_segment = -1;
    r.passed_upward_turn = false;
    r.phase_bits_lost = 0;
    mpfi_set(r.tau, zero_);
    int j = knot0;
    if (knot0 < 0) {
      j = segment_of(theta0);
      if (j < 0 || open(lt(theta0, end_[j]))) return false;
    }
    const int j0 = j;
    mpfi_sub(W_, v0, vel_[j]);
    const Truth riding = is_zero(W_);
    if (open(riding)) return false;
    bool done;
    if (riding == Truth::yes) {
      r.kind = EventKind::ride;
      done = ride(j, theta0);
    } else {
      mpfi_srcptr pos = theta0;  // phase at which the current piece begins (fall_ after a jump)
      mpfi_sub(L_, end_[j], theta0);
      mpfi_set(G_, zero_);
      bool on_wall = true, jumped = false;
      for (long iter = 0;; ++iter) {
        if (iter > kWalkLimit) return false;
        if (on_wall) {
          mpfi_add(t1_, W_, W_);
          mpfi_div(sigma_, t1_, a_);
        } else {
          mpfi_mul(t1_, W_, W_);
          mpfi_mul_si(t2_, a_, 2);
          mpfi_mul(t2_, t2_, G_);
          mpfi_add(q_, t1_, t2_);
          nonneg(q_);
          mpfi_sqrt(q_, q_);
          mpfi_mid(mid_, W_);  // likely_negative: picks one of two equal formulas
          if (mpfr_sgn(mid_) < 0) {
            mpfi_mul_si(t1_, G_, 2);
            mpfi_sub(t2_, q_, W_);
            mpfi_div(sigma_, t1_, t2_);
          } else {
            mpfi_add(t1_, W_, q_);
            mpfi_div(sigma_, t1_, a_);
          }
        }
        mpfi_srcptr q = on_wall ? W_ : q_;
        const Truth inside = lt(sigma_, L_);
        if (open(inside)) return false;
        if (inside == Truth::yes) {
          mpfi_add(r.tau, r.tau, sigma_);
          mpfi_add(th_, pos, sigma_);
          intersect(th_, th_, span_[j]);
          r.indirect = jumped ? Truth::yes : left_zone(theta0, v0, j0, vel_[j], q);
          r.corner = pos == fall_ && is_zero(sigma_) == Truth::yes &&
                     (mpfi_sub(t1_, fall_, start_[j]), is_zero(t1_) == Truth::yes);
          done = collide(j, th_, q, -1);
          break;
        }
        const int k = next(j);
        mpfi_add(r.tau, r.tau, L_);
        if (k == 0) ++r.periods;
        const Truth before = lt(L_, sigma_);
        if (open(before)) return false;
        if (before == Truth::no) {
          mpfi_mul(t1_, a_, L_);
          mpfi_sub(W_, W_, t1_);
          mpfi_add(W_, W_, vel_[j]);
          mpfi_sub(W_, W_, vel_[k]);
          const Truth approach = le(W_, zero_);
          if (open(approach)) return false;
          if (approach == Truth::yes) {
            r.corner = true;
            mpfi_neg(speed_, W_);
            r.indirect = jumped ? Truth::yes : left_zone(theta0, v0, j0, vel_[k], speed_);
            done = collide(k, start_[k], speed_, k);
            break;
          }
          mpfi_set(G_, zero_);
          on_wall = true;
        } else {
          mpfi_sub(t1_, sigma_, L_);
          mpfi_mul(gap_, a_, t1_);
          if (on_wall) {
            mpfi_mul(gap_, gap_, L_);
          } else {
            mpfi_mul_si(t1_, G_, 2);
            mpfi_mul(t2_, a_, sigma_);
            mpfi_div(t1_, t1_, t2_);
            mpfi_add(t1_, L_, t1_);
            mpfi_mul(gap_, gap_, t1_);
          }
          mpfi_div_si(gap_, gap_, 2);
          mpfi_mul(t1_, a_, L_);
          mpfi_sub(W_, W_, t1_);
          mpfi_add(W_, W_, vel_[j]);
          mpfi_sub(W_, W_, vel_[k]);
          nonneg(gap_);
          mpfi_swap(G_, gap_);
          on_wall = false;
        }
        j = k;
        pos = start_[k];
        mpfi_sub(L_, end_[k], start_[k]);
        if (jumped) continue;
        mpfi_add(t1_, height_[j], G_);
        if (lt(top_, t1_) != Truth::yes) continue;
        // Above the top: the analytic jump to the fall back onto it (shortcut where certain).
        jumped = true;
        height_at(f0_, j0, theta0);
        mpfi_mul(t1_, v0, v0);
        mpfi_mul_si(t2_, a_, 2);
        mpfi_sub(t3_, top_, f0_);
        mpfi_mul(t2_, t2_, t3_);
        mpfi_sub(root_, t1_, t2_);
        nonneg(root_);
        mpfi_sqrt(root_, root_);
        mpfi_add(t1_, v0, root_);
        mpfi_div(tau_fall_, t1_, a_);
        mpfi_add(x_, theta0, tau_fall_);
        // floor_certain: both ends have the same integer part (NaN: not equal, unknown).
        mpfr_floor(floor_lo_, &x_->left);
        mpfr_floor(floor_hi_, &x_->right);
        if (mpfr_equal_p(floor_lo_, floor_hi_)) {
          mpfi_interv_fr(whole_, floor_lo_, floor_lo_);
          mpfi_sub(fall_, x_, whole_);
          intersect(fall_, fall_, phase_span_);
          const int jf = segment_if_certain(fall_);
          if (jf >= 0) {
            // whole_periods: to_double of [w, w] is the double nearest w.
            const double d = mpfr_get_d(floor_lo_, MPFR_RNDN);
            r.periods = d > 9e18 ? static_cast<long long>(9e18) : static_cast<long long>(d);
            mpfi_abs(t1_, x_);
            r.phase_bits_lost =
                std::max(0, mpfr_zero_p(&t1_->right) ? 0 : static_cast<int>(mpfr_get_exp(&t1_->right)));
            mpfi_set(r.tau, tau_fall_);
            j = jf;
            pos = fall_;
            mpfi_sub(L_, end_[j], fall_);
            height_at(t1_, j, fall_);
            mpfi_sub(G_, top_, t1_);
            nonneg(G_);
            mpfi_neg(t2_, root_);
            mpfi_sub(W_, t2_, vel_[j]);
            on_wall = false;
            continue;
          }
        }
        if (lt(longest_walk_, tau_fall_) == Truth::yes) return false;
      }
    }
    return done && finite(r.theta) && finite(r.v);
  }

 private:
  long bits_;
  Law law_;
  bool paper_;
  int n_;
  mpfi_t a_, eps_, c_, collapse_, top_, zero_, phase_span_, three_fifths_, longest_walk_;
  mpfi_t start_[kMaxSeg], end_[kMaxSeg], height_[kMaxSeg], vel_[kMaxSeg], span_[kMaxSeg];
  Turn turn_[kMaxSeg];
  mpfi_t L_, G_, W_, q_, sigma_, gap_, t1_, t2_, t3_, th_, speed_, speed2_, out_, up_, f0_, root_, tau_fall_, x_,
      whole_, fall_;
  mpfr_t mid_, fr_zero_, floor_lo_, floor_hi_;

  std::vector<mpfi_t*> intervals() {
    return {&a_,    &eps_,  &c_,     &collapse_, &top_,   &zero_,  &phase_span_,   &three_fifths_, &longest_walk_,
            &L_,    &G_,    &W_,     &q_,        &sigma_, &gap_,   &t1_,           &t2_,           &t3_,
            &th_,   &speed_, &speed2_, &out_,    &up_,    &f0_,    &root_,         &tau_fall_,     &x_,
            &whole_, &fall_, &r.theta, &r.v,     &r.tau,  &r.stuck_theta, &r.stuck_v};
  }
  int next(int j) const { return j + 1 == n_ ? 0 : j + 1; }
  // Wall::segment_of, -1 where it is undecided.
  int segment_of(mpfi_srcptr theta) const {
    for (int j = n_ - 1; j > 0; --j) {
      const Truth t = le(start_[j], theta);
      if (t == Truth::yes) return j;
      if (t != Truth::no) return -1;
    }
    return 0;
  }
  int segment_if_certain(mpfi_srcptr theta) const {
    for (int j = n_ - 1; j >= 0; --j) {
      const Truth after_start = j == 0 ? Truth::yes : le(start_[j], theta);
      if (after_start == Truth::yes) return lt(theta, end_[j]) == Truth::yes ? j : -1;
      if (after_start != Truth::no) return -1;
    }
    return -1;
  }
  // ScalarTraits<Mpfi>::nonneg in place: [0, max(hi, 0)] when the lower end is negative
  // (mpfi_interv_fr also gives the upper end MPFI's -0 when it is zero).
  void nonneg(mpfi_ptr x) {
    if (mpfr_sgn(&x->left) >= 0) return;
    mpfi_interv_fr(x, fr_zero_, mpfr_sgn(&x->right) < 0 ? fr_zero_ : &x->right);
  }
  void height_at(mpfi_ptr out, int j, mpfi_srcptr theta) const {
    mpfi_sub(out, theta, start_[j]);
    mpfi_mul(out, vel_[j], out);
    mpfi_add(out, height_[j], out);
  }

  Truth left_zone(mpfi_srcptr theta0, mpfi_srcptr v0, int j0, mpfi_srcptr u, mpfi_srcptr q) {
    const Truth falling = lt(u, q);
    if (falling == Truth::no) return Truth::no;
    height_at(f0_, j0, theta0);
    mpfi_sub(f0_, top_, f0_);
    mpfi_mul(f0_, f0_, a_);
    mpfi_mul_si(t1_, f0_, 2);
    mpfi_mul(t2_, v0, v0);
    return both(lt(t1_, t2_), falling);
  }
  // ScalarTraits<Mpfi>::pow_3_5 of x, in place.
  void pow_3_5(mpfi_ptr x) {
    if (is_zero(x) == Truth::yes) return;
    nonneg(x);
    if (mpfr_zero_p(&x->left)) {  // [0, u]: [0, upper end of u^(3/5)]
      mpfi_interv_fr(up_, &x->right, &x->right);
      mpfi_log(up_, up_);
      mpfi_mul(up_, three_fifths_, up_);
      mpfi_exp(up_, up_);
      mpfi_interv_fr(x, fr_zero_, &up_->right);
      return;
    }
    mpfi_log(x, x);
    mpfi_mul(x, three_fifths_, x);
    mpfi_exp(x, x);
  }
  // false: undecided.
  bool collide(int j, mpfi_srcptr theta, mpfi_srcptr speed, int knot) {
    mpfi_srcptr out = out_;
    switch (law_) {
      case Law::elastic: out = speed; break;
      case Law::constant: mpfi_mul(out_, speed, eps_); break;
      case Law::veldep:
        mpfi_div(out_, speed, c_);
        pow_3_5(out_);
        mpfi_neg(out_, out_);
        mpfi_exp(out_, out_);
        mpfi_mul(out_, speed, out_);
        break;
    }
    r.segment = j;
    mpfi_add(r.v, vel_[j], out);
    if (law_ == Law::constant) {
      mpfi_sub(t2_, end_[j], theta);
      mpfi_mul(t2_, collapse_, t2_);
      const Truth sticks = le(out, t2_);
      if (open(sticks)) return false;
      if (sticks == Truth::yes) {
        if (r.kind != EventKind::sticking) {
          r.kind = EventKind::sticking;
          r.stick_segment = j;
          mpfi_set(r.stuck_theta, theta);
          mpfi_set(r.stuck_v, r.v);
        }
        return ride(j, theta);
      }
    }
    mpfi_set(r.theta, theta);
    r.knot = knot;
    return true;
  }

  bool ride(int j, mpfi_srcptr pos) {
    for (;;) {
      mpfi_sub(t1_, end_[j], pos);
      mpfi_add(r.tau, r.tau, t1_);
      const int k = next(j);
      if (k == 0) ++r.periods;
      r.segment = j;
      switch (turn_[j]) {
        case Turn::down:
          mpfi_set(r.theta, start_[k]);
          mpfi_set(r.v, vel_[j]);
          r.knot = k;
          return true;
        case Turn::none:
          break;
        case Turn::up:
          r.passed_upward_turn = true;
          if (law_ == Law::constant && paper_) break;
          r.corner = true;
          mpfi_sub(speed2_, vel_[k], vel_[j]);
          return collide(k, start_[k], speed2_, k);
      }
      j = k;
      pos = start_[k];
    }
  }
};


// ---------------------------------------------------------------------------------------
// Bitwise checks of the floors against ImpactMap
// ---------------------------------------------------------------------------------------

bool same_bits(double x, double y) { return std::bit_cast<std::uint64_t>(x) == std::bit_cast<std::uint64_t>(y); }
bool same_bits(mpfr_srcptr x, mpfr_srcptr y) {
  if (mpfr_get_prec(x) != mpfr_get_prec(y)) return false;
  if (mpfr_nan_p(x) || mpfr_nan_p(y)) return mpfr_nan_p(x) && mpfr_nan_p(y);
  return mpfr_equal_p(x, y) && mpfr_signbit(x) == mpfr_signbit(y);
}

template <class R, class S>
bool same_flags(const R& f, const StepResult<S>& t) {
  return f.periods == t.periods && f.segment == t.segment && f.kind == t.kind && f.corner == t.corner &&
         f.indirect == t.indirect && f.stick_segment == t.stick_segment &&
         f.passed_upward_turn == t.passed_upward_turn && f.phase_bits_lost == t.phase_bits_lost;
}

struct Check {
  long steps = 0;       // steps compared
  long stickings = 0;   // of which sticking
  long undecided = -1;  // of which undecided in both (interval checks only; -1: not counted)
  long first_bad = -1;  // first mismatching step (1-based), -1 if none
  std::string what;
};

std::string describe(const Check& c) {
  std::ostringstream o;
  if (c.first_bad < 0) {
    o << "MATCH (" << c.steps << " steps, " << c.stickings << " sticking";
    if (c.undecided >= 0) o << ", " << c.undecided << " undecided";
    o << ")";
  } else
    o << "MISMATCH at step " << c.first_bad << ": " << c.what;
  return o.str();
}

std::string mismatch_text(const std::string& map_theta, const std::string& other_theta) {
  std::ostringstream o;
  o << "ImpactMap theta " << map_theta << ", other theta " << other_theta;
  return o.str();
}

Check check_plain(const Case& k, long steps) {
  const Model<double> model = make_model<double>(k.spec, 53);
  const ImpactMap<double> map(model);
  const PlainMap plain{plain_model(model)};
  State<double> s = make_state<double>(k.ic, 53);
  Check c;
  for (long n = 1; n <= steps; ++n) {
    const StepResult<double> t = map.step(s);
    const PlainResult f = plain.step(s.theta, s.v);
    bool ok = same_flags(f, t) && same_bits(f.theta, t.next.theta) && same_bits(f.v, t.next.v) &&
              same_bits(f.tau, t.tau);
    if (t.kind == EventKind::sticking)
      ok = ok && same_bits(f.stuck_theta, t.stuck_theta) && same_bits(f.stuck_v, t.stuck_v);
    if (!ok) {
      c.first_bad = n;
      c.what = mismatch_text(ScalarTraits<double>::to_string(t.next.theta), ScalarTraits<double>::to_string(f.theta));
      return c;
    }
    c.steps = n;
    c.stickings += t.kind == EventKind::sticking;
    s = t.next;
    if (vbig(s.v)) s = make_state<double>(k.ic, 53);
  }
  return c;
}

Check check_raw(const Case& k, long bits, long steps) {
  const Model<Mpfr> model = make_model<Mpfr>(k.spec, bits);
  const ImpactMap<Mpfr> map(model);
  RawMpfrMap raw(model, bits);
  State<Mpfr> s = make_state<Mpfr>(k.ic, bits);
  Check c;
  for (long n = 1; n <= steps; ++n) {
    const StepResult<Mpfr> t = map.step(s);
    raw.step(s.theta.get(), s.v.get());
    const RawResult& f = raw.r;
    bool ok = same_flags(f, t) && same_bits(f.theta, t.next.theta.get()) && same_bits(f.v, t.next.v.get()) &&
              same_bits(f.tau, t.tau.get());
    if (t.kind == EventKind::sticking)
      ok = ok && same_bits(f.stuck_theta, t.stuck_theta.get()) && same_bits(f.stuck_v, t.stuck_v.get());
    if (!ok) {
      c.first_bad = n;
      c.what = mismatch_text(mpfr_to_string(t.next.theta.get(), MPFR_RNDN), mpfr_to_string(f.theta, MPFR_RNDN));
      return c;
    }
    c.steps = n;
    c.stickings += t.kind == EventKind::sticking;
    s = t.next;
    if (vbig(s.v)) s = make_state<Mpfr>(k.ic, bits);
  }
  return c;
}

std::string interval_text(mpfi_srcptr x) {
  std::string s = "[";  // appended piece by piece: "[" + temporary trips GCC 12's -Wrestrict
  s += mpfr_to_string(&x->left, MPFR_RNDD);
  s += ", ";
  s += mpfr_to_string(&x->right, MPFR_RNDU);
  s += ']';
  return s;
}
bool same_bits(mpfi_srcptr x, mpfi_srcptr y) { return same_bits(&x->left, &y->left) && same_bits(&x->right, &y->right); }

// ImpactMap<Mpfi> and the raw-MPFI floor from the same states: both undecided at the same
// steps (then both restart from the initial condition, as the runners do), otherwise every
// field equal, both ends of every interval bit for bit.
Check check_raw_mpfi(const Case& k, long bits, long steps) {
  const Model<Mpfi> model = make_model<Mpfi>(k.spec, bits);
  const ImpactMap<Mpfi> map(model);
  RawMpfiMap raw(model, bits);
  const State<Mpfi> start = make_state<Mpfi>(k.ic, bits);
  State<Mpfi> s = start;
  Check c;
  c.undecided = 0;
  for (long n = 1; n <= steps; ++n) {
    std::optional<StepResult<Mpfi>> t;
    try {
      t = map.step(s);
    } catch (const Undecided&) {
    }
    const bool decided = raw.step(s.theta.get(), s.v.get(), s.knot);
    const RawIntervalResult& f = raw.r;
    const char* bad = nullptr;
    if (decided != t.has_value()) bad = decided ? "undecided in ImpactMap only" : "undecided in the floor only";
    else if (t) {
      if (!same_bits(f.theta, t->next.theta.get())) bad = "theta";
      else if (!same_bits(f.v, t->next.v.get())) bad = "v";
      else if (!same_bits(f.tau, t->tau.get())) bad = "tau";
      else if (f.knot != t->next.knot || !same_flags(f, *t)) bad = "a discrete field";
      else if (t->kind == EventKind::sticking &&
               !(same_bits(f.stuck_theta, t->stuck_theta.get()) && same_bits(f.stuck_v, t->stuck_v.get())))
        bad = "stuck theta/v";
    }
    if (bad) {
      c.first_bad = n;
      c.what = std::string(bad) + "; from theta " + ScalarTraits<Mpfi>::to_string(s.theta) +
               (t ? "; " + mismatch_text(ScalarTraits<Mpfi>::to_string(t->next.theta), interval_text(f.theta)) : "");
      return c;
    }
    c.steps = n;
    if (!t) {
      ++c.undecided;
      s = start;
      continue;
    }
    c.stickings += t->kind == EventKind::sticking;
    s = t->next;
    if (vbig(s.v)) s = start;
  }
  return c;
}

// ---------------------------------------------------------------------------------------
// Runners: run n steps from the current state (resetting as described at the top)
// ---------------------------------------------------------------------------------------

// The state update of a runner. For IEEE types each field goes through a register on its
// own: gcc otherwise merges the copy of State<double> into one 16-byte load right after the
// step stored theta and v as two 8-byte stores, a store-forwarding stall (~10 cycles) that
// hit some maps and not others depending on how they write their result (seen with perf).
template <class T>
inline void take(T& dst, T& src) {
  if constexpr (std::is_same_v<T, double>) {
    T x = src;
    asm volatile("" : "+x"(x));
    dst = x;
  } else {
    dst = std::move(src);
  }
}

struct Runner {
  virtual ~Runner() = default;
  virtual void reset() = 0;
  virtual void run(long n) = 0;
  long resets = 0;
};

template <class T>
struct MapRunner : Runner {
  ImpactMap<T> map;
  State<T> start, s;
  MapRunner(const Case& k, long bits)
      : map(make_model<T>(k.spec, bits)), start(make_state<T>(k.ic, bits)), s(start) {}
  void reset() override { s = start; resets = 0; }
  void run(long n) override {
    long done = 0;
    while (done < n) {
      try {
        for (; done < n; ++done) {
          StepResult<T> r = map.step(s);
          take(s.theta, r.next.theta);
          take(s.v, r.next.v);
          s.knot = r.next.knot;
          if (vbig(s.v)) { s = start; ++resets; }
        }
      } catch (const Undecided&) {
        s = start;
        ++resets;
        ++done;
      }
    }
  }
};

struct PlainRunner : Runner {
  PlainMap map;
  double theta0, v0, theta, v;
  explicit PlainRunner(const Case& k) : map{plain_model(make_model<double>(k.spec, 53))} {
    const State<double> s = make_state<double>(k.ic, 53);
    theta0 = theta = s.theta;
    v0 = v = s.v;
  }
  void reset() override { theta = theta0; v = v0; resets = 0; }
  void run(long n) override {
    long done = 0;
    while (done < n) {
      try {
        for (; done < n; ++done) {
          PlainResult r = map.step(theta, v);
          take(theta, r.theta);
          take(v, r.v);
          if (vbig(v)) { theta = theta0; v = v0; ++resets; }
        }
      } catch (const Undecided&) {
        theta = theta0; v = v0;
        ++resets;
        ++done;
      }
    }
  }
};

struct RawRunner : Runner {
  RawMpfrMap map;
  mpfr_t theta0, v0, theta, v;
  RawRunner(const Case& k, long bits) : map(make_model<Mpfr>(k.spec, bits), bits) {
    const State<Mpfr> s = make_state<Mpfr>(k.ic, bits);
    for (mpfr_t* p : {&theta0, &v0, &theta, &v}) mpfr_init2(*p, bits);
    mpfr_set(theta0, s.theta.get(), MPFR_RNDN);
    mpfr_set(v0, s.v.get(), MPFR_RNDN);
    reset();
  }
  ~RawRunner() override { for (mpfr_t* p : {&theta0, &v0, &theta, &v}) mpfr_clear(*p); }
  void reset() override {
    mpfr_set(theta, theta0, MPFR_RNDN);
    mpfr_set(v, v0, MPFR_RNDN);
    resets = 0;
  }
  void restart() {
    mpfr_set(theta, theta0, MPFR_RNDN);
    mpfr_set(v, v0, MPFR_RNDN);
    ++resets;
  }
  void run(long n) override {
    long done = 0;
    while (done < n) {
      try {
        for (; done < n; ++done) {
          map.step(theta, v);
          mpfr_swap(theta, map.r.theta);
          mpfr_swap(v, map.r.v);
          if (vbig_raw()) restart();
        }
      } catch (const Undecided&) {
        restart();
        ++done;
      }
    }
  }
  bool vbig_raw() const { return mpfr_cmp_si(v, 10000) > 0; }
};

struct RawMpfiRunner : Runner {
  RawMpfiMap map;
  mpfi_t theta0, v0, theta, v;
  int knot = -1;
  RawMpfiRunner(const Case& k, long bits) : map(make_model<Mpfi>(k.spec, bits), bits) {
    const State<Mpfi> s = make_state<Mpfi>(k.ic, bits);
    for (mpfi_t* p : {&theta0, &v0, &theta, &v}) mpfi_init2(*p, bits);
    mpfi_set(theta0, s.theta.get());
    mpfi_set(v0, s.v.get());
    reset();
  }
  ~RawMpfiRunner() override { for (mpfi_t* p : {&theta0, &v0, &theta, &v}) mpfi_clear(*p); }
  void reset() override {
    restart();
    resets = 0;
  }
  void restart() {
    mpfi_set(theta, theta0);
    mpfi_set(v, v0);
    knot = -1;
    ++resets;
  }
  // As MapRunner<Mpfi>: an undecided step counts as a step and restarts.
  void run(long n) override {
    for (long done = 0; done < n; ++done) {
      if (!map.step(theta, v, knot)) {
        restart();
        continue;
      }
      mpfi_swap(theta, map.r.theta);
      mpfi_swap(v, map.r.v);
      knot = map.r.knot;
      if (mpfr_cmp_si(&v->right, 10000) > 0) restart();
    }
  }
};

// ---------------------------------------------------------------------------------------
// Timing
// ---------------------------------------------------------------------------------------

struct Timing {
  double median_ns = 0, min_ns = 0, max_ns = 0;  // thread CPU time per step over the repetitions
  double cpu_share = 0;      // CPU time / wall time (median repetition): < 1 means preempted
  long steps = 0;            // per repetition
  double resets_per_k = 0;   // resets per 1000 steps (median repetition)
  std::vector<double> ns;    // per repetition, in round order (for paired ratios)
};

using bench::thread_cpu_seconds;
double wall_seconds() {
  timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

// Steps for one repetition of about target_s seconds of CPU time.
long calibrate(Runner& r, double target_s) {
  long n = 8;
  double t = 0;
  for (;;) {
    r.reset();
    const double t0 = thread_cpu_seconds();
    r.run(n);
    t = thread_cpu_seconds() - t0;
    if (t >= target_s / 5 || n > (1L << 40)) break;
    n *= t < target_s / 100 ? 8 : 2;
  }
  return std::max(1L, static_cast<long>(n * (target_s / std::max(t, 1e-9))));
}

// Times a group of runners (a floor first, then the rows compared to it) in interleaved
// rounds: each round runs every runner once, so load changes on the shared machine hit the
// floor and its rows alike. Each repetition starts from the initial condition.
std::vector<Timing> measure_group(const std::vector<Runner*>& group, double target_s, int reps) {
  std::vector<Timing> out(group.size());
  std::vector<std::vector<std::pair<double, double>>> res(group.size());  // (ns, resets/k)
  std::vector<std::vector<double>> share(group.size());
  for (size_t i = 0; i < group.size(); ++i) out[i].steps = calibrate(*group[i], target_s);
  for (int k = 0; k < reps; ++k) {
    for (size_t i = 0; i < group.size(); ++i) {
      Runner& r = *group[i];
      r.reset();
      const double w0 = wall_seconds(), c0 = thread_cpu_seconds();
      r.run(out[i].steps);
      const double c = thread_cpu_seconds() - c0, w = wall_seconds() - w0;
      const double ns = c * 1e9 / out[i].steps;
      out[i].ns.push_back(ns);
      res[i].emplace_back(ns, 1000.0 * r.resets / out[i].steps);
      share[i].push_back(w > 0 ? c / w : 1);
    }
  }
  for (size_t i = 0; i < group.size(); ++i) {
    auto v = res[i];
    std::sort(v.begin(), v.end());
    out[i].median_ns = v[v.size() / 2].first;
    out[i].resets_per_k = v[v.size() / 2].second;
    out[i].min_ns = v.front().first;
    out[i].max_ns = v.back().first;
    std::sort(share[i].begin(), share[i].end());
    out[i].cpu_share = share[i][share[i].size() / 2];
  }
  return out;
}

// Median over rounds of (row time / floor time in the same round).
double paired_ratio(const Timing& row, const Timing& floor) {
  std::vector<double> q;
  for (size_t k = 0; k < row.ns.size() && k < floor.ns.size(); ++k) q.push_back(row.ns[k] / floor.ns[k]);
  std::sort(q.begin(), q.end());
  return q.empty() ? 0 : q[q.size() / 2];
}

// ---------------------------------------------------------------------------------------
// Output
// ---------------------------------------------------------------------------------------

struct Row {
  std::string model, scalar;
  long bits;
  Timing t;
  const Timing* floor = nullptr;  // null: this row is a floor
  std::string floor_name;
};

// The timing table: its columns (and text widths) in one place, for the text and the JSON.
bench::Table step_table() {
  bench::Table t;
  t.name = "step";
  t.title = "ns per impact-map step, ImpactMap<T> vs hand-written floors";
  t.columns = {"model", "scalar", "bits", "ns/step", "spread", "floor ns", "floor", "ratio", "cpu%", "resets/k"};
  t.widths = {-19, -15, 5, 10, 6, 10, -16, 7, 5, 8};
  return t;
}

// The sine wall's step (issue 27) against the triangle's, same model and scalar, same rounds:
// the price of the certified first root (a march of Taylor-bounded stretches, sin and cos per
// stretch) over the triangle's closed-form roots.
bench::Table sine_table() {
  bench::Table t = step_table();
  t.name = "sine";
  t.title = "ns per impact-map step, the sine wall against the triangle";
  return t;
}

// The sine wall twin of a triangle case: the same law and parameters, from (0.1, 8) (the
// triangle cases' (0.1, 5) lies inside the sine wall, whose velocity there is 5.08).
Case sine_case(Case k) {
  k.name += " sine";
  k.spec.wall = parse_wall("wall", "sine");
  k.ic.theta = parse_decimal("theta", "0.1");
  k.ic.v = parse_decimal("v", "8");
  validate(k.spec);
  validate(k.spec, k.ic, "theta", "v");
  return k;
}

void add_row(bench::Table& table, const Row& r) {
  const double spread = r.t.median_ns > 0 ? 100.0 * (r.t.max_ns - r.t.min_ns) / r.t.median_ns : 0;
  table.add_and_print({r.model, r.scalar, std::to_string(r.bits), fmt("%.1f", r.t.median_ns), fmt("%.0f%%", spread),
                       r.floor ? fmt("%.1f", r.floor->median_ns) : "-", r.floor ? r.floor_name : "(floor)",
                       r.floor ? fmt("%.2fx", paired_ratio(r.t, *r.floor)) : "-", fmt("%.0f%%", 100 * r.t.cpu_share),
                       fmt("%.3g", r.t.resets_per_k)});
}

struct Options {
  bool quick = false;
  bool check_only = false;  // --check: the bitwise floor checks, no timing (a ctest test)
  double time_s = 0.2;
  int reps = 5;
  std::string model_filter;
  std::string profile;  // run one runner only (for callgrind): plain|double|raw|mpfr|rawi|interval|idouble
  long bits = 113;
  long steps = 100000;
};

[[noreturn]] void usage(int code) {
  std::printf(
      "usage: bench_step [--quick | --check] [--time SECONDS] [--reps N] [--model SUBSTRING] [--json FILE]\n"
      "       bench_step --columns   (the table's columns as JSON; nothing is run)\n"
      "       bench_step --profile plain|double|raw|mpfr|rawi|interval|idouble [--model SUBSTRING] [--bits B] [--steps N]\n"
      "         (runs one runner N steps without timing, for valgrind --tool=callgrind;\n"
      "          raw = raw-MPFR floor, rawi = raw-MPFI floor, interval = ImpactMap<Mpfi>, idouble = ImpactMap<DoubleInterval>)\n"
      "  Times ImpactMap<T>::step for each model and scalar type next to hand-written floors\n"
      "  (plain double; raw MPFR and raw MPFI with preallocated temporaries), after checking\n"
      "  bitwise that the floors compute the same orbits (and, for MPFI, are undecided at the\n"
      "  same steps). --quick: a small subset, short runs (smoke test). --check: the --quick\n"
      "  checks only, no timing (registered with ctest as bench.step_floors_match).\n"
      "  --json FILE: also write the table and the run's provenance as JSON (tools/bench/record_tables.py).\n"
      "  Exit code 1 if a floor does not reproduce ImpactMap bitwise; timings are never checked.\n");
  std::exit(code);
}

Options parse_args(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) usage(2);
      return argv[++i];
    };
    if (a == "--quick") o.quick = true;
    else if (a == "--check") o.check_only = o.quick = true;
    else if (a == "--no-experiment") {}  // accepted for old command lines: there are no experiments now
    else if (a == "--time") o.time_s = std::atof(value().c_str());
    else if (a == "--reps") o.reps = std::atoi(value().c_str());
    else if (a == "--model") o.model_filter = value();
    else if (a == "--profile") o.profile = value();
    else if (a == "--bits") o.bits = std::atol(value().c_str());
    else if (a == "--steps") o.steps = std::atol(value().c_str());
    else if (a == "--help" || a == "-h") usage(0);
    else usage(2);
  }
  if (o.quick) {
    o.time_s = std::min(o.time_s, 0.02);
    o.reps = std::min(o.reps, 1);
  }
  if (!(o.time_s > 0) || o.reps < 1) usage(2);
  return o;
}

}  // namespace

int main(int argc, char** argv) {
  const bench::Run run = bench::Run::start("bench_step", argc, argv);
  bench::Table table = step_table();
  bench::Table sine_columns = sine_table();
  if (run.columns_only) return run.print_columns({&table, &sine_columns});
  const Options opt = parse_args(argc, argv);

  if (!opt.profile.empty()) {
    Case k = all_cases()[1];
    for (const Case& c : all_cases())
      if (!opt.model_filter.empty() && c.name.find(opt.model_filter) != std::string::npos) k = c;
    std::unique_ptr<Runner> r;
    if (opt.profile == "plain") r = std::make_unique<PlainRunner>(k);
    else if (opt.profile == "double") r = std::make_unique<MapRunner<double>>(k, 53);
    else if (opt.profile == "raw") r = std::make_unique<RawRunner>(k, opt.bits);
    else if (opt.profile == "mpfr") r = std::make_unique<MapRunner<Mpfr>>(k, opt.bits);
    else if (opt.profile == "interval") r = std::make_unique<MapRunner<Mpfi>>(k, opt.bits);
    else if (opt.profile == "idouble") r = std::make_unique<MapRunner<DoubleInterval>>(k, 53);
    else if (opt.profile == "rawi") r = std::make_unique<RawMpfiRunner>(k, opt.bits);
    else usage(2);
    r->reset();
    r->run(opt.steps);
    std::printf("%s %s bits %ld: %ld steps, %ld resets\n", k.name.c_str(), opt.profile.c_str(), opt.bits, opt.steps,
                r->resets);
    return 0;
  }
  std::printf("# bench_step: ns per impact-map step, ImpactMap<T> vs hand-written floors\n");
  run.print_provenance();
  std::printf("# libraries: %s\n", library_versions().c_str());
  std::printf("# timing: thread CPU time; %d rounds, each running the floor and its rows once for ~%.3g s each\n"
              "#   (same step count in every round, each run from the initial condition). ns/step = median over\n"
              "#   rounds, spread = (max-min)/median, ratio = median over rounds of row/floor in the same round,\n"
              "#   cpu%% = CPU/wall time (below 100%% the process was preempted).\n",
              opt.reps, opt.time_s);
  std::printf("# NOTE: the machine is shared (other people compile), so absolute ns vary from run to run;\n"
              "#   quote the ratios from one run, where a row and its floor were timed minutes apart.\n");
  std::printf("# resets/k: state resets per 1000 steps (undecided interval step, or v > 1e4).\n");
  table.notes.push_back("Thread CPU time; " + std::to_string(opt.reps) + " interleaved rounds of ~" + bench::fmt("%.3g", opt.time_s) +
                        " s per runner; ns/step: median over rounds; spread: (max - min) / median; ratio: median over "
                        "rounds of row / floor in the same round; cpu%: CPU / wall time (below 100% the process was "
                        "preempted); resets/k: state resets per 1000 steps (undecided interval step, or v > 1e4).");

  std::vector<Case> cases;
  for (Case& k : all_cases())
    if (opt.model_filter.empty() || k.name.find(opt.model_filter) != std::string::npos) cases.push_back(k);
  if (opt.quick && opt.model_filter.empty()) cases = {all_cases()[1]};  // the sticking model
  const std::vector<long> bit_list = opt.quick ? std::vector<long>{113} : std::vector<long>{53, 113, 256, 1024, 4096};

  // --- correctness of the floors -------------------------------------------------------
  bool all_ok = true;
  std::printf("#\n# floor checks (bitwise: theta, v, tau, stuck theta/v, periods, segment, kind, corner,\n"
              "#   indirect, sticking segment, upward turn, phase bits lost; for MPFI both ends of each\n"
              "#   interval, the knot, and undecided at the same steps):\n");
  for (const Case& k : (opt.quick ? all_cases() : cases)) {
    const Check c = check_plain(k, 1000);
    std::printf("#   %-19s plain-double vs ImpactMap<double>: %s\n", k.name.c_str(), describe(c).c_str());
    all_ok = all_ok && c.first_bad < 0;
    for (long bits : {53L, 256L, 4096L}) {
      if (opt.quick && bits != 256) continue;
      const Check r = check_raw(k, bits, 200);
      std::printf("#   %-19s raw-mpfr:%-4ld vs ImpactMap<Mpfr>:   %s\n", k.name.c_str(), bits, describe(r).c_str());
      all_ok = all_ok && r.first_bad < 0;
    }
    // The interval floor at the timed precisions and at 64 and 128 bits (inline limbs up to
    // 1024 bits in Mpfi; 4096 on the heap). Intervals widen until a step is undecided, so a
    // check sees undecided steps (both must agree on them) as well as decided ones.
    for (long bits : {53L, 64L, 113L, 128L, 256L, 1024L, 4096L}) {
      if (opt.quick && bits != 64 && bits != 128 && bits != 256) continue;
      const Check r = check_raw_mpfi(k, bits, opt.quick ? 1000 : 2000);
      std::printf("#   %-19s raw-mpfi:%-4ld vs ImpactMap<Mpfi>:   %s\n", k.name.c_str(), bits, describe(r).c_str());
      all_ok = all_ok && r.first_bad < 0;
    }
  }
  std::fflush(stdout);

  if (opt.check_only) {
    std::printf("# %s\n", all_ok ? "every floor reproduces ImpactMap bitwise" : "FAILED: a floor does not reproduce ImpactMap bitwise");
    return all_ok ? 0 : 1;
  }
  // --- timing --------------------------------------------------------------------------
  std::printf("#\n");
  table.print_header();
  for (const Case& k : cases) {
    {
      // Double family, timed in rounds with the plain-double floor.
      PlainRunner floor(k);
      MapRunner<double> d(k, 53);
      MapRunner<DoubleInterval> di(k, 53);  // the fast certified type, against the same floor
      MapRunner<DoubleDouble> dd(k, 106);   // double-word: its target is 10x the double step
      std::vector<Runner*> g{&floor, &d, &di, &dd};
      std::unique_ptr<MapRunner<long double>> ld;
      std::unique_ptr<MapRunner<Quad>> qd;
      if (!opt.quick) {
        ld = std::make_unique<MapRunner<long double>>(k, 64);
        qd = std::make_unique<MapRunner<Quad>>(k, 113);
        g.push_back(ld.get());
        g.push_back(qd.get());
      }
      const std::vector<Timing> t = measure_group(g, opt.time_s, opt.reps);
      add_row(table, {k.name, "plain", 53, t[0], nullptr, ""});
      add_row(table, {k.name, "double", 53, t[1], &t[0], "plain-double"});
      add_row(table, {k.name, "interval:double", 53, t[2], &t[0], "plain-double"});
      add_row(table, {k.name, "dd", 106, t[3], &t[1], "double"});
      size_t i = 4;
      if (!opt.quick) {
        add_row(table, {k.name, "long", 64, t[i++], &t[0], "plain-double"});
        add_row(table, {k.name, "quad", 113, t[i++], &t[0], "plain-double"});
      }
    }
    for (long bits : bit_list) {
      // Both floors and their rows in the same rounds.
      RawRunner floor(k, bits);
      MapRunner<Mpfr> m(k, bits);
      RawMpfiRunner ifloor(k, bits);
      MapRunner<Mpfi> i(k, bits);
      std::vector<Runner*> g{&floor, &m, &ifloor, &i};
      const std::vector<Timing> t = measure_group(g, opt.time_s, opt.reps);
      add_row(table, {k.name, "raw-mpfr", bits, t[0], nullptr, ""});
      add_row(table, {k.name, "mpfr", bits, t[1], &t[0], "raw-mpfr"});
      add_row(table, {k.name, "raw-mpfi", bits, t[2], nullptr, ""});
      add_row(table, {k.name, "interval", bits, t[3], &t[2], "raw-mpfi"});
    }
  }
  // --- the sine wall against the triangle ------------------------------------------------
  bench::Table sine = sine_table();
  std::printf("#\n");
  sine.print_header();
  for (const Case& k : cases) {
    const Case ks = sine_case(k);
    MapRunner<double> td(k, 53), sd(ks, 53);
    MapRunner<DoubleInterval> ti(k, 53), si(ks, 53);
    std::vector<Runner*> g{&td, &sd, &ti, &si};
    std::unique_ptr<MapRunner<Mpfr>> tm, sm;
    std::unique_ptr<MapRunner<Mpfi>> tn, sn;
    if (!opt.quick) {
      tm = std::make_unique<MapRunner<Mpfr>>(k, 128);
      sm = std::make_unique<MapRunner<Mpfr>>(ks, 128);
      tn = std::make_unique<MapRunner<Mpfi>>(k, 128);
      sn = std::make_unique<MapRunner<Mpfi>>(ks, 128);
      for (Runner* r : {static_cast<Runner*>(tm.get()), static_cast<Runner*>(sm.get()), static_cast<Runner*>(tn.get()),
                        static_cast<Runner*>(sn.get())})
        g.push_back(r);
    }
    const std::vector<Timing> t = measure_group(g, opt.time_s, opt.reps);
    add_row(sine, {ks.name, "double", 53, t[1], &t[0], "triangle"});
    add_row(sine, {ks.name, "interval:double", 53, t[3], &t[2], "triangle"});
    if (!opt.quick) {
      add_row(sine, {ks.name, "mpfr", 128, t[5], &t[4], "triangle"});
      add_row(sine, {ks.name, "interval", 128, t[7], &t[6], "triangle"});
    }
  }
  std::printf("# load average at end: %s\n", bench::read_first_line("/proc/loadavg").c_str());
  if (!run.finish({&table, &sine})) return 1;
  if (!all_ok) std::printf("# FAILED: a floor does not reproduce ImpactMap bitwise (see the checks above)\n");
  return all_ok ? 0 : 1;
}
