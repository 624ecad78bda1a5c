// Nearest names for misspelt commands and options (suggest.hpp).
#include "suggest.hpp"

#include <algorithm>
#include <vector>

namespace ncjoule::cli {

std::size_t edit_distance(const std::string& a, const std::string& b) {
  // Damerau-Levenshtein (optimal string alignment): a swapped pair of letters ("estiamte") is
  // one slip, as a typist makes it.
  std::vector<std::vector<std::size_t>> d(a.size() + 1, std::vector<std::size_t>(b.size() + 1));
  for (std::size_t i = 0; i <= a.size(); ++i)
    d[i][0] = i;
  for (std::size_t j = 0; j <= b.size(); ++j)
    d[0][j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i)
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t cost = a[i - 1] == b[j - 1] ? 0 : 1;
      d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + cost});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1])
        d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
    }
  return d[a.size()][b.size()];
}

namespace {

// The candidate nearest `word`, if it is near enough to be the one meant.
std::string nearest(const std::string& word, const std::vector<std::string>& candidates) {
  std::string best;
  std::size_t best_distance = word.size() / 3 + 1;
  for (const std::string& c : candidates) {
    // A prefix ("est" for "estimate") is a name cut short, as near as a one-letter slip.
    const std::size_t d = c.rfind(word, 0) == 0 && word.size() >= 3 ? 1 : edit_distance(word, c);
    if (d < best_distance || (d == best_distance && best.empty() && d <= word.size() / 3)) {
      best_distance = d;
      best = c;
    }
  }
  return best;
}

std::vector<std::string> long_names(const CLI::App& app) {
  std::vector<std::string> names;
  for (const CLI::Option* o : app.get_options())
    for (const std::string& name : o->get_lnames())
      names.push_back("--" + name);
  return names;
}

} // namespace

std::string suggestion(const CLI::App& app, const CLI::ParseError& /*error*/, int argc,
                       const char* const* argv) {
  std::vector<std::string> commands;
  for (const CLI::App* sub : app.get_subcommands([](const CLI::App*) { return true; }))
    commands.push_back(sub->get_name());
  // The first word that is not an option names the command.
  int first = 1;
  while (first < argc && argv[first][0] == '-')
    ++first;
  if (first >= argc) return {};
  const std::string command = argv[first];
  const CLI::App* chosen = nullptr;
  for (const CLI::App* sub : app.get_subcommands([](const CLI::App*) { return true; }))
    if (sub->get_name() == command) chosen = sub;
  if (!chosen) {
    const std::string near = nearest(command, commands);
    return near.empty() ? "" : "'" + command + "' is no command; did you mean '" + near + "'?";
  }
  std::vector<std::string> options = long_names(*chosen);
  for (const std::string& o : long_names(app))
    options.push_back(o);
  for (int i = first + 1; i < argc; ++i) {
    std::string word = argv[i];
    if (word.rfind("--", 0) != 0) continue;
    word = word.substr(0, word.find('='));
    if (std::find(options.begin(), options.end(), word) != options.end()) continue;
    const std::string near = nearest(word, options);
    if (!near.empty())
      return "'" + word + "' is no option of " + command + "; did you mean '" + near + "'?";
  }
  return {};
}

} // namespace ncjoule::cli
