// A separate CMake project that uses an installed bouncer through find_package(bouncer).
// Checks one step of the eq. 5 fixed point (eps = 1/2, p = 1: a = 24, v* = 12) at 256 bits.
#include <bouncer/model/impact_map.hpp>

#include <cstdio>

int main() {
  using namespace bouncer;
  ModelSpec spec;
  spec.law = Law::constant;
  spec.a = *Decimal::parse("24");
  spec.eps = *Decimal::parse("0.5");
  spec.wall = parse_wall("wall", "triangle");
  ImpactMap<Mpfr> map(make_model<Mpfr>(spec, 256));
  const State<Mpfr> s = make_state<Mpfr>({*Decimal::parse("0.25"), *Decimal::parse("12")}, 256);
  const StepResult<Mpfr> r = map.step(s);
  const double dtheta = (r.next.theta - s.theta).to_double(), dv = (r.next.v - s.v).to_double();
  std::printf("theta %s v %s\n", ScalarTraits<Mpfr>::to_string(r.next.theta).c_str(),
              ScalarTraits<Mpfr>::to_string(r.next.v).c_str());
  return (dtheta < 1e-70 && dtheta > -1e-70 && dv < 1e-70 && dv > -1e-70) ? 0 : 1;
}
