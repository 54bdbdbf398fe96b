// Helpers shared by the GoogleTest suites (tests/test_*.cpp).
#pragma once

#include <string>

#include "bouncer/model/spec.hpp"

namespace bouncer::test_support {

// The validated model of law `law` with the triangle wall, from exact decimal texts: gravity
// a, restitution eps (read for Law::constant only) and c (Law::veldep's constant). Throws
// InputError as the command line would.
inline ModelSpec spec(Law law, const std::string& a, const std::string& eps = "1", const std::string& c = "1000") {
  ModelSpec m;
  m.law = law;
  m.a = parse_decimal("a", a);
  if (law == Law::constant) m.eps = parse_decimal("eps", eps);
  m.c = parse_decimal("c", c);
  m.wall = parse_wall("wall", "triangle");
  validate(m);
  return m;
}

}  // namespace bouncer::test_support
