// The type lists of the scalar set (bouncer/scalar/scalar_set.hpp) as GoogleTest type
// lists, so that every typed suite runs over the set the library is instantiated for:
//     TYPED_TEST_SUITE(MySuite, GTestTypes<bouncer::PointScalars>);
#pragma once

#include <gtest/gtest.h>

#include <tuple>

#include "bouncer/scalar/scalar_set.hpp"

namespace bouncer {

namespace gtest_detail {
template <class Tuple>
struct AsTypes;
template <class... T>
struct AsTypes<std::tuple<T...>> {
  using type = ::testing::Types<T...>;
};
}  // namespace gtest_detail

template <class Tuple>
using GTestTypes = typename gtest_detail::AsTypes<Tuple>::type;

}  // namespace bouncer
