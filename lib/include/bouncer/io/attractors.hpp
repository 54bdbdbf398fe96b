// The outputs of `bouncer attractors` (run/attractors.hpp): the per-start CSV, the JSON
// summary, the picture of the basins coloured by attractor, and the readable text summary.
// The command adds the provenance and writes them (tools/cmd_attractors.cpp).
#pragma once

#include <string>

#include "bouncer/io/plot.hpp"
#include "bouncer/run/attractors.hpp"
#include "bouncer/run/attractors_sweep.hpp"

namespace bouncer {

// "period 3", "fixed point", "family of fixed points", "sticking cycle, k = 4",
// "chaotic set", "accelerator mode, Q = 3", ... (legends and summaries).
std::string attractor_title(const FoundAttractor& a);

// One row per start: theta,v,attractor,kind,period (attractor: the id, or "undecided" /
// "outside"; theta and v as the run's scalar prints them: they read back to the same value).
std::string attractors_csv(const AttractorsResult& r);

// The summary as JSON text (an object): the request, each attractor (kind, period, points,
// multipliers and their certificate, exponent, basin share +- its binomial standard error),
// the undecided starts, the work done.
std::string attractors_json(const AttractorsResult& r);

// The basins: one pixel per start (grid sampling; Halton points are painted on an
// nx x ny raster), coloured by attractor, the legend giving each one's share +- error.
ImageFigure attractors_figure(const AttractorsResult& r, Palette palette);

// A readable summary for a terminal (no provenance: the command adds it).
std::string attractors_text(const AttractorsResult& r);

// `attractors --vary`: one row per value and attractor chain present there
// (value,chain,kind,period,starts,fraction,fraction_stderr; chain "undecided" for the
// undecided starts); the summary (per chain its kind, period and share at every value, null
// where absent); the stacked basin shares against the parameter (one column per value, the
// chains' shares stacked from the bottom in chain order, undecided grey on top); the text.
// With the branches (AttractorsSweepResult::branches): the JSON adds per chain `branch` and
// `ends` (each appearance or disappearance, its explaining event, certified enclosure and
// sentence) and `branches`; the text a sentence per appearance or disappearance and each
// branch's events; the figure a dashed line at each explained a* of the chains in its legend.
std::string attractors_sweep_csv(const AttractorsSweepResult& r);
std::string attractors_sweep_json(const AttractorsSweepResult& r);
ImageFigure attractors_sweep_figure(const AttractorsSweepResult& r, Palette palette);
std::string attractors_sweep_text(const AttractorsSweepResult& r);

}  // namespace bouncer
