// FileWatch: which of a pipeline's files changed since the last look, by content. `watch` and
// `serve` poll it and reload only when a watched file's bytes changed (or it appeared or went
// away) — not when its time stamp moved with the same bytes, and not when the set of files grows
// (a first frame's shaders, a capture's reload).
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace rg {

class FileWatch {
public:
    // Compares `files` (Session::files()) with what was seen before: true when one seen before
    // has other contents now. Files not seen before are remembered as they are, files no longer
    // listed are forgotten. Reads a file only when its time stamp or size moved.
    bool changed(const std::vector<std::string>& files);
    // Remembers the files of `files` not seen before, as they are now, and leaves the others
    // (and what changed in them) for the next changed().
    void add(const std::vector<std::string>& files);

private:
    struct Seen {
        std::filesystem::file_time_type time{};
        uintmax_t size = 0;
        bool exists = false;
        uint64_t hash = 0;
    };
    static Seen look(const std::string& file, const Seen* before);
    std::map<std::string, Seen> m_seen;
};

}  // namespace rg
