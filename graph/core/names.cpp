#include "names.h"

#include <algorithm>
#include <utility>

namespace rg {

size_t editDistance(const std::string& a, const std::string& b) {
    std::vector<size_t> prev(b.size() + 1), cur(b.size() + 1);
    for (size_t j = 0; j <= b.size(); ++j) prev[j] = j;
    for (size_t i = 1; i <= a.size(); ++i) {
        cur[0] = i;
        for (size_t j = 1; j <= b.size(); ++j) {
            const size_t subst = prev[j - 1] + (a[i - 1] == b[j - 1] ? 0 : 1);
            cur[j] = std::min({prev[j] + 1, cur[j - 1] + 1, subst});
        }
        std::swap(prev, cur);
    }
    return prev[b.size()];
}

std::string closestName(const std::string& name, const std::vector<std::string>& candidates,
                        size_t below) {
    std::string best;
    for (const auto& c : candidates) {
        if (c.empty()) continue;
        if (const size_t d = editDistance(name, c); d < below) {
            below = d;
            best = c;
        }
    }
    return best;
}

std::string closestName(const std::string& name, const std::vector<std::string>& candidates) {
    return closestName(name, candidates, name.size() <= 3 ? 2 : 3);
}

std::string suggestion(const std::string& name, const std::vector<std::string>& candidates) {
    const std::string best = closestName(name, candidates);
    return best.empty() ? "" : " (did you mean '" + best + "'?)";
}

std::string joinQuoted(const std::vector<std::string>& names) {
    std::string s;
    for (const auto& n : names) s += (s.empty() ? "'" : ", '") + n + "'";
    return s;
}

}  // namespace rg
