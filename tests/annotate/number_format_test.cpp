// The compact formats of annotation fields.
#include <doctest/doctest.h>

#include "ncjoule/duration.hpp"
#include "number_format.hpp"

#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <string>

using namespace ncjoule::annotation;
using ncjoule::ClockParts;
using ncjoule::split_duration;

TEST_CASE("significant digits without exponents or trailing zeros") {
  CHECK(format_significant(34.5, 3, 3) == "34.5");
  CHECK(format_significant(1.2345, 3, 3) == "1.23");
  CHECK(format_significant(0.012345, 3, 3) == "0.012"); // at most max_decimals
  CHECK(format_significant(0.012345, 3, 4) == "0.0123");
  CHECK(format_significant(1234.6, 3, 3) == "1235");
  CHECK(format_significant(2.0, 3, 3) == "2");
  CHECK(format_significant(0.0, 3, 3) == "0");
  CHECK(format_significant(-0.0001, 3, 3) == "0");
  CHECK(format_significant(0.000000806, 4, 12) == "0.000000806");
  CHECK(format_significant(-12.5, 3, 3) == "-12.5");
}

TEST_CASE("durations") {
  CHECK(format_duration(0.0123) == "0.012s"); // milliseconds at most
  CHECK(format_duration(0.0004) == "0s");
  CHECK(format_duration(1.234) == "1.23s");
  CHECK(format_duration(12.34) == "12.3s");
  CHECK(format_duration(59.96) == "1m00s");
  CHECK(format_duration(83) == "1m23s");
  CHECK(format_duration(3723.4) == "1h02m03s");
}

TEST_CASE("SI prefixes") {
  CHECK(format_si(450, "J") == "450J");
  CHECK(format_si(1234, "J") == "1.23kJ");
  CHECK(format_si(999.7, "J") == "1kJ");
  CHECK(format_si(4.5e6, "J") == "4.5MJ");
  CHECK(format_si(0.5, "W") == "0.5W");
}

TEST_CASE("user text becomes one safe token") {
  CHECK(safe_token("2D Pocket1", 24) == "2D_Pocket1");
  CHECK(safe_token("  Face (rough) – 50% #1 ", 24) == "Face_rough_50_1");
  CHECK(safe_token("a=b", 24) == "a_b");
  CHECK(safe_token("Very long operation name indeed", 10) == "Very_long");
}

TEST_CASE("large values keep their significant digits and zeros, never an exponent") {
  CHECK(format_significant(1e23, 3, 3) ==
        "100000000000000000000000"); // not 99999999999999991611392
  CHECK(format_significant(-4.56789e20, 3, 3) == "-457000000000000000000");
  CHECK(format_significant(123456789, 3, 3) == "123456789"); // whole numbers in full
  CHECK(format_si(1e30, "J") == "1000000000000000000TJ");
  CHECK(format_si(2.5e15, "J") == "2500TJ");
  // 1e11 s: a million dwells of 99,999.999 s in a loop, in hours, minutes and seconds.
  CHECK(format_duration(99999.999 * 1e6) == "27777777h30m00s");
  CHECK(format_duration(6e28) == "16700000000000000000000000h");
  CHECK(format_duration(std::numeric_limits<double>::infinity()) == "0s");
  CHECK(format_duration(std::nan("")) == "0s");
  CHECK(format_si(std::numeric_limits<double>::quiet_NaN(), "W") == "0W");
}

TEST_CASE("every finite value gives digits, a point and its unit only") {
  // From the smallest to the largest double, both signs: no 'e', no 'inf' or 'nan', no '+'.
  auto plain = [](const std::string& text, std::string_view unit) {
    std::string number = text.substr(0, text.size() - unit.size());
    while (!number.empty() && std::string_view("kMGT").find(number.back()) != std::string::npos)
      number.pop_back();
    bool ok = !number.empty() && text.size() <= 320;
    for (char c : number)
      ok = ok && ((c >= '0' && c <= '9') || c == '.' || c == '-');
    return ok;
  };
  auto plain_duration = [](const std::string& text) {
    bool ok = !text.empty() && text.size() <= 320 && (text.back() == 's' || text.back() == 'h');
    for (char c : text)
      ok = ok && ((c >= '0' && c <= '9') || c == '.' || c == 'h' || c == 'm' || c == 's');
    return ok;
  };
  for (double magnitude = 1e-300; std::isfinite(magnitude); magnitude *= 7.3) {
    for (double value : {magnitude, -magnitude}) {
      CAPTURE(value);
      CHECK(plain(format_significant(value, 3, 3), ""));
      CHECK(plain(format_significant(value, 4, 6), ""));
      CHECK(plain(format_si(value, "J"), "J"));
      CHECK(plain_duration(format_duration(value)));
    }
  }
  CHECK(plain(format_si(std::numeric_limits<double>::max(), "J"), "J"));
  CHECK(plain_duration(format_duration(std::numeric_limits<double>::max())));
}

TEST_CASE("durations of a minute and more are written as printf wrote them") {
  // The former "%dm%02.0fs" / "%.0fh%02dm%02.0fs" of split_duration's parts, against the text
  // written without printf: every 0.37 s to 56 hours (half seconds and minute and hour turns
  // among them), then larger durations up to the hours' limit.
  auto by_printf = [](double seconds) {
    const ClockParts p = split_duration(seconds, 1);
    char text[64];
    if (p.hours == 0)
      std::snprintf(text, sizeof text, "%dm%02.0fs", p.minutes, p.seconds);
    else
      std::snprintf(text, sizeof text, "%.0fh%02dm%02.0fs", p.hours, p.minutes, p.seconds);
    return std::string(text);
  };
  std::size_t checked = 0, same = 0;
  auto check = [&](double seconds) {
    ++checked;
    same += format_duration(seconds) == by_printf(seconds);
  };
  for (double s = 59.95; s < 200'000; s += 0.37)
    check(s);
  for (double s : {59.95, 60.0, 119.5, 3599.5, 3600.0, 86399.5, 1e6 + 0.5, 3.6e12 - 0.6})
    check(s);
  for (double s = 1e5; s < 3.5e12; s *= 1.37)
    check(s);
  CHECK(checked > 500'000);
  CHECK(same == checked);
  CHECK(format_duration(3600) == "1h00m00s");
  CHECK(format_duration(60) == "1m00s");
}

TEST_CASE("the place of a number's first digit is log10's, at and around every power of ten") {
  // decimal_magnitude compares with the powers of ten and leaves values near one to log10: the
  // decimals of every number an annotation writes hang on it.
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> exponent(-9, 15);
  std::size_t differ = 0, checked = 0;
  auto check = [&](double v) {
    ++checked;
    if (decimal_magnitude(v) != int(std::floor(std::log10(v)))) ++differ;
  };
  for (int k = 0; k < 200'000; ++k)
    check(std::pow(10.0, exponent(rng)));
  for (int e = -9; e <= 15; ++e) {
    const double p = std::pow(10.0, e);
    double below = p, above = p;
    for (int step = 0; step < 50; ++step) {
      check(below), check(above);
      below = std::nextafter(below, 0.0), above = std::nextafter(above, 1e300);
    }
    check(p * (1 - 1e-9)), check(p * (1 + 1e-9)), check(p * (1 - 2e-9)), check(p * (1 + 2e-9));
  }
  CHECK(checked > 200'000);
  CHECK(differ == 0);
}
