// Near-name suggestions for error messages (near_names.hpp).
#include "reading/near_names.hpp"

#include <algorithm>
#include <cctype>
#include <utility>

namespace sympl::app {

namespace {
std::string lower(std::string s) {
    for (char& c : s) c = char(std::tolower(static_cast<unsigned char>(c)));
    return s;
}
}  // namespace

std::size_t edit_distance(const std::string& a, const std::string& b) {
    // d[i][j]: edits from a's first i letters to b's first j, three rows kept.
    const std::size_t n = b.size();
    std::vector<std::size_t> before(n + 1), previous(n + 1), current(n + 1);
    for (std::size_t j = 0; j <= n; ++j) previous[j] = j;
    for (std::size_t i = 1; i <= a.size(); ++i) {
        current[0] = i;
        for (std::size_t j = 1; j <= n; ++j) {
            const std::size_t replace = previous[j - 1] + (a[i - 1] == b[j - 1] ? 0 : 1);
            current[j] = std::min({previous[j] + 1, current[j - 1] + 1, replace});
            if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1])
                current[j] = std::min(current[j], before[j - 2] + 1);
        }
        before.swap(previous);
        previous.swap(current);
    }
    return previous[n];
}

std::vector<std::string> near_names(const std::string& given, const std::vector<std::string>& known) {
    const std::string g = lower(given);
    if (g.empty()) return {};
    const std::size_t allowed = g.size() <= 4 ? 1 : g.size() <= 8 ? 2 : 3;
    std::vector<std::pair<std::size_t, std::string>> near;
    for (const auto& name : known) {
        if (name == given) continue;
        const std::string k = lower(name);
        // The distance is at least the lengths' difference: past `allowed`,
        // the O(|g| |k|) table is not needed (a 1 MB name against each of
        // the catalog's took seconds, a minute under the sanitizers).
        const std::size_t gap = g.size() > k.size() ? g.size() - k.size() : k.size() - g.size();
        std::size_t d = gap > allowed ? allowed + 1 : edit_distance(g, k);
        // A name's start or end given in full ("yoshida" of "yoshida_4") counts as near, behind the typos.
        if (d > allowed && g.size() >= 4 && (k.starts_with(g) || k.ends_with(g))) d = allowed + 1;
        else if (d > allowed) continue;
        near.emplace_back(d, name);
    }
    std::stable_sort(near.begin(), near.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
    std::vector<std::string> out;
    for (const auto& [d, name] : near)
        if (out.size() < 3 && d <= near.front().first + 1) out.push_back(name);
    return out;
}

std::string did_you_mean(const std::string& given, const std::vector<std::string>& known) {
    const auto near = near_names(given, known);
    if (near.empty()) return "";
    std::string s = "did you mean ";
    for (std::size_t i = 0; i < near.size(); ++i)
        s += (i == 0 ? "" : i + 1 == near.size() ? " or " : ", ") + ("'" + near[i] + "'");
    return s + "? ";
}

std::string expected_one_of(const std::string& given, const std::vector<std::string>& known) {
    std::string list;
    for (const auto& n : known) list += (list.empty() ? "" : ", ") + n;
    return did_you_mean(given, known) + "expected one of: " + list;
}

}  // namespace sympl::app
