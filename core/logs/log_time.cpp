// MTConnect time stamps: ISO 8601 in UTC (2017-02-07T19:38:27.6093750Z), as agents and adapters
// write them; an offset (+01:00) or a missing Z are read too.
#include <cmath>
#include <cstdio>

#include "ncjoule/logs.hpp"

namespace ncjoule {
namespace {

// Days from 1970-01-01 to the date (proleptic Gregorian; Howard Hinnant's days_from_civil).
long long days_from_civil(long long y, unsigned m, unsigned d) {
  y -= m <= 2;
  const long long era = (y >= 0 ? y : y - 399) / 400;
  const unsigned yoe = static_cast<unsigned>(y - era * 400);
  const unsigned doy = (153 * (m + (m > 2 ? -3 : 9)) + 2) / 5 + d - 1;
  const unsigned doe = yoe * 365 + yoe / 4 - yoe / 100 + doy;
  return era * 146097 + static_cast<long long>(doe) - 719468;
}

bool digits(std::string_view s, std::size_t at, std::size_t n, int& out) {
  if (at + n > s.size()) return false;
  out = 0;
  for (std::size_t i = at; i < at + n; ++i) {
    if (s[i] < '0' || s[i] > '9') return false;
    out = out * 10 + (s[i] - '0');
  }
  return true;
}

} // namespace

std::optional<double> parse_log_time(std::string_view s) {
  int year, month, day, hour, minute, second;
  // YYYY-MM-DDTHH:MM:SS
  if (s.size() < 19 || s[4] != '-' || s[7] != '-' || (s[10] != 'T' && s[10] != ' ') ||
      s[13] != ':' || s[16] != ':')
    return std::nullopt;
  if (!digits(s, 0, 4, year) || !digits(s, 5, 2, month) || !digits(s, 8, 2, day) ||
      !digits(s, 11, 2, hour) || !digits(s, 14, 2, minute) || !digits(s, 17, 2, second))
    return std::nullopt;
  if (month < 1 || month > 12 || day < 1 || day > 31 || hour > 23 || minute > 59 || second > 60)
    return std::nullopt;
  std::size_t at = 19;
  double fraction = 0;
  if (at < s.size() && s[at] == '.') {
    double scale = 0.1;
    ++at;
    const std::size_t begin = at;
    while (at < s.size() && s[at] >= '0' && s[at] <= '9') {
      fraction += (s[at] - '0') * scale;
      scale /= 10;
      ++at;
    }
    if (at == begin) return std::nullopt;
  }
  double offset_s = 0;
  if (at < s.size()) {
    if (s[at] == 'Z' || s[at] == 'z') {
      ++at;
    } else if (s[at] == '+' || s[at] == '-') {
      int oh, om;
      const int sign = s[at] == '+' ? 1 : -1;
      if (!digits(s, at + 1, 2, oh) || at + 3 >= s.size() || s[at + 3] != ':' ||
          !digits(s, at + 4, 2, om))
        return std::nullopt;
      offset_s = sign * (oh * 3600.0 + om * 60.0);
      at += 6;
    }
  }
  if (at != s.size()) return std::nullopt;
  const double days = double(days_from_civil(year, unsigned(month), unsigned(day)));
  return days * 86400 + hour * 3600.0 + minute * 60.0 + second + fraction - offset_s;
}

std::string format_log_time(double t_s) {
  if (!std::isfinite(t_s)) return "-";
  long long s = static_cast<long long>(std::floor(t_s));
  long long days = s >= 0 ? s / 86400 : (s - 86399) / 86400;
  long long rest = s - days * 86400;
  // civil_from_days
  days += 719468;
  const long long era = (days >= 0 ? days : days - 146096) / 146097;
  const unsigned doe = static_cast<unsigned>(days - era * 146097);
  const unsigned yoe = (doe - doe / 1460 + doe / 36524 - doe / 146096) / 365;
  const unsigned doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
  const unsigned mp = (5 * doy + 2) / 153;
  const unsigned d = doy - (153 * mp + 2) / 5 + 1;
  const unsigned m = mp < 10 ? mp + 3 : mp - 9;
  const long long y = static_cast<long long>(yoe) + era * 400 + (m <= 2);
  char text[40];
  std::snprintf(text, sizeof text, "%04lld-%02u-%02u %02lld:%02lld:%02lld UTC", y, m, d,
                rest / 3600, rest / 60 % 60, rest % 60);
  return text;
}

} // namespace ncjoule
