#include "number_format.hpp"

#include "ncjoule/duration.hpp"
#include "ncjoule/fixed_text.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>

namespace ncjoule::annotation {
namespace {

// "%dm%02.0fs" (no hours) or "%.0fh%02dm%02.0fs" as printf writes them for whole hours below
// 1e9, minutes and seconds 0..59.
std::string clock_text(long hours, int minutes, int seconds) {
  char text[32];
  char* p = text;
  auto two = [&](int v) { *p++ = char('0' + v / 10), *p++ = char('0' + v % 10); };
  if (hours > 0) {
    p = std::to_chars(p, text + 16, hours).ptr;
    *p++ = 'h';
    two(minutes);
  } else {
    p = std::to_chars(p, text + 16, minutes).ptr;
  }
  *p++ = 'm';
  two(seconds);
  *p++ = 's';
  return std::string(text, p);
}

} // namespace

// floor(log10(v)) for v > 0, as the library's log10 gives it, without calling it for most
// values: a block's comment has three or four numbers to place. Away from a power of ten the
// comparison with the powers is certain; within a relative 1e-9 of one (where log10's last bit
// could round across the integer) the library decides.
int decimal_magnitude(double v) {
  static constexpr double kPowers[] = {1e-6, 1e-5, 1e-4, 1e-3, 1e-2, 1e-1, 1e0,  1e1,  1e2, 1e3,
                                       1e4,  1e5,  1e6,  1e7,  1e8,  1e9,  1e10, 1e11, 1e12};
  constexpr int kFirst = -6;
  constexpr int kCount = int(sizeof kPowers / sizeof kPowers[0]);
  if (!(v >= kPowers[0] * (1 + 1e-9)) || !(v < kPowers[kCount - 1] * (1 - 1e-9)))
    return static_cast<int>(std::floor(std::log10(v)));
  int k = 0; // kPowers[k] <= v < kPowers[k + 1], roughly
  while (k + 1 < kCount && kPowers[k + 1] <= v)
    ++k;
  const bool near_power =
      std::fabs(v - kPowers[k]) <= kPowers[k] * 1e-9 ||
      (k + 1 < kCount && std::fabs(kPowers[k + 1] - v) <= kPowers[k + 1] * 1e-9);
  if (near_power) return static_cast<int>(std::floor(std::log10(v)));
  return kFirst + k;
}

std::string format_significant(double value, int digits, int max_decimals) {
  if (!std::isfinite(value)) return "0";
  int decimals = 0;
  if (value != 0) {
    const int magnitude = decimal_magnitude(std::fabs(value));
    // A whole number: its digits in full, and past what a double holds exactly, the
    // significant ones and zeros (never "%.0f"'s binary tail, never an exponent).
    if (magnitude >= digits - 1) return whole_number_text(value, digits);
    decimals = std::clamp(digits - 1 - magnitude, 0, max_decimals);
  }
  // As "%.*f" writes it (fixed_text.hpp), without printf: annotating writes a few for every
  // block of the program.
  std::string out;
  append_fixed(out, value, decimals);
  if (out.find('.') != std::string::npos) {
    while (out.back() == '0')
      out.pop_back();
    if (out.back() == '.') out.pop_back();
  }
  if (out == "-0") out = "0";
  return out;
}

std::string format_duration(double seconds) {
  if (!std::isfinite(seconds) || seconds < 0) seconds = 0;
  // Below a minute, three significant digits (at most ms); 59.96 s would print as "60s", so the
  // minute form starts where rounding reaches it.
  if (seconds < 59.95) return format_significant(seconds, 3, 3) + "s";
  const ClockParts p = split_duration(seconds, 1);
  if (p.hours >= 1e9) return huge_hours(p.hours) + "h";
  // Whole hours, minutes and seconds (a 1 s step): written without printf, as it writes them,
  // since the cumulative time of nearly every block of a long program takes this form.
  if (p.seconds >= 0 && p.seconds < 60 && p.seconds == std::floor(p.seconds) &&
      !std::signbit(p.seconds) && p.hours >= 0 && p.hours == std::floor(p.hours) &&
      !std::signbit(p.hours) && p.minutes >= 0 && p.minutes < 60)
    return clock_text(static_cast<long>(p.hours), p.minutes, static_cast<int>(p.seconds));
  char text[64];
  if (p.hours == 0)
    std::snprintf(text, sizeof text, "%dm%02.0fs", p.minutes, p.seconds);
  else
    std::snprintf(text, sizeof text, "%.0fh%02dm%02.0fs", p.hours, p.minutes, p.seconds);
  return text;
}

std::string format_si(double value, std::string_view unit) {
  static constexpr const char* kPrefixes[] = {"", "k", "M", "G", "T"};
  if (!std::isfinite(value)) value = 0;
  int prefix = 0;
  double scaled = value;
  // Move up a prefix while the value, rounded to 3 significant digits, reaches 1000.
  while (prefix < 4 && std::fabs(scaled) >= 999.5) {
    scaled /= 1000;
    ++prefix;
  }
  return format_significant(scaled, 3, 3) + kPrefixes[prefix] + std::string(unit);
}

std::string safe_token(std::string_view text, std::size_t max_length) {
  std::string out;
  for (char c : text) {
    const bool keep = (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') ||
                      c == '.' || c == ',' || c == '-';
    if (keep)
      out += c;
    else if (!out.empty() && out.back() != '_')
      out += '_';
  }
  while (!out.empty() && out.back() == '_')
    out.pop_back();
  if (out.size() > max_length) out.resize(max_length);
  while (!out.empty() && out.back() == '_')
    out.pop_back();
  return out;
}

} // namespace ncjoule::annotation
