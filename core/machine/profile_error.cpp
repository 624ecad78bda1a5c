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

ProfileError::ProfileError(std::string file, std::string key, std::string reason)
    : std::runtime_error(describe(file, key, reason)), file_(std::move(file)), key_(std::move(key)),
      reason_(std::move(reason)) {}

} // namespace ncjoule
