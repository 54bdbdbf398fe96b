// A separate CMake project that uses an installed bouncer through find_package(bouncer),
// with no C++ standard of its own (the target carries C++20). It prints one certified step
// of the eq. 5 fixed point (eps = 1/2, p = 1: a = 24, v* = 12) at 256 bits, and exits 0 only
// if the enclosure of the image contains the start (a fixed point) and is narrow.
// docs/guide/cmake.md shows this file.
#include <bouncer/model/impact_map.hpp>

#include <iostream>

int main() {
  using namespace bouncer;
  ModelSpec spec;  // exact decimals
  spec.law = Law::constant;
  spec.a = *Decimal::parse("24");
  spec.eps = *Decimal::parse("0.5");
  spec.wall = parse_wall("wall", "triangle");
  const ImpactMap<Mpfi> map(make_model<Mpfi>(spec, 256));  // intervals at 256 bits
  const State<Mpfi> start = make_state<Mpfi>({*Decimal::parse("0.25"), *Decimal::parse("12")}, 256);
  const StepResult<Mpfi> r = map.step(start);  // throws Undecided instead of guessing
  std::cout << "theta " << r.next.theta << "\nv     " << r.next.v << "\nevent " << name(r.kind) << "\n";
  const bool fixed = r.next.theta.contains(start.theta) && r.next.v.contains(start.v);
  const bool narrow = r.next.v.width().to_double() < 1e-70;
  return fixed && narrow ? 0 : 1;
}
