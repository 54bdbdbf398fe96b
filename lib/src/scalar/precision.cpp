// Precisions by name (scalar/precision.hpp): each type of the scalar set is one family.
#include "bouncer/scalar/precision.hpp"

#include <optional>

#include "bouncer/base/error.hpp"
#include "bouncer/scalar/decimal.hpp"

namespace bouncer {

std::string Precision::text() const {
  return with_scalar(*this, [&](auto tag) {
    using Tr = ScalarTraits<typename decltype(tag)::type>;
    return Tr::fixed_bits ? std::string(Tr::family) : std::string(Tr::family) + ":" + std::to_string(bits);
  });
}

// Each type of the scalar set is one family: its name alone for the types of fixed
// precision, NAME:BITS for the others (in the set's order).
Precision parse_precision(const std::string& field, const std::string& text) {
  std::optional<Precision> fixed;
  for_each_scalar<Scalars>([&](auto tag) {
    using T = typename decltype(tag)::type;
    using Tr = ScalarTraits<T>;
    if (Tr::fixed_bits && !fixed && text == Tr::family) fixed = Precision{precision_kind<T>(), Tr::fixed_bits};
  });
  if (fixed) return *fixed;
  const std::string allowed = "allowed: " + precision_names<Scalars>() + " with " + std::to_string(kMinBits) +
                              " <= BITS <= " + std::to_string(kMaxBits);
  std::optional<Precision> chosen;
  for_each_scalar<Scalars>([&](auto tag) {
    using T = typename decltype(tag)::type;
    using Tr = ScalarTraits<T>;
    if (Tr::fixed_bits || chosen) return;
    const std::string pre = std::string(Tr::family) + ":";
    if (text.rfind(pre, 0) != 0) return;
    const std::string num = text.substr(pre.size());
    auto d = Decimal::parse(num);
    if (!d || d->value().get_den() != 1 || num.find_first_not_of("0123456789") != std::string::npos)
      throw InputError(field, "'" + text + "': bits must be a whole number (" + allowed + ")");
    const mpz_class bits = d->value().get_num();
    if (bits < kMinBits || bits > kMaxBits)
      throw InputError(field, "'" + text + "': bits out of range (" + allowed + ")");
    chosen = Precision{precision_kind<T>(), bits.get_si()};
  });
  if (chosen) return *chosen;
  throw InputError(field, "unknown precision '" + text + "' (" + allowed + ")");
}

}  // namespace bouncer
