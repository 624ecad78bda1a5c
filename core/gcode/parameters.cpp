#include "parameters.hpp"

#include <cctype>

namespace ncjoule::detail {
namespace {
std::string key(std::string_view name) {
  std::string k;
  k.reserve(name.size());
  for (char c : name)
    if (c != ' ' && c != '\t') k.push_back(char(std::tolower(static_cast<unsigned char>(c))));
  return k;
}
bool is_global(std::string_view name) {
  return !name.empty() && name[0] == '_';
}
} // namespace

Parameters::Parameters() : numbered_(std::make_unique<double[]>(param::kCount + 1)) {
  numbered_[param::kCoordSystem] = 1;
}

bool Parameters::read(int index, double& value, std::string& error) {
  if (index < 0 || index > param::kCount) {
    error = "parameter #" + std::to_string(index) + " is out of range (0-" +
            std::to_string(param::kCount) + ")";
    return false;
  }
  value = numbered_[index];
  return true;
}

bool Parameters::read(std::string_view raw, double& value, std::string& error) {
  const std::string name = key(raw);
  if (!is_global(name) && !scopes_.empty()) {
    auto it = scopes_.back().named.find(name);
    if (it != scopes_.back().named.end()) return value = it->second, true;
  } else {
    auto it = globals_.find(name);
    if (it != globals_.end()) return value = it->second, true;
    if (system_ && system_(name, value)) return true;
  }
  if (!is_global(name) && scopes_.empty()) {
    auto it = globals_.find(name);
    if (it != globals_.end()) return value = it->second, true;
  }
  error = "named parameter #<" + std::string(raw) + "> is read before it is set";
  return false;
}

bool Parameters::exists(std::string_view raw) {
  double v;
  std::string e;
  return read(raw, v, e);
}

bool Parameters::write(int index, double value, std::string& error) {
  if (index < 1 || index > param::kCount) {
    error = "parameter #" + std::to_string(index) + " cannot be set (valid: 1-" +
            std::to_string(param::kCount) + ")";
    return false;
  }
  numbered_[index] = value;
  return true;
}

void Parameters::write(std::string_view raw, double value) {
  const std::string name = key(raw);
  if (!is_global(name) && !scopes_.empty())
    scopes_.back().named[name] = value;
  else
    globals_[name] = value;
}

void Parameters::push_scope() {
  Scope s;
  for (int i = 1; i <= 30; ++i)
    s.saved_locals[i] = numbered_[i];
  scopes_.push_back(std::move(s));
}

void Parameters::pop_scope() {
  if (scopes_.empty()) return;
  for (int i = 1; i <= 30; ++i)
    numbered_[i] = scopes_.back().saved_locals[i];
  scopes_.pop_back();
}

} // namespace ncjoule::detail
