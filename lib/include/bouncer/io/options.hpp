// Readers of the option groups that several commands share (ranges, grids, the classifier's
// window, one start, the precisions of point orbits, the exponent's and the periodic search's
// settings): each turns the texts of an Options map (scene + command line) into a typed value
// and throws InputError naming the option and its allowed range. One reader per group, used
// by the command line (tools/) and the Python module alike, so their ranges and defaults
// cannot drift apart. The model's own group is model_from (io/scene.hpp).
#pragma once

#include <string>
#include <utility>

#include "bouncer/analysis/classify.hpp"
#include "bouncer/analysis/lyapunov.hpp"
#include "bouncer/analysis/periodic.hpp"
#include "bouncer/io/scene.hpp"

namespace bouncer {

// "A:B" with two decimals, A < B (or A <= B when `allow_equal`).
std::pair<Decimal, Decimal> parse_range(const std::string& field, const std::string& text, bool allow_equal = false);

// "NxM" with 1 <= N, M <= limit.
std::pair<long, long> parse_grid(const std::string& field, const std::string& text, long limit);

// A flag (--certify, --carry): "true" or "false" (default false), else InputError.
bool flag_from(const Options& o, const std::string& key);

// The single initial condition (--theta, --v) of an orbit command, validated against the model.
InitialCondition start_from(const Options& o, const ModelSpec& spec);

// The classifier's window: transient, steps, max-period (<= steps/2), recheck-factor.
ClassifyOptions classify_options_from(const Options& o);

// The precision of a command that follows point orbits: an analysis scalar
// (scalar/scalar_set.hpp). point_precision: the picture commands' message;
// analysis_precision: the analysis commands' (names `command` and the certified commands).
Precision point_precision(const Options& o);
Precision analysis_precision(const Options& o, const std::string& command);

// A swept parameter needs no value of its own: the model is built at the range's start,
// parsed here first so that a bad range is blamed on --range, not on the parameter.
void default_to_range_start(Options& o, const std::string& vary);

// Both ends of a varied parameter's range (bifurcation, lyapunov --vary, continue,
// certify-periodic --a-range ...) must give a valid model; InputError names `field`.
void validate_range_ends(const ModelSpec& m, Parameter p, const std::string& field, const Decimal& lo, const Decimal& hi);

// `bouncer lyapunov` (one exponent): transient, steps, blocks.
LyapunovOptions lyapunov_options_from(const Options& o);
// `bouncer periodic`: the period (required, 1..100) and Newton's settings.
long periodic_period_from(const Options& o);
NewtonOptions periodic_newton_from(const Options& o);

}  // namespace bouncer
