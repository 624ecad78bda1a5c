// A recursive-descent evaluator for G-code values. Precedence, lowest first, as in LinuxCNC:
// AND OR XOR; EQ NE GT GE LT LE; + -; * / MOD; ** ; unary - +; primaries.
#include "expression.hpp"

#include <charconv>
#include <cmath>
#include <cstring>
#include <numbers>

namespace ncjoule::detail {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;
constexpr double kEqualTolerance = 1e-4; // rs274ngc's TOLERANCE_EQUAL

class Evaluator {
public:
  Evaluator(std::string_view text, ParameterReader& params) : t_(text), params_(params) {}

  bool run(double& value, std::string& error, std::size_t& offset) {
    bool ok = primary(value) && pos_ == t_.size();
    if (ok) return true;
    if (error_.empty()) error_ = "unexpected text in value";
    error = error_;
    offset = error_pos_;
    return false;
  }

private:
  std::string_view t_;
  ParameterReader& params_;
  std::size_t pos_ = 0;
  std::string error_;
  std::size_t error_pos_ = 0;

  bool fail(std::string message) {
    if (error_.empty()) {
      error_ = std::move(message);
      error_pos_ = pos_;
    }
    return false;
  }
  bool at(std::string_view s) const { return t_.compare(pos_, s.size(), s) == 0; }
  bool take(std::string_view s) {
    if (!at(s)) return false;
    pos_ += s.size();
    return true;
  }

  bool number(double& v) {
    std::size_t i = pos_;
    while (i < t_.size() && (std::isdigit(static_cast<unsigned char>(t_[i])) || t_[i] == '.'))
      ++i;
    if (i == pos_) return fail("expected a number");
    if (!parse_plain_number(t_.substr(pos_, i - pos_), v)) return fail("malformed number");
    pos_ = i;
    return true;
  }

  bool parameter(double& v) {
    // at '#'
    ++pos_;
    if (pos_ < t_.size() && t_[pos_] == '<') {
      std::size_t close = t_.find('>', pos_);
      if (close == std::string_view::npos) return fail("named parameter is not closed: '>'");
      std::string_view name = t_.substr(pos_ + 1, close - pos_ - 1);
      std::size_t start = pos_;
      pos_ = close + 1;
      std::string err;
      if (!params_.read(name, v, err)) {
        pos_ = start;
        return fail(err);
      }
      return true;
    }
    std::size_t start = pos_;
    double index;
    if (!primary(index)) return false;
    const double r = std::round(index);
    if (std::abs(index - r) > 1e-4) {
      pos_ = start;
      return fail("parameter number is not an integer");
    }
    std::string err;
    if (!params_.read(saturate<int>(r), v, err)) {
      pos_ = start;
      return fail(err);
    }
    return true;
  }

  bool bracket(double& v) {
    // at '['
    ++pos_;
    if (!logic(v)) return false;
    if (!take("]")) return fail("expected ']'");
    return true;
  }

  bool function(double& v) {
    static constexpr const char* names[] = {"abs", "acos", "asin", "atan",  "cos",
                                            "exp", "fix",  "fup",  "ln",    "round",
                                            "sin", "sqrt", "tan",  "exists"};
    for (const char* f : names) {
      const std::size_t len = std::strlen(f);
      if (t_.compare(pos_, len, f) != 0 || pos_ + len >= t_.size() || t_[pos_ + len] != '[')
        continue;
      const std::size_t start = pos_;
      pos_ += len;
      const std::string_view name(f);
      if (name == "exists") {
        ++pos_;
        if (!take("#<")) return fail("EXISTS needs a named parameter: exists[#<name>]");
        std::size_t close = t_.find('>', pos_);
        if (close == std::string_view::npos) return fail("named parameter is not closed: '>'");
        v = params_.exists(t_.substr(pos_, close - pos_)) ? 1.0 : 0.0;
        pos_ = close + 1;
        if (!take("]")) return fail("expected ']'");
        return true;
      }
      double a;
      if (!bracket(a)) return false;
      if (name == "atan") {
        if (!take("/")) return fail("ATAN needs two arguments: atan[y]/[x]");
        if (pos_ >= t_.size() || t_[pos_] != '[') return fail("expected '[' after atan[y]/");
        double b;
        if (!bracket(b)) return false;
        v = std::atan2(a, b) / kDegree;
        return true;
      }
      if (name == "abs")
        v = std::abs(a);
      else if (name == "acos") {
        if (a < -1 || a > 1) return pos_ = start, fail("ACOS argument out of range [-1, 1]");
        v = std::acos(a) / kDegree;
      } else if (name == "asin") {
        if (a < -1 || a > 1) return pos_ = start, fail("ASIN argument out of range [-1, 1]");
        v = std::asin(a) / kDegree;
      } else if (name == "cos")
        v = std::cos(a * kDegree);
      else if (name == "exp")
        v = std::exp(a);
      else if (name == "fix")
        v = std::floor(a);
      else if (name == "fup")
        v = std::ceil(a);
      else if (name == "ln") {
        if (a <= 0) return pos_ = start, fail("LN of zero or a negative number");
        v = std::log(a);
      } else if (name == "round")
        v = std::round(a); // halves away from zero, as LinuxCNC
      else if (name == "sin")
        v = std::sin(a * kDegree);
      else if (name == "sqrt") {
        if (a < 0) return pos_ = start, fail("SQRT of a negative number");
        v = std::sqrt(a);
      } else if (name == "tan")
        v = std::tan(a * kDegree);
      return true;
    }
    return fail("unknown function or word in expression");
  }

