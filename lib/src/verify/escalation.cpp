#include "bouncer/verify/escalation.hpp"

#include <algorithm>

namespace bouncer {

std::vector<long> EscalationSchedule::bits() const {
  std::vector<long> out;
  const long top = std::max(max_bits, 16L);
  for (long b = std::max(start_bits, 16L); b < top; b *= 2) out.push_back(b);
  out.push_back(top);
  return out;
}

std::string Tier::text() const {
  return double_interval ? std::string("interval:double") : "interval:" + std::to_string(bits);
}

std::vector<Tier> EscalationSchedule::tiers() const {
  std::vector<Tier> out;
  if (double_first) out.push_back(Tier{true, 53});
  for (long b : bits()) out.push_back(Tier{false, b});
  return out;
}

std::string EscalationSchedule::text() const {
  const std::vector<long> b = bits();
  std::string s = double_first ? "interval:double, then " : "";
  for (size_t i = 0; i < b.size() && i < 3; ++i) s += (i ? ", " : "") + std::to_string(b[i]);
  if (b.size() > 3) s += ", ... doubling up to " + std::to_string(b.back());
  return s + " bits";
}

namespace detail {

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

std::string give_up_text(const Attempt& best, long max_bits) {
  const std::string where = best.double_interval ? std::string("interval:double") : std::to_string(best.bits) + " bits";
  return "undecided at step " + std::to_string(best.steps + 1) + " at " + where +
         " (the best run; max " + std::to_string(max_bits) + " bits): " + best.reason;
}

}  // namespace detail

}  // namespace bouncer
