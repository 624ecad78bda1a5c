// Internal: where each O-word label appears with each keyword (o100 if, o100 endif, ...), for
// control flow to find the matching line. Looked up by binary search: a program with a label
// used many times (50,000 "o100 if [0]" blocks) searched it from the top at every branch, which
// made the run quadratic in the file.
#pragma once

#include <algorithm>
#include <cstddef>
#include <initializer_list>
#include <optional>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

namespace ncjoule::detail {

class LabelIndex {
public:
  // Lines must be added in increasing order (a scan of the file from the top).
  void add(const std::string& label, const std::string& keyword, std::size_t line) {
    labels_[label][keyword].push_back(line);
  }

  // The first line after `after` where `label` appears with one of `keywords`.
  std::optional<std::size_t> next(const std::string& label, std::size_t after,
                                  std::initializer_list<const char*> keywords) const {
    std::optional<std::size_t> found;
    for_each(label, keywords, [&](const std::vector<std::size_t>& lines) {
      const auto it = std::upper_bound(lines.begin(), lines.end(), after);
      if (it != lines.end() && (!found || *it < *found)) found = *it;
    });
    return found;
  }

  // The last line before `before` where `label` appears with one of `keywords`.
  std::optional<std::size_t> previous(const std::string& label, std::size_t before,
                                      std::initializer_list<const char*> keywords) const {
    std::optional<std::size_t> found;
    for_each(label, keywords, [&](const std::vector<std::size_t>& lines) {
      const auto it = std::lower_bound(lines.begin(), lines.end(), before);
      if (it != lines.begin() && (!found || *std::prev(it) > *found)) found = *std::prev(it);
    });
    return found;
  }

  // The last line where `label` appears with `keyword`.
  std::optional<std::size_t> last(const std::string& label, const char* keyword) const {
    return previous(label, static_cast<std::size_t>(-1), {keyword});
  }

private:
  template <class F>
  void for_each(const std::string& label, std::initializer_list<const char*> keywords,
                F&& f) const {
    const auto at = labels_.find(label);
    if (at == labels_.end()) return;
    for (const char* k : keywords) {
      const auto lines = at->second.find(k);
      if (lines != at->second.end()) f(lines->second);
    }
  }

  // label -> keyword -> lines, in increasing order
  std::unordered_map<std::string, std::unordered_map<std::string, std::vector<std::size_t>>>
      labels_;
};

} // namespace ncjoule::detail
