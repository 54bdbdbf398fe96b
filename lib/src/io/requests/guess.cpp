#include "bouncer/io/requests/guess.hpp"

#include <string>

namespace bouncer {

std::optional<InitialCondition> guess_from(const Options& o, const ModelSpec& spec) {
  if (!o.has("guess")) return std::nullopt;
  const auto& g = o.values.at("guess");
  if (g.size() != 2) throw InputError("guess", "takes two values theta,v (got " + std::to_string(g.size()) + ")");
  InitialCondition ic{parse_decimal("guess", g[0]), parse_decimal("guess", g[1])};
  validate(spec, ic, "guess", "guess");
  return ic;
}

}  // namespace bouncer
