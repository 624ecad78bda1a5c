#include "ncjoule/profile.hpp"

namespace ncjoule {
namespace {

std::string describe(const std::string& file, const std::string& key, const std::string& reason) {
  std::string text = file.empty() ? std::string("<profile>") : file;
  text += ": ";
  if (!key.empty()) text += "key '" + key + "': ";
  return text + reason;
}

} // namespace

ProfileError::ProfileError(std::string file, std::string key, std::string reason, int line,
                           int column)
    : std::runtime_error(describe(file, key, reason)), file_(std::move(file)), key_(std::move(key)),
      reason_(std::move(reason)), line_(line), column_(column) {}

Diagnostic ProfileError::diagnostic() const {
  return {Severity::Error, file_.empty() ? std::string("<profile>") : file_, line_, column_,
          key_.empty() ? reason_ : "key '" + key_ + "': " + reason_};
}

} // namespace ncjoule