  bool primary(double& v) {
    if (pos_ >= t_.size()) return fail("expected a value");
    const char c = t_[pos_];
    if (c == '-') return ++pos_, primary(v) && (v = -v, true);
    if (c == '+') return ++pos_, primary(v);
    if (c == '[') return bracket(v);
    if (c == '#') return parameter(v);
    if ((c >= '0' && c <= '9') || c == '.') return number(v);
    if (c >= 'a' && c <= 'z') return function(v);
    return fail(std::string("unexpected character '") + c + "' in value");
  }

  bool power(double& v) {
    if (!primary(v)) return false;
    while (at("**")) {
      pos_ += 2;
      double r;
      if (!primary(r)) return false;
      if (v < 0 && std::floor(r) != r) return fail("negative number raised to a fractional power");
      v = std::pow(v, r);
    }
    return true;
  }

  bool multiplicative(double& v) {
    if (!power(v)) return false;
    for (;;) {
      if (at("*") && !at("**")) {
        ++pos_;
        double r;
        if (!power(r)) return false;
        v *= r;
      } else if (at("/")) {
        ++pos_;
        double r;
        if (!power(r)) return false;
        if (r == 0) return fail("division by zero");
        v /= r;
      } else if (at("mod")) {
        pos_ += 3;
        double r;
        if (!power(r)) return false;
        if (r == 0) return fail("MOD by zero");
        v = std::fmod(v, r);
        if (v < 0) v += std::abs(r);
      } else {
        return true;
      }
    }
  }

  bool additive(double& v) {
    if (!multiplicative(v)) return false;
    for (;;) {
      if (at("+")) {
        ++pos_;
        double r;
        if (!multiplicative(r)) return false;
        v += r;
      } else if (at("-")) {
        ++pos_;
        double r;
        if (!multiplicative(r)) return false;
        v -= r;
      } else {
        return true;
      }
    }
  }

  bool comparison(double& v) {
    if (!additive(v)) return false;
    for (;;) {
      static constexpr const char* ops[] = {"eq", "ne", "gt", "ge", "lt", "le"};
      int op = -1;
      for (int k = 0; k < 6; ++k)
        if (at(ops[k])) op = k;
      if (op < 0) return true;
      pos_ += 2;
      double r;
      if (!additive(r)) return false;
      switch (op) {
      case 0:
        v = std::abs(v - r) < kEqualTolerance;
        break;
      case 1:
        v = std::abs(v - r) >= kEqualTolerance;
        break;
      case 2:
        v = v > r;
        break;
      case 3:
        v = v >= r;
        break;
      case 4:
        v = v < r;
        break;
      case 5:
        v = v <= r;
        break;
      }
    }
  }

  bool logic(double& v) {
    if (!comparison(v)) return false;
    for (;;) {
      int op = at("and") ? 0 : at("xor") ? 2 : at("or") ? 1 : -1;
      if (op < 0) return true;
      pos_ += op == 1 ? 2 : 3;
      double r;
      if (!comparison(r)) return false;
      const bool a = v != 0, b = r != 0;
      v = op == 0 ? (a && b) : op == 1 ? (a || b) : (a != b);
    }
  }
};

} // namespace

bool parse_plain_number(std::string_view t, double& value) {
  if (t.empty()) return false;
  bool negative = false;
  std::size_t i = 0;
  if (t[0] == '-' || t[0] == '+') negative = t[0] == '-', i = 1;
  if (i >= t.size()) return false;
  // from_chars rejects a leading '.', which G-code allows (".5"): parse the two halves.
  const char* first = t.data() + i;
  const char* last = t.data() + t.size();
  for (const char* c = first; c != last; ++c)
    if (!((*c >= '0' && *c <= '9') || *c == '.')) return false;
  double v = 0;
  if (*first == '.') {
    if (last - first == 1) return false;
    std::string tmp = "0";
    tmp.append(first, last);
    auto r = std::from_chars(tmp.data(), tmp.data() + tmp.size(), v);
    if (r.ec != std::errc() || r.ptr != tmp.data() + tmp.size()) return false;
  } else {
    auto r = std::from_chars(first, last, v);
    if (r.ec != std::errc() || r.ptr != last) return false;
  }
  value = negative ? -v : v;
  return true;
}

bool evaluate(std::string_view text, ParameterReader& params, double& value, std::string& error,
              std::size_t& offset) {
  if (parse_plain_number(text, value)) return true;
  Evaluator e(text, params);
  return e.run(value, error, offset);
}

} // namespace ncjoule::detail
