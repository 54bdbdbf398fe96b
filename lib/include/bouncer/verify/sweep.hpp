// Precision sweep: one orbit question in double, long double, double-double, quad and MPFR at
// 64 ... 4096 bits, each compared step by step with a certified interval reference.
//
// Reference: the orbit's certified enclosure (verify/enclosure.hpp, Lohner by default),
// escalated (64, 128, ... up to reference_max_bits) until it covers all N steps; if no
// precision of the schedule covers them, the best run's steps are used and the report says
// how far the reference reaches.
//
// A precision "leaves the certified enclosure" at the first step n where its state is
// farther than `tolerance` from the enclosure (max norm; theta measured on the circle), or
// its step is a different event (sticking vs impact), or it fails (NaN). With tolerance 0
// every rounded run would leave at step 1 (its own rounding of the inputs), so the sweep
// measures where the rounding errors, amplified by the dynamics, reach a fixed size; that
// step grows linearly with the bits at slope ln 2 / lambda (lambda: the Lyapunov exponent
// per step), which gives `implied_lyapunov`.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "bouncer/analysis/classify.hpp"
#include "bouncer/model/spec.hpp"
#include "bouncer/scalar/precision.hpp"
#include "bouncer/verify/enclosure.hpp"
#include "bouncer/verify/escalation.hpp"

namespace bouncer {

struct SweepQuestion {
  ModelSpec model;
  InitialCondition start;
  long long steps = 1000;
  double tolerance = 0x1p-20;  // ~ 9.5e-7
  EscalationSchedule reference{64, 16384};
  EnclosureMethod method = EnclosureMethod::lohner;
  std::vector<Precision> precisions;  // empty: the default list
  long max_period = 2000;             // longest period looked for in a run's final steps
  long classify_steps = 500;          // classify window for runs with neither sticking nor a period
};

// Every point type of the scalar set (scalar/scalar_set.hpp), those of variable precision at
// 64, 128, ..., 4096 bits: double, long, dd, quad, mpfr:64, 128, 256, 512, 1024, 2048, 4096.
std::vector<Precision> default_sweep_precisions();

struct SweepRow {
  std::string precision;                // Precision::text()
  long bits = 0;
  std::optional<long long> leaves_at;   // first step outside the enclosure (+ tolerance)
  std::string why;                      // how it left: distance, event, failure
  std::optional<long long> sticking_period;
  std::optional<long> attractor_period; // period of the final steps, when no sticking
  // Neither sticking nor a period: bouncer::classify over classify_steps more steps at this
  // precision (chaotic, quasiperiodic, unbounded, ...), with its evidence and exponent.
  std::optional<Classification> classification;
  std::string answer;                   // qualitative answer, one phrase
};

struct SweepReport {
  std::vector<SweepRow> rows;
  long reference_bits = 0;
  long long reference_steps = 0;        // steps covered by the reference
  std::string reference_status;         // "covers all N steps" or where it stopped
  std::string reference_answer;
  std::vector<Attempt> reference_attempts;
  std::optional<double> slope;          // steps per bit (least squares over rows that left)
  std::optional<double> implied_lyapunov;  // ln 2 / slope, per step
  double seconds = 0;
};

SweepReport precision_sweep(const SweepQuestion& q);

}  // namespace bouncer
