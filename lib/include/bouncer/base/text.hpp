// Text for messages: the distance used to suggest close names for a typo (options, commands,
// reproduce's item ids, scene names) and the closest name itself; approximate values. (One
// printable line of any value: one_line, base/input.hpp.)
#pragma once

#include <algorithm>
#include <cstddef>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

namespace bouncer {

// Edit distance (Levenshtein), for suggestions.
inline std::size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diag = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diag + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diag = up;
    }
  }
  return row[b.size()];
}

// The closest of `names` to `word`, if it is close enough to be a typo. A name that is a
// prefix of the word, or the word a prefix of it (--epsilon / --eps), counts as distance 1.
inline std::optional<std::string> closest(const std::string& word, const std::vector<std::string>& names) {
  std::optional<std::string> best;
  std::size_t best_d = std::max<std::size_t>(2, word.size() / 3) + 1;
  for (const std::string& n : names) {
    std::size_t d = edit_distance(word, n);
    const std::size_t shorter = std::min(word.size(), n.size());
    if (shorter >= 4 && (word.rfind(n, 0) == 0 || n.rfind(word, 0) == 0)) d = std::min<std::size_t>(d, 1);
    if (d < best_d) {
      best = n;
      best_d = d;
    }
  }
  return best;
}

// x to `digits` significant digits as iostream prints it ("0.409976", "1e-07"): an
// approximate value in a sentence or a label (the phase where a flight grazes the sine wall,
// found by a march, not located).
inline std::string approximate_text(double x, int digits = 6) {
  std::ostringstream o;
  o.precision(digits);
  o << x;
  return o.str();
}

}  // namespace bouncer
