// A temporary file's name beside the file it will be renamed to: what every cache and output
// writer uses so that a reader never sees half a file (the rename is atomic) and no two writers —
// threads, processes, or workers on other machines sharing the cache folder — share a temporary.
#pragma once

#include <atomic>
#include <cstdint>
#include <string>

#include <unistd.h>

namespace rg {

// `path` + ".tmp-HOST-PID-N": the host's name, this process's id and a count within it.
inline std::string tempPathBeside(const std::string& path) {
    static std::atomic<uint64_t> counter{0};
    char host[64] = {};
    if (::gethostname(host, sizeof host - 1) != 0) host[0] = '\0';
    return path + ".tmp-" + host + "-" + std::to_string(::getpid()) + "-" +
           std::to_string(counter.fetch_add(1));
}

}  // namespace rg
