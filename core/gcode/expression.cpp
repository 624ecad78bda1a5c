// A recursive-descent evaluator for G-code values. Precedence, lowest first, as in LinuxCNC:
// AND OR XOR; EQ NE GT GE LT LE; + -; * / MOD; ** ; unary - +; primaries.
//
// It recurses once per level of brackets, and no deeper than kMaxExpressionNesting levels: a
// program of a few KB of '[' must give an error, not overflow the stack of the thread that
// runs it (a host program may run it on a small one). Chains of signs and parameter references
// ("- - -1", "###1") are read in a loop, not by recursion. A value that is not finite (10**400,
// EXP[1000]) is an error where it arises.
#include "expression.hpp"

#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <numbers>
#include <utility>
#include <vector>

namespace ncjoule::detail {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;
constexpr double kEqualTolerance = 1e-4; // rs274ngc's TOLERANCE_EQUAL

class Evaluator {
public:
  Evaluator(std::string_view text, ParameterReader& params) : t_(text), params_(params) {}

  // `bare`: the text is the inside of a pair of brackets (operators at the top level).
  bool run(double& value, std::string& error, std::size_t& offset, bool bare = false) {
    bool ok = (bare ? binary(value, 1) : primary(value)) && pos_ == t_.size() && finite(value, 0);
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
  int depth_ = 0; // brackets open
  std::string error_;
  std::size_t error_pos_ = 0;

  bool fail(std::string message) {
    if (error_.empty()) {
      error_ = std::move(message);
      error_pos_ = pos_;
    }
    return false;
  }
  // A result that overflowed (or, from infinities, is no number): an error at `at`, the
  // operator or function that made it.
  bool finite(double v, std::size_t at) {
    if (std::isfinite(v)) return true;
    pos_ = at;
    return fail("the value overflows: it is not a finite number");
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
    if (!parse_plain_number(t_.substr(pos_, i - pos_), v)) {
      // Digits and at most one point that still do not parse: too many digits for a double.
      const std::string_view text = t_.substr(pos_, i - pos_);
      const bool well_formed = text != "." && text.find('.') == text.rfind('.');
      return fail(well_formed ? "number out of range: too large to be a value"
                              : "malformed number");
    }
    pos_ = i;
    return true;
  }

  // A named parameter, at '#<'.
  bool named_parameter(double& v) {
    ++pos_;
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

  // The numbered parameter whose number is `index`, written at `start` (after its '#').
  bool numbered_parameter(double index, std::size_t start, double& v) {
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
    if (depth_ >= kMaxExpressionNesting)
      return fail("expression nested more than " + std::to_string(kMaxExpressionNesting) +
                  " brackets deep");
    ++pos_;
    ++depth_;
    const bool ok = binary(v, 1);
    --depth_;
    if (!ok) return false;
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
      if (!function_value(name, a, start, v)) return false;
      return finite(v, start);
    }
    return fail("unknown function or word in expression");
  }

  // The value of a one-argument function (not ATAN, not EXISTS) written at `start`.
  bool function_value(std::string_view name, double a, std::size_t start, double& v) {
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

  // A value with the signs and parameter references before it, read in a loop: "--#-#1" is
  // -(-#(-#1)). Only a chain of '#' needs a record (where each index starts, and the sign
  // before it); signs alone fold into one.
  bool primary(double& v) {
    bool negate = false;
    std::vector<std::pair<std::size_t, bool>> references; // outermost first
    for (;;) {
      if (pos_ >= t_.size()) return fail("expected a value");
      const char c = t_[pos_];
      if (c == '-') {
        negate = !negate;
      } else if (c == '#' && (pos_ + 1 >= t_.size() || t_[pos_ + 1] != '<')) {
        references.emplace_back(pos_ + 1, negate);
        negate = false;
      } else if (c != '+') {
        break;
      }
      ++pos_;
    }
    if (!operand(v)) return false;
    if (negate) v = -v;
    for (auto r = references.rbegin(); r != references.rend(); ++r) {
      if (!numbered_parameter(v, r->first, v)) return false;
      if (r->second) v = -v;
    }
    return true;
  }

  // A value without signs or a numbered parameter's '#' before it.
  bool operand(double& v) {
    if (pos_ >= t_.size()) return fail("expected a value");
    const char c = t_[pos_];
    if (c == '[') return bracket(v);
    if (c == '#') return named_parameter(v);
    if ((c >= '0' && c <= '9') || c == '.') return number(v);
    if (c >= 'a' && c <= 'z') return function(v);
    return fail(std::string("unexpected character '") + c + "' in value");
  }

  // Binary operators by precedence, lowest first; all associate to the left (2**3**2 is 64).
  enum class Op {
    None,
    And,
    Or,
    Xor,
    Eq,
    Ne,
    Gt,
    Ge,
    Lt,
    Le,
    Plus,
    Minus,
    Times,
    Divide,
    Mod,
    Power
  };
  struct Operator {
    Op op = Op::None;
    int precedence = 0;
    std::size_t length = 0;
  };
  Operator next_operator() const {
    if (at("**")) return {Op::Power, 5, 2};
    if (at("*")) return {Op::Times, 4, 1};
    if (at("/")) return {Op::Divide, 4, 1};
    if (at("mod")) return {Op::Mod, 4, 3};
    if (at("+")) return {Op::Plus, 3, 1};
    if (at("-")) return {Op::Minus, 3, 1};
    static constexpr std::pair<const char*, Op> relational[] = {{"eq", Op::Eq}, {"ne", Op::Ne},
                                                                {"gt", Op::Gt}, {"ge", Op::Ge},
                                                                {"lt", Op::Lt}, {"le", Op::Le}};
    for (const auto& [text, op] : relational)
      if (at(text)) return {op, 2, 2};
    if (at("and")) return {Op::And, 1, 3};
    if (at("xor")) return {Op::Xor, 1, 3};
    if (at("or")) return {Op::Or, 1, 2};
    return {};
  }

  // Operands joined by operators of at least `lowest` precedence (precedence climbing). It
  // recurses for an operand of higher precedence only: at most five levels within one pair of
  // brackets, whatever the expression's length.
  bool binary(double& v, int lowest) {
    if (!primary(v)) return false;
    for (;;) {
      const Operator o = next_operator();
      if (o.op == Op::None || o.precedence < lowest) return true;
      const std::size_t at_op = pos_;
      pos_ += o.length;
      double r;
      if (!binary(r, o.precedence + 1)) return false;
      if (!apply(o.op, v, r, at_op)) return false;
    }
  }

  bool apply(Op op, double& v, double r, std::size_t at_op) {
    switch (op) {
    case Op::Power:
      if (v < 0 && std::floor(r) != r) return fail("negative number raised to a fractional power");
      v = std::pow(v, r);
      break;
    case Op::Times:
      v *= r;
      break;
    case Op::Divide:
      if (r == 0) return fail("division by zero");
      v /= r;
      break;
    case Op::Mod:
      if (r == 0) return fail("MOD by zero");
      v = std::fmod(v, r);
      if (v < 0) v += std::abs(r);
      break;
    case Op::Plus:
      v += r;
      break;
    case Op::Minus:
      v -= r;
      break;
    case Op::Eq:
      v = std::abs(v - r) < kEqualTolerance;
      break;
    case Op::Ne:
      v = std::abs(v - r) >= kEqualTolerance;
      break;
    case Op::Gt:
      v = v > r;
      break;
    case Op::Ge:
      v = v >= r;
      break;
    case Op::Lt:
      v = v < r;
      break;
    case Op::Le:
      v = v <= r;
      break;
    case Op::And:
      v = v != 0 && r != 0;
      break;
    case Op::Or:
      v = v != 0 || r != 0;
      break;
    case Op::Xor:
      v = (v != 0) != (r != 0);
      break;
    case Op::None:
      break;
    }
    return finite(v, at_op);
  }
};

} // namespace

namespace {

// Clinger's fast path: digits that fit a double's mantissa exactly (below 2^53), divided by a
// power of ten that is itself exact (up to 1e22), give the correctly rounded value in one
// division, the value from_chars gives. Nearly every word of a program is such a number
// ("X12.345"); the rest go to from_chars. False when the text is not digits with at most one
// point; `done` false when it is but lies outside the fast path.
bool parse_decimal_fast(const char* first, const char* last, double& value, bool& done) {
  static constexpr double kPowersOfTen[] = {1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,
                                            1e8,  1e9,  1e10, 1e11, 1e12, 1e13, 1e14, 1e15,
                                            1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22};
  constexpr std::uint64_t kExact = std::uint64_t(1) << 53;
  std::uint64_t mantissa = 0;
  int decimals = 0;
  bool point = false, digits = false, exact = true;
  for (const char* c = first; c != last; ++c) {
    if (*c == '.') {
      if (point) return false;
      point = true;
      continue;
    }
    if (*c < '0' || *c > '9') return false;
    digits = true;
    if (point) ++decimals;
    // Past 2^53 / 10 another digit may overflow what a double holds: from_chars reads it.
    if (mantissa >= kExact / 10) exact = false;
    if (exact) mantissa = mantissa * 10 + std::uint64_t(*c - '0');
  }
  if (!digits) return false;
  done = exact && decimals <= 22;
  if (done) value = double(mantissa) / kPowersOfTen[decimals];
  return true;
}

} // namespace

bool parse_plain_number(std::string_view t, double& value) {
  if (t.empty()) return false;
  bool negative = false;
  std::size_t i = 0;
  if (t[0] == '-' || t[0] == '+') negative = t[0] == '-', i = 1;
  if (i >= t.size()) return false;
  const char* first = t.data() + i;
  const char* last = t.data() + t.size();
  double v = 0;
  bool done = false;
  if (!parse_decimal_fast(first, last, v, done)) {
    // Not digits with at most one point; from_chars is left to say so for a second point.
    for (const char* c = first; c != last; ++c)
      if (!((*c >= '0' && *c <= '9') || *c == '.')) return false;
  }
  if (!done) {
    // from_chars rejects a leading '.', which G-code allows (".5"): parse the two halves.
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

bool evaluate_bare(std::string_view text, ParameterReader& params, double& value,
                   std::string& error, std::size_t& offset) {
  if (parse_plain_number(text, value)) return true;
  Evaluator e(text, params);
  return e.run(value, error, offset, true);
}

} // namespace ncjoule::detail
