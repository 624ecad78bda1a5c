// append_fixed writes what printf("%.*f") writes, byte for byte: on random values of every
// magnitude, on values a hair either side of a rounding half, on exact ties, and beyond its fast
// range.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <string>

#include "ncjoule/fixed_text.hpp"

using namespace ncjoule;

namespace {

std::string by_printf(double value, int decimals) {
  char buffer[512];
  std::snprintf(buffer, sizeof buffer, "%.*f", decimals, value);
  return buffer;
}

// The first value (of `values`, each at 0..9 decimals) where append_fixed and printf differ, as
// "value decimals: ours vs printf's"; empty when they all agree.
template <class Values> std::string first_difference(const Values& values) {
  for (const double v : values)
    for (int d = 0; d <= 9; ++d) {
      const std::string ours = fixed_text(v, d), theirs = by_printf(v, d);
      if (ours != theirs)
        return by_printf(v, 17) + " " + std::to_string(d) + ": " + ours + " vs " + theirs;
    }
  return {};
}

} // namespace

TEST_CASE("fixed decimals agree with printf on random values of every magnitude") {
  std::mt19937_64 random(43);
  std::uniform_real_distribution<double> mantissa(-1, 1);
  std::uniform_int_distribution<int> exponent(-12, 15);
  std::vector<double> values;
  for (int i = 0; i < 200000; ++i)
    values.push_back(std::ldexp(mantissa(random), 0) * std::pow(10.0, exponent(random)));
  CHECK(first_difference(values) == "");
}

TEST_CASE("fixed decimals agree with printf at and beside every rounding half") {
  std::vector<double> values;
  // Decimal halves as a program writes them (0.00005, 12.34565): not exact in binary, they fall
  // a hair to either side, and printf rounds by the side.
  for (int whole = 0; whole < 2000; ++whole)
    for (const double half : {0.5, 0.05, 0.005, 0.0005, 0.00005, 0.000005}) {
      const double v = whole * 0.001 + half;
      for (const double x : {v, -v, std::nextafter(v, 0.0), std::nextafter(v, 1e9)})
        values.push_back(x);
    }
  // Exact binary ties (2.5, 0.125, 1.0625), which printf rounds to even.
  for (int k = 0; k < 4000; ++k)
    values.push_back(std::ldexp(double(k) + 0.5, -(k % 12)));
  CHECK(first_difference(values) == "");
}

TEST_CASE("fixed decimals: signs, zeros, huge and non-finite values as printf writes them") {
  CHECK(fixed_text(-0.0, 4) == "-0.0000");
  CHECK(fixed_text(-0.00004, 4) == "-0.0000");
  CHECK(fixed_text(0.0, 0) == "0");
  CHECK(fixed_text(2.5, 0) == "2");
  CHECK(fixed_text(3.5, 0) == "4");
  CHECK(fixed_text(1234.56785, 4) == by_printf(1234.56785, 4));
  const double big[] = {0x1p40,
                        0x1p40 + 0.5,
                        1e15 + 0.3,
                        1e300,
                        -1e300,
                        std::numeric_limits<double>::max(),
                        std::numeric_limits<double>::denorm_min()};
  CHECK(first_difference(big) == "");
  CHECK(fixed_text(1e300, 4).size() == 306);
  CHECK(fixed_text(std::numeric_limits<double>::infinity(), 4) == by_printf(INFINITY, 4));
  CHECK(fixed_text(-std::numeric_limits<double>::infinity(), 2) == by_printf(-INFINITY, 2));
  CHECK(fixed_text(std::nan(""), 4) == by_printf(std::nan(""), 4));
  CHECK(fixed_text(0.123456789012, 12) == by_printf(0.123456789012, 12)); // past 9 decimals
  std::string out = "x=";
  append_fixed(out, 1.5, 3);
  CHECK(out == "x=1.500");
}
