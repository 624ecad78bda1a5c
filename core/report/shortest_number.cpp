#include "shortest_number.hpp"

#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>

// Dragonbox, as fmt ships it: fmt's own shortest formatting chooses notations by other rules
// ("100000" where to_chars writes "1e+05"), so only the digits are taken from it.
#include <fmt/format.h>

namespace ncjoule::report_detail {
namespace {

constexpr char kDigitPairs[] = "00010203040506070809"
                               "10111213141516171819"
                               "20212223242526272829"
                               "30313233343536373839"
                               "40414243444546474849"
                               "50515253545556575859"
                               "60616263646566676869"
                               "70717273747576777879"
                               "80818283848586878889"
                               "90919293949596979899";

constexpr auto kPowersOfTen = [] {
  std::array<std::uint64_t, 20> powers{};
  std::uint64_t power = 1;
  for (std::uint64_t& p : powers) {
    p = power;
    power *= 10; // wraps after 10^19, which is not kept
  }
  return powers;
}();

// Digits of n > 0: from its bit length (log10(2) ~ 1233 / 4096), corrected by one comparison.
int digit_count(std::uint64_t n) {
  const int bits = 64 - std::countl_zero(n);
  const int guess = (bits * 1233) >> 12;
  return guess + 1 - (n < kPowersOfTen[std::size_t(guess)] ? 1 : 0);
}

// The 8 digits of n < 10^8 as 8 ASCII bytes of a word, the first digit in its lowest byte: each
// step splits every lane of the word in two by a multiply and a shift, all lanes at once. The
// multipliers give exact quotients over the lanes' ranges (x * 10486 >> 20 is x / 100 below
// 10^4, x * 103 >> 10 is x / 10 below 100), and no lane's product reaches the next lane.
std::uint64_t eight_digits(std::uint32_t n) {
  std::uint64_t v = n / 10000 | std::uint64_t(n % 10000) << 32; // 2 lanes of 4 digits
  const std::uint64_t hundreds = (v * 10486) >> 20 & 0x0000007F0000007Full;
  v = hundreds | (v - hundreds * 100) << 16; // 4 lanes of 2 digits
  const std::uint64_t tens = (v * 103) >> 10 & 0x000F000F000F000Full;
  v = tens | (v - tens * 10) << 8;  // 8 lanes of 1 digit
  return v | 0x3030303030303030ull; // '0' added to each
}

// The 17 digits of n < 10^17, zeros in front, at p[0..17), stored a word at a time.
void write_seventeen_digits(char* p, std::uint64_t n) {
  constexpr std::uint64_t kEight = 100000000;
  if (n < kEight) { // 8 digits at most (a float's, mostly): one word of them
    std::memset(p, '0', 9);
    const std::uint64_t word = eight_digits(std::uint32_t(n));
    if constexpr (std::endian::native == std::endian::little) {
      std::memcpy(p + 9, &word, 8);
    } else {
      for (int i = 0; i < 8; ++i)
        p[9 + i] = char(word >> (8 * i));
    }
    return;
  }
  const std::uint64_t high = n / kEight; // < 10^9
  const std::uint64_t words[2] = {eight_digits(std::uint32_t(high % kEight)),
                                  eight_digits(std::uint32_t(n % kEight))};
  p[0] = char('0' + high / kEight);
  for (int w = 0; w < 2; ++w) {
    if constexpr (std::endian::native == std::endian::little) {
      std::memcpy(p + 1 + 8 * w, &words[w], 8);
    } else {
      for (int i = 0; i < 8; ++i)
        p[1 + 8 * w + i] = char(words[w] >> (8 * i));
    }
  }
}

// A whole number's every digit.
char* write_whole(char* p, unsigned __int128 n) {
  char digits[40];
  int count = 0;
  do {
    digits[count++] = char('0' + unsigned(n % 10));
    n /= 10;
  } while (n > 0);
  while (count > 0)
    *p++ = digits[--count];
  return p;
}

// The number significand * 10^exponent (significand > 0, no trailing zeros), the shortest
// digits of `magnitude`, in to_chars's plain form. The digits are written once, to a scratch
// buffer, and copied in pieces of a fixed 16 or 24 bytes (what follows a piece is written over
// or lies past the end returned): cutting them at the point by dividing by a power of ten, or
// by shifting them in a 128-bit register, took longer.
template <class Float>
char* write_decimal(char* p, std::uint64_t significand, int exponent, Float magnitude) {
  const int n = digit_count(significand); // at most 17
  char padded[17 + 24];
  write_seventeen_digits(padded, significand);
  std::memset(padded + 17, '0', 24); // set, for the pieces copied past the digits
  const char* digits = padded + 17 - n;
  // d.ddd x 10^x: the exponent of scientific notation.
  const int x = exponent + n - 1;
  const int abs_x = x < 0 ? -x : x;
  const int scientific = n + (n > 1 ? 1 : 0) + 2 + (abs_x >= 100 ? 3 : 2);
  int fixed;
  if (x < 0)
    fixed = n + 1 - x; // "0." then -x - 1 zeros, then the digits
  else if (x + 1 >= n)
    fixed = x + 1; // the digits, then zeros
  else
    fixed = n + 1; // a point among the digits
  if (fixed <= scientific) {
    if (x < 0) {
      // At most 3 zeros after the point: with more, scientific notation is shorter.
      std::memcpy(p, "0.000", 5);
      p += 1 - x;
      std::memcpy(p, digits, 24);
      return p + n;
    }
    if (x + 1 > n) {
      // Whole, beyond its shortest digits: written as printf's %.0f writes it, every digit of
      // the number itself (to_chars's 63193312, where the shortest digits are 6319331e1). It
      // has at most 22 digits here (longer ones are shorter in scientific notation).
      return write_whole(p, static_cast<unsigned __int128>(magnitude));
    }
    if (x + 1 == n) {
      std::memcpy(p, digits, 24);
      return p + n;
    }
    // The first x + 1 digits (at most 16), the point, the rest (at most 16).
    std::memcpy(p, digits, 16);
    p[x + 1] = '.';
    std::memcpy(p + x + 2, digits + x + 1, 16);
    return p + n + 1;
  }
  p[0] = digits[0];
  if (n > 1) {
    p[1] = '.';
    std::memcpy(p + 2, digits + 1, 16);
    p += n + 1;
  } else {
    p += 1;
  }
  *p++ = 'e';
  *p++ = x < 0 ? '-' : '+';
  if (abs_x >= 100) *p++ = char('0' + abs_x / 100);
  const auto pair = std::size_t(abs_x % 100) * 2;
  *p++ = kDigitPairs[pair];
  *p++ = kDigitPairs[pair + 1];
  return p;
}

template <class Float> char* write_float(char* p, Float value) {
  if (std::signbit(value)) *p++ = '-';
  if (value == 0) {
    *p++ = '0';
    return p;
  }
  const Float magnitude = std::fabs(value);
  const auto decimal = fmt::detail::dragonbox::to_decimal(magnitude);
  std::uint64_t significand = decimal.significand;
  int exponent = decimal.exponent;
  while (significand % 10 == 0) {
    significand /= 10;
    ++exponent;
  }
  return write_decimal(p, significand, exponent, magnitude);
}

} // namespace

char* write_shortest(char* p, double value) {
  return write_float(p, value);
}

char* write_shortest(char* p, float value) {
  return write_float(p, value);
}

} // namespace ncjoule::report_detail
