#include "ncjoule/duration.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace ncjoule {
namespace {

constexpr double kHugeHours = 1e9; // from here on, hours alone, to three significant digits

} // namespace

ClockParts split_duration(double seconds, double step) {
  if (!std::isfinite(seconds) || seconds < 0) seconds = 0;
  if (step > 0 && seconds / step < 1e15) seconds = std::round(seconds / step) * step;
  ClockParts p;
  p.hours = std::floor(seconds / 3600);
  double rest = seconds - p.hours * 3600;
  // Past 2^53 s the hours cannot hold the rest (rounding makes it negative or huge): the hours
  // say all there is to say.
  if (!(rest >= 0 && rest < 3600)) rest = 0;
  p.minutes = static_cast<int>(std::fmin(59, std::floor(rest / 60)));
  p.seconds = std::fmax(0, rest - p.minutes * 60.0);
  return p;
}

std::string whole_number_text(double value, int digits) {
  if (!std::isfinite(value)) value = 0;
  digits = digits < 1 ? 1 : digits > 17 ? 17 : digits;
  // Exact up to 2^53: every digit printed is the number's own.
  if (std::fabs(value) < 9e15) {
    char text[32];
    std::snprintf(text, sizeof text, "%.0f", value);
    return std::string(text) == "-0" ? "0" : text;
  }
  // Beyond, the digits a double holds and zeros: "%.*e" rounds them ("1.67e+25"), which are
  // then written out in full.
  char text[48];
  std::snprintf(text, sizeof text, "%.*e", digits - 1, value);
  std::string out;
  const char* c = text;
  for (; *c != 'e'; ++c)
    if (*c != '.') out += *c;
  const long exponent = std::strtol(c + 1, nullptr, 10);
  out.append(static_cast<std::size_t>(exponent - (digits - 1)), '0');
  return out;
}

std::string huge_hours(double hours) {
  return whole_number_text(hours, 3);
}

std::string duration_words(double seconds) {
  const ClockParts p = split_duration(seconds, 0.1);
  char text[96];
  if (p.hours >= kHugeHours) return huge_hours(p.hours) + " h";
  if (p.hours > 0)
    std::snprintf(text, sizeof text, "%.0f h %02d min %04.1f s", p.hours, p.minutes, p.seconds);
  else if (p.minutes > 0)
    std::snprintf(text, sizeof text, "%d min %04.1f s", p.minutes, p.seconds);
  else
    std::snprintf(text, sizeof text, "%.1f s", p.seconds);
  return text;
}

std::string duration_clock(double seconds) {
  const ClockParts p = split_duration(seconds, 1);
  if (p.hours >= kHugeHours) return huge_hours(p.hours) + " h";
  char text[64];
  if (p.hours > 0)
    std::snprintf(text, sizeof text, "%.0f:%02d:%02.0f", p.hours, p.minutes, p.seconds);
  else
    std::snprintf(text, sizeof text, "%d:%02.0f", p.minutes, p.seconds);
  return text;
}

} // namespace ncjoule
