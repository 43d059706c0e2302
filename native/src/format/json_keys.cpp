#include "format/json_keys.h"

#include <algorithm>
#include <cctype>

namespace fenestra {

namespace {

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

// Optimal string alignment distance: insertions, deletions, substitutions and swaps of
// neighbouring characters each count one.
std::size_t edit_distance(const std::string& a, const std::string& b) {
  const std::size_t n = a.size(), m = b.size();
  std::vector<std::vector<std::size_t>> d(n + 1, std::vector<std::size_t>(m + 1));
  for (std::size_t i = 0; i <= n; ++i) d[i][0] = i;
  for (std::size_t j = 0; j <= m; ++j) d[0][j] = j;
  for (std::size_t i = 1; i <= n; ++i)
    for (std::size_t j = 1; j <= m; ++j) {
      d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + (a[i - 1] == b[j - 1] ? 0 : 1)});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1]) d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
    }
  return d[n][m];
}

}  // namespace

std::string closest_word(const std::string& word, const std::vector<std::string>& known) {
  constexpr std::size_t kLongest = 64;  // longer words are no typo of a key
  if (word.empty() || word.size() > kLongest) return "";
  const std::string w = lower(word);
  // One edit in a short word, up to a third of a long one.
  const std::size_t allowed = std::max<std::size_t>(1, std::min<std::size_t>(3, w.size() / 3));
  std::string best;
  std::size_t best_distance = allowed + 1;
  for (const std::string& k : known) {
    const std::size_t d = edit_distance(w, lower(k));
    if (d < best_distance) best = k, best_distance = d;
  }
  if (!best.empty()) return best;
  // A part left out or added: "illuminance" for "illuminance_lux", "paths" for "paths_per_sensor".
  auto contains_at_end = [](const std::string& whole, const std::string& part) {
    return part.size() >= 4 && whole.size() > part.size() &&
           (whole.compare(0, part.size(), part) == 0 || whole.compare(whole.size() - part.size(), part.size(), part) == 0);
  };
  for (const std::string& k : known) {
    const std::string lk = lower(k);
    if ((contains_at_end(lk, w) || contains_at_end(w, lk)) && (best.empty() || k.size() < best.size())) best = k;
  }
  return best;
}

std::string did_you_mean(const std::string& word, const std::vector<std::string>& known) {
  const std::string close = closest_word(word, known);
  return close.empty() ? "" : " (did you mean `" + close + "`?)";
}

std::optional<UnknownKey> find_unknown_key(const nlohmann::json& object, const std::vector<std::string>& known) {
  if (!object.is_object()) return std::nullopt;
  for (const auto& item : object.items()) {
    if (std::find(known.begin(), known.end(), item.key()) != known.end()) continue;
    std::string list;
    for (const auto& k : known) list += (list.empty() ? "" : ", ") + k;
    const std::string close = closest_word(item.key(), known);
    return UnknownKey{item.key(), "unknown key; " + (close.empty() ? std::string() : "did you mean `" + close + "`? ") +
                                      "(known: " + list + ")"};
  }
  return std::nullopt;
}

}  // namespace fenestra
