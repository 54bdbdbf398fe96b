#pragma once
// The shortest decimal text of a double that reads back to it: the bytes of
// std::to_chars(first, last, x) (no format, no precision), written faster.
//
// Every double bouncer writes as text goes through here (ScalarTraits<double>::to_string,
// the orbit writers). libstdc++ 12's std::to_chars costs about 40 ns per double (Ryu's
// digits, then its choice between the fixed and the scientific layout); the orbit's CSV row
// has three, and writing a row cost 4-5x the step that computed it (issue 25). Here the
// digits come from Dragonbox (Jeon 2020; Debian's libdragonbox-dev, header only, used in
// src/scalar/shortest.cpp alone) and the layout is written with two-digit tables.
//
// The bytes are std::to_chars' exactly (tests/test_shortest.cpp compares them on random bit
// patterns, decades, powers of two, integers and the special values):
//  - the digits: both algorithms give the shortest digit string that rounds back to x (the
//    rounding interval's ends included when x's significand is even, as round-to-nearest-
//    even reads it back) and, of several such strings, the one nearest x (ties: even);
//  - the layout: fixed ("0.0123", "12.5", "300") where it is no longer than scientific
//    ("1.25e-07", "1e+22"), as the standard's plain overload prescribes;
//  - zero, infinities, NaN, and the fixed form of a value with trailing integer zeros (whose
//    shortest fixed text the standard defines as the value's exact digits when x is above
//    2^53) are std::to_chars' own: this code calls it there.
#include <cstddef>

namespace bouncer {

// Room that shortest_chars may write into (the text itself is at most 24 bytes; the rest is
// room for fixed-size copies).
inline constexpr std::size_t kShortestChars = 64;

// Writes the text of x at out, which must hold kShortestChars bytes; returns its end.
char* shortest_chars(char* out, double x);

}  // namespace bouncer
