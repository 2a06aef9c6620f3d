#include "file_watch.h"

#include <fstream>
#include <iterator>

#include "core/hash.h"

namespace rg {

namespace fs = std::filesystem;

FileWatch::Seen FileWatch::look(const std::string& file, const Seen* before) {
    Seen s;
    std::error_code ec;
    s.time = fs::last_write_time(file, ec);
    s.exists = !ec;
    if (!s.exists) return s;
    s.size = fs::file_size(file, ec);
    if (before && before->exists && before->time == s.time && before->size == s.size) {
        s.hash = before->hash;
        return s;
    }
    std::ifstream in(file, std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    ContentHash h;
    h.str(bytes);
    s.hash = h.value();
    return s;
}

bool FileWatch::changed(const std::vector<std::string>& files) {
    std::map<std::string, Seen> now;
    bool any = false;
    for (const auto& f : files) {
        if (now.contains(f)) continue;
        auto it = m_seen.find(f);
        const Seen s = look(f, it == m_seen.end() ? nullptr : &it->second);
        if (it != m_seen.end() && (s.exists != it->second.exists || s.hash != it->second.hash))
            any = true;
        now.emplace(f, s);
    }
    m_seen = std::move(now);
    return any;
}

void FileWatch::add(const std::vector<std::string>& files) {
    for (const auto& f : files)
        if (!m_seen.contains(f)) m_seen.emplace(f, look(f, nullptr));
}

}  // namespace rg
