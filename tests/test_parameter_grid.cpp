#include <fmt/format.h>

#include <catch2/catch.hpp>
#include <cmath>
#include <cstdlib>
#include <string>

#include "impactkit/core/errors.hpp"
#include "impactkit/core/parameter_grid.hpp"

using impactkit::GridValue;
using impactkit::GridValues;

TEST_CASE("grid values are the decimals a user typed, for the paper's sweep grid", "[grid]") {
  // 0.1 to 2.5 in 2401 values: the k-th is the decimal (100 + k) / 1000,
  // built here as text from integers and read by strtod (no binary arithmetic).
  const auto values = GridValues(0.1, 2.5, 2401);
  REQUIRE(values.size() == 2401);
  for (int k = 0; k < 2401; ++k) {
    const int thousandths = 100 + k;
    const std::string exact = fmt::format("{}.{:03d}", thousandths / 1000, thousandths % 1000);
    INFO("k = " << k << ", expected " << exact);
    REQUIRE(values[k] == std::strtod(exact.c_str(), nullptr));
  }
}

TEST_CASE(
    "grid values keep their ends exactly and their order when the grid is finer than "
    "the rounding",
    "[grid]") {
  const double from = 1.0, to = 1.0 + 8e-15;  // a spacing of ~9 ulps
  const auto values = GridValues(from, to, 5);
  CHECK(values.front() == from);
  CHECK(values.back() == to);
  for (std::size_t k = 1; k < values.size(); ++k) CHECK(values[k] > values[k - 1]);
  // Descending grids are grids too.
  const auto down = GridValues(2.5, 0.1, 25);
  CHECK(down[1] == 2.4);
  CHECK(down[24] == 0.1);
}

TEST_CASE("a grid index outside the grid or an infinite end is refused", "[grid]") {
  CHECK_THROWS_AS(GridValue(0.0, 1.0, 3, 3), impactkit::InvalidInput);
  CHECK_THROWS_AS(GridValue(0.0, 1.0, 0, 0), impactkit::InvalidInput);
  CHECK_THROWS_AS(GridValue(0.0, INFINITY, 3, 1), impactkit::InvalidInput);
  CHECK(GridValue(0.3, 0.7, 1, 0) == 0.3);
}
