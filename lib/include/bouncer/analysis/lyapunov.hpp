// Leading Lyapunov exponent per collision, through the AD tangent map (TangentMap), with
// renormalisation at every step, a transient, and an error estimate from blocks.
// Implemented in lib/src/analysis/lyapunov.cpp for double and Mpfr.
//
//   lambda = (1/M) sum_n log |J_n w_n|,   w_{n+1} = J_n w_n / |J_n w_n|,   |w_0| = 1,
// over the M measured steps after the transient. The M steps are cut into `blocks` equal
// blocks; `stderr` is the standard error of the block means (sd / sqrt(blocks)), which
// accounts for correlations shorter than a block.
//
// Special outcomes:
//   * a sticking (or ride) step in the measured window has J = 0: the release state does
//     not depend on the input, the map contracts the neighbourhood to a point, and
//     lambda = -inf (`contracted`, with the step in `note`);
//   * unbounded velocity growth (Fermi acceleration) is flagged with the fitted exponent
//     alpha of v ~ n^alpha; lambda is still reported but is a transient quantity;
//   * an undecided step (NaN/overflow, walk limit) stops the run: `undecided`.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "bouncer/model/model.hpp"
#include "bouncer/scalar/scalar_set.hpp"

namespace bouncer {

struct LyapunovOptions {
  long transient = 1000;  // steps discarded first
  long steps = 10000;     // steps measured
  long blocks = 20;       // for the error estimate (reduced when steps is small)
};

struct LyapunovResult {
  double lambda = 0;        // per collision; -inf when contracted
  double stderr_ = 0;       // standard error of the block means (NaN if < 2 blocks)
  long steps = 0;           // steps measured
  long blocks = 0;          // blocks used
  bool contracted = false;  // sticking/ride: J == 0 somewhere in the window
  bool unbounded = false;   // velocity grows without bound (see alpha)
  double alpha = 0;         // fitted v ~ n^alpha of the running maximum of v
  double v_max = 0;         // largest v seen in the window
  bool undecided = false;   // a step could not be completed
  std::string note;         // the reason for the special outcomes, one line
};

// With `end`, the state after the last step taken is stored there (after transient + steps
// steps, or where a contracting or undecided step stopped the run), so a caller can go on
// along the same orbit (the exponent curves classify it there).
template <class T>
LyapunovResult lyapunov(const Model<T>& model, State<T> start, const LyapunovOptions& opt, State<T>* end = nullptr);

// Growth exponent of the running maximum of v: least-squares slope of log(max v) against
// log n at logarithmically spaced n (the helper shared with classify).
double growth_exponent(const std::vector<std::pair<double, double>>& n_vmax);

// Instantiated in lib/src/analysis/lyapunov.cpp for the analysis scalars (scalar/scalar_set.hpp).
#define BOUNCER_X(T, kind) \
  extern template LyapunovResult lyapunov<T>(const Model<T>&, State<T>, const LyapunovOptions&, State<T>*);
BOUNCER_FOR_EACH_ANALYSIS_SCALAR(BOUNCER_X)
#undef BOUNCER_X

}  // namespace bouncer
