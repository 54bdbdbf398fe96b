#include "bouncer/workflow/commands.hpp"

#include <array>

namespace bouncer {

namespace {

constexpr CommandKind C = CommandKind::computing;
constexpr CommandKind W = CommandKind::workflow;

constexpr std::array kCommands{
    CommandInfo{"orbit", "Iterate the impact map and print the orbit", C},
    CommandInfo{"certify-sticking", "Certified sticking period from the release state (1/2, 4), with precision escalation", C},
    CommandInfo{"certify-periodic", "Certified period-Q orbit (Krawczyk): existence, uniqueness, multipliers, stability", C},
    CommandInfo{"certify-chaos", "Certified chaos: a horseshoe of covering relations, h_top >= a bound, its certificate replayed in Arb", C},
    CommandInfo{"check-certificate", "Replay a chaos certificate with Arb, a second interval library; exit 0 if it proves its bound", W},
    CommandInfo{"sweep", "One orbit in every precision against a certified interval reference", C},
    CommandInfo{"audit", "Rerun a recorded result from its provenance; exit 0 if bit-identical", W},
    CommandInfo{"periodic", "Find a period-q orbit (Newton) and its stability multipliers", C},
    CommandInfo{"lyapunov", "Leading Lyapunov exponent per collision (AD tangent map)", C},
    CommandInfo{"classify", "Classify an orbit's long-term behaviour (attractor type)", C},
    CommandInfo{"bifurcation", "Bifurcation diagram: sweep a, eps or c; CSV, density PNG, JSON", C},
    CommandInfo{"portrait", "Phase portrait (theta, v) of several orbits; --polar for Fermi acceleration", C},
    CommandInfo{"basin", "Basins of attraction: classify a grid of initial conditions; CSV, PNG, JSON", C},
    CommandInfo{"attractors", "Every attractor at a parameter point: recurrences of many starts, basin shares, Krawczyk proofs; CSV, PNG, JSON", C},
    CommandInfo{"scan", "Parameter scan over (a, eps) or (a, c): solution types per point; CSV, PNG, JSON", C},
    CommandInfo{"merge", "Join the tiles of shard runs (--shard i/N) into PREFIX.csv/.png/.json", W},
    CommandInfo{"continue", "Continue a period-q orbit in a, eps or c; locate where its branch ends", C},
    CommandInfo{"trajectory", "Particle and wall heights against time from a state (theta, v), impacts and sticking marked", C},
    CommandInfo{"tongues",
                "Arnold tongues (fig. arnold): eq. 5 fixed-point curves in (a, eps), solid where the proved family fills (0, 1/2)", C},
    CommandInfo{"reproduce",
                "Redraw every figure and recheck every claim of the paper; write DIR/report.md, report.html, claims.json", W},
};

}  // namespace

std::span<const CommandInfo> command_table() { return kCommands; }

const CommandInfo* find_command(std::string_view name) {
  for (const CommandInfo& c : kCommands)
    if (c.name == name) return &c;
  return nullptr;
}

bool is_computing_command(std::string_view name) {
  const CommandInfo* c = find_command(name);
  return c && c->kind == CommandKind::computing;
}

}  // namespace bouncer
