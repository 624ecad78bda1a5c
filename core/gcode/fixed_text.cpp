#include "ncjoule/fixed_text.hpp"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>

namespace ncjoule {
namespace {

constexpr double kPowersOfTen[] = {1e0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9};
constexpr std::uint64_t kIntegerPowersOfTen[] = {1,      10,      100,      1000,      10000,
                                                 100000, 1000000, 10000000, 100000000, 1000000000};

// Below this the scaled value's last bit is at most 2^-13: see append_fixed.
constexpr double kFastLimit = 0x1p40;
// How far from a half the scaled value's fraction must be for its rounding to be certain.
constexpr double kHalfMargin = 0x1p-12;

// "00", "01", ..., "99": digits are written two at a time.
constexpr char kDigitPairs[] =
    "00010203040506070809101112131415161718192021222324252627282930313233"
    "34353637383940414243444546474849505152535455565758596061626364656667"
    "6869707172737475767778798081828384858687888990919293949596979899";

// Writes the digits of n, at least `width` of them (zeros in front), ending at `end`; returns
// where they begin.
char* digits_backwards(char* end, std::uint64_t n, int width) {
  char* p = end;
  while (n >= 10 || width > 1) {
    p -= 2;
    std::memcpy(p, kDigitPairs + 2 * (n % 100), 2);
    n /= 100;
    width -= 2;
  }
  if (n != 0 || width > 0) *--p = char('0' + n);
  return p;
}

void append_by_printf(std::string& out, double value, int decimals) {
  char buffer[64];
  const int n = std::snprintf(buffer, sizeof buffer, "%.*f", decimals, value);
  if (n < 0) return;
  if (std::size_t(n) < sizeof buffer) {
    out.append(buffer, std::size_t(n));
    return;
  }
  // Values near 1e300 print hundreds of digits: sized exactly.
  const std::size_t at = out.size();
  out.resize(at + std::size_t(n) + 1);
  std::snprintf(out.data() + at, std::size_t(n) + 1, "%.*f", decimals, value);
  out.resize(at + std::size_t(n));
}

} // namespace

char* write_fixed_fast(char* out, double value, int decimals) {
  // value * 10^decimals is rounded once (10^decimals is exact for decimals <= 9, well within
  // 2^53), so the product s is within half its last bit, at most 2^-14 below kFastLimit, of the
  // exact product. Rounding s to an integer then gives what rounding the exact product (printf's
  // answer) gives, unless a half lies between the two: that needs s's fraction within 2^-14 of
  // 0.5. Fractions within 2^-12 of it (exact ties included, which printf rounds to even) are left
  // to printf.
  if (decimals < 0 || decimals > 9 || !std::isfinite(value)) return nullptr;
  const double scaled = std::fabs(value * kPowersOfTen[decimals]);
  if (scaled >= kFastLimit) return nullptr;
  // The conversion truncates (scaled >= 0: floor, without a call to the library's floor).
  const auto whole = std::uint64_t(scaled);
  const double fraction = scaled - double(whole); // exact: both are multiples of its last bit
  if (std::fabs(fraction - 0.5) <= kHalfMargin) return nullptr;
  const std::uint64_t n = whole + (fraction > 0.5 ? 1 : 0);
  const std::uint64_t unit = kIntegerPowersOfTen[decimals];
  // Written backwards from the middle of a local buffer, then copied to `out` as a whole
  // kFixedFastChars (one fixed-size copy, no call to memcpy; what follows the text is scratch).
  char buffer[2 * kFixedFastChars];
  char* const end = buffer + kFixedFastChars;
  char* p = end;
  if (decimals > 0) {
    p = digits_backwards(p, n % unit, decimals);
    *--p = '.';
  }
  p = digits_backwards(p, n / unit, 1);
  if (std::signbit(value)) *--p = '-';
  std::memcpy(out, p, kFixedFastChars);
  return out + (end - p);
}

void append_fixed(std::string& out, double value, int decimals) {
  char buffer[kFixedFastChars];
  if (const char* end = write_fixed_fast(buffer, value, decimals))
    out.append(buffer, std::size_t(end - buffer));
  else
    append_by_printf(out, value, decimals);
}

std::string fixed_text(double value, int decimals) {
  std::string out;
  append_fixed(out, value, decimals);
  return out;
}

} // namespace ncjoule
