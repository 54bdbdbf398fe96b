// The trapping region's exact top and the grid commands' default v range (trapping.hpp).
#include "bouncer/model/trapping.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

namespace bouncer {

namespace {

// U and D exactly, from the rational knots and heights; for the sine wall (U = D = 2 pi, an
// irrational) the rational 6.2831853072 > 2 pi: the lemma holds for any bounds of the wall's
// speeds, and a larger U or D only raises the top.
std::pair<mpq_class, mpq_class> wall_speeds_exact(const WallSpec& w) {
  if (w.shape == WallShape::sine) {
    mpq_class two_pi_above("62831853072/10000000000");
    two_pi_above.canonicalize();
    return {two_pi_above, two_pi_above};
  }
  mpq_class up = 0, down = 0;
  for (const Decimal& k : w.knots) {
    const mpq_class u = wall_velocity_exact(w, k.value());
    up = std::max(up, u);
    down = std::max(down, mpq_class(-u));
  }
  return {up, down};
}

}  // namespace

std::optional<mpq_class> trapping_top_exact(const ModelSpec& m) {
  if (m.law != Law::constant || m.eps.value() >= 1) return std::nullopt;
  const auto [U, D] = wall_speeds_exact(m.wall);
  const mpq_class& eps = m.eps.value();
  mpq_class top = (U + eps * (U + 2 * D)) / (1 - eps);
  top.canonicalize();
  return top;
}

std::optional<std::pair<Decimal, Decimal>> trapping_v_range(const ModelSpec& m) {
  const mpq_class U = wall_speeds_exact(m.wall).first;
  std::ostringstream lo, hi;
  lo << U.get_d();
  if (const auto exact = trapping_top_exact(m)) {
    const mpq_class t = *exact * 10000;
    mpz_class up;  // the ceiling, exactly
    mpz_cdiv_q(up.get_mpz_t(), t.get_num_mpz_t(), t.get_den_mpz_t());
    hi << exact_decimal(mpq_class(up, 10000));
  } else if (m.law == Law::veldep) {
    const double top = *trapping_top(make_model<double>(m, 53));
    hi << std::fixed << std::setprecision(4) << std::ceil(top * 1e4 * (1 + 1e-12)) / 1e4;  // up, with a margin for double
  } else {
    return std::nullopt;
  }
  return std::pair{parse_decimal("v-range", lo.str()), parse_decimal("v-range", hi.str())};
}

}  // namespace bouncer
