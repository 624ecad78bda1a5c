// write_shortest() is the JSON's number writer: every double and float must come out character
// for character as std::to_chars writes it, over every exponent and the values an estimate has.
#include <doctest/doctest.h>

#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <random>
#include <string>
#include <string_view>

#include "shortest_number.hpp"

using ncjoule::report_detail::kShortestNumberMaxChars;
using ncjoule::report_detail::write_shortest;

namespace {

template <class Float> std::string_view standard(char* buffer, Float value) {
  return {buffer, std::size_t(std::to_chars(buffer, buffer + 64, value).ptr - buffer)};
}

template <class Float> std::string_view ours(char* buffer, Float value) {
  return {buffer, std::size_t(write_shortest(buffer, value) - buffer)};
}

// Counts the values written otherwise than to_chars writes them; the first few are shown.
template <class Float> struct Comparison {
  int differ = 0;
  int longest = 0;
  void check(Float value) {
    char a[64], b[64];
    const std::string_view expected = standard(a, value), got = ours(b, value);
    longest = std::max(longest, int(got.size()));
    if (expected == got) return;
    if (++differ <= 5) MESSAGE("to_chars: " << expected << " ours: " << got);
  }
};

template <class Float, class Bits> Float from_bits(Bits bits) {
  Float value;
  std::memcpy(&value, &bits, sizeof value);
  return value;
}

} // namespace

TEST_CASE("write_shortest writes doubles as std::to_chars does") {
  Comparison<double> doubles;
  std::mt19937_64 rng(17);
  // Any bit pattern: every exponent, subnormals, both signs.
  for (int i = 0; i < 2'000'000; ++i) {
    const double value = from_bits<double>(rng());
    if (std::isfinite(value)) doubles.check(value);
  }
  // The values of an estimate: seconds, joules, watts, millimetres, with few digits and many.
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int i = 0; i < 1'000'000; ++i) {
    const double scale = std::pow(10.0, double(int(rng() % 30) - 12));
    doubles.check(unit(rng) * scale);
    doubles.check(std::round(unit(rng) * 1e6) / 1e3 * scale); // decimal fractions: 12.345
    doubles.check(double(rng() % 100000) * scale);            // whole numbers and their tenths
  }
  // Powers of ten and their neighbours, where the notation switches.
  for (int e = -325; e <= 308; ++e) {
    const double p = std::pow(10.0, double(e));
    for (const double v :
         {p, std::nextafter(p, 0.0), std::nextafter(p, 1e309), 1.5 * p, 9.5 * p, 123456.0 * p})
      if (std::isfinite(v)) doubles.check(v);
  }
  for (const double v :
       {0.0, -0.0, 1.0, -1.0, 0.1, 0.2 + 0.1, 100000.0, 1e16, 1e-5, 123e-7,
        std::numeric_limits<double>::max(), std::numeric_limits<double>::min(),
        std::numeric_limits<double>::denorm_min(), std::numeric_limits<double>::lowest()})
    doubles.check(v);
  CHECK(doubles.differ == 0);
  CHECK(doubles.longest <= kShortestNumberMaxChars);
}

TEST_CASE("write_shortest writes floats as std::to_chars does") {
  Comparison<float> floats;
  std::mt19937 rng(23);
  for (int i = 0; i < 2'000'000; ++i) {
    const float value = from_bits<float>(std::uint32_t(rng()));
    if (std::isfinite(value)) floats.check(value);
  }
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  for (int i = 0; i < 1'000'000; ++i) {
    const float scale = std::pow(10.0f, float(int(rng() % 20) - 8));
    floats.check(unit(rng) * scale);
    floats.check(float(rng() % 100000) * scale);
  }
  for (int e = -45; e <= 38; ++e) {
    const float p = std::pow(10.0f, float(e));
    for (const float v : {p, std::nextafter(p, 0.0f), std::nextafter(p, 1e39f), 1.5f * p})
      if (std::isfinite(v)) floats.check(v);
  }
  for (const float v : {0.0f, -0.0f, 0.1f, 2.6205046f, 100000.0f, std::numeric_limits<float>::max(),
                        std::numeric_limits<float>::denorm_min()})
    floats.check(v);
  CHECK(floats.differ == 0);
  CHECK(floats.longest <= kShortestNumberMaxChars);
}
