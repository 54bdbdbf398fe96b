// `bouncer sweep`'s outputs, from the typed report of verify/sweep.hpp: the JSON document
// (PREFIX.json, --json), the text table, PREFIX.csv and the divergence figure (PREFIX.png).
#pragma once

#include <string>

#include "bouncer/io/plot.hpp"
#include "bouncer/io/provenance.hpp"
#include "bouncer/verify/sweep.hpp"

namespace bouncer {

// The JSON document: provenance, note, inputs, tolerance, the reference (method, bits,
// steps, status, answer, attempts), one row per precision, the slope and the implied
// Lyapunov exponent, seconds. One-space indent, ending in a newline.
std::string sweep_json(const SweepReport& rep, const SweepQuestion& q, const Provenance& p);

// The text table after the provenance lines: the reference, one line per precision
// (precision, bits, leaves_at or '-', answer) and the implied Lyapunov exponent.
std::string sweep_table(const SweepReport& rep, const SweepQuestion& q);

// PREFIX.csv: provenance lines, "# reference:" and "# implied_lyapunov:" lines, the header
// precision,bits,leaves_enclosure_at,answer and one row per precision (the answer quoted,
// RFC 4180).
std::string sweep_csv(const SweepReport& rep, const Provenance& p);

// The first step outside the certified enclosure against the bits (log2 axis), the rows that
// stay within it at the steps the reference covers, and the least-squares fit when there is
// a slope. Carries the provenance (Title, provenance) as PNG metadata.
Figure sweep_divergence_figure(const SweepReport& rep, const SweepQuestion& q, const Provenance& p);

}  // namespace bouncer
