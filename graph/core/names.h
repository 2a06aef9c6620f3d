// Names in error messages: the closest known name to a misspelt one ("did you mean ...?") and
// quoted lists. One place for the compiler, the executor, the Lua schemas and the scene loaders.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace rg {

// Levenshtein distance (insertions, deletions, substitutions).
size_t editDistance(const std::string& a, const std::string& b);

// The candidate closest to `name` at an edit distance below `below`, the earliest on ties; "" when
// none. Empty candidates are skipped.
std::string closestName(const std::string& name, const std::vector<std::string>& candidates,
                        size_t below);
// The same with the messages' usual limit: within 2 edits, or 1 for names of up to 3 characters.
std::string closestName(const std::string& name, const std::vector<std::string>& candidates);

// " (did you mean 'x'?)" for closestName(name, candidates), or "".
std::string suggestion(const std::string& name, const std::vector<std::string>& candidates);

// 'a', 'b', 'c'
std::string joinQuoted(const std::vector<std::string>& names);

}  // namespace rg
