// Internal: numbered and named parameters, with LinuxCNC's scoping (#1-#30 and names without a
// leading underscore are local to a subroutine call; #31 and up and _names are global).
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "expression.hpp"

namespace ncjoule::detail {

// LinuxCNC's numbered parameters that hold machine state.
namespace param {
constexpr int kCount = 5602;
constexpr int kG28 = 5161; // 5161-5169: G28 home (machine coordinates)
constexpr int kG30 = 5181; // 5181-5189: G30 home
constexpr int kG92Enabled = 5210;
constexpr int kG92 = 5211; // 5211-5219: G92 offsets
constexpr int kCoordSystem = 5220;
constexpr int kG54 = 5221; // 5221-5229 G54, +20 for each next system up to G59.3
constexpr int kToolNumber = 5400;
constexpr int kPosition = 5420; // 5420-5428: current position (program coordinates)
} // namespace param

class Parameters final : public ParameterReader {
public:
  Parameters();

  // Read-only "#<_x>"-style values computed by the interpreter on demand.
  using SystemLookup = std::function<bool(std::string_view name, double& value)>;
  void set_system_lookup(SystemLookup lookup) { system_ = std::move(lookup); }

  bool read(int index, double& value, std::string& error) override;
  bool read(std::string_view name, double& value, std::string& error) override;
  bool exists(std::string_view name) override;

  bool write(int index, double value, std::string& error);
  void write(std::string_view name, double value);
  double& at(int index) { return numbered_[index]; }

  // Subroutine scoping.
  void push_scope();
  void pop_scope();
  std::size_t depth() const { return scopes_.size(); }

private:
  struct Scope {
    double saved_locals[31] = {};
    std::unordered_map<std::string, double> named;
  };
  // Zeroed in one go (a memset): a fresh interpreter is made for every program and every check.
  std::unique_ptr<double[]> numbered_;
  std::unordered_map<std::string, double> globals_;
  std::vector<Scope> scopes_;
  SystemLookup system_;
};

} // namespace ncjoule::detail
