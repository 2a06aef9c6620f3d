// Reading a whole file at once: its size first, then one read into storage of that size (an
// istreambuf_iterator copies a character at a time: ~0.1 s for a 60 MB glTF, read twice at load).
#pragma once

#include <fstream>
#include <string>

namespace rg {

// The bytes of an open binary stream from its current position to its end into `out` (a
// std::string or std::vector of a byte type); false when reading fails.
template <typename Bytes>
bool readWhole(std::ifstream& in, Bytes& out) {
    const std::streampos start = in.tellg();
    in.seekg(0, std::ios::end);
    const std::streampos end = in.tellg();
    if (start < 0 || end < start) return false;
    in.seekg(start);
    out.resize(static_cast<size_t>(end - start));
    if (!out.empty()) in.read(reinterpret_cast<char*>(out.data()), std::streamsize(out.size()));
    return !in.bad() && in.gcount() == std::streamsize(out.size());
}

}  // namespace rg
