#pragma once
// ContentHash: a 64-bit key for disk caches of derived data (the once-per-build outputs of
// Executor::setOnceCache): FNV-1a's xor-multiply over 8-byte words (the tail byte by byte), each
// step followed by a xor-shift so that a word's high bits reach the low ones, and splitmix64's
// finaliser on the result. Every step is a bijection of the state, so inputs differing in one
// word always give different states. Word-wise it runs ~8× faster than byte-wise FNV-1a (a scene's vertices and textures are
// megabytes). Every variable-length field is length-prefixed, so fields cannot run into each other.
#include <cstdint>
#include <cstring>
#include <string_view>

namespace rg {

class ContentHash {
public:
    void bytes(const void* data, size_t n) {
        const auto* p = static_cast<const unsigned char*>(data);
        u64(n);
        for (; n >= 8; n -= 8, p += 8) {
            uint64_t w;
            std::memcpy(&w, p, 8);
            mix(w);
        }
        for (; n; --n, ++p) mix(*p);
    }
    void u64(uint64_t v) { mix(v); }
    void f32(float v) {
        uint32_t bits;
        std::memcpy(&bits, &v, 4);
        mix(bits);
    }
    void str(std::string_view s) { bytes(s.data(), s.size()); }
    uint64_t value() const {
        uint64_t z = m_h + 0x9e3779b97f4a7c15ull;
        z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
        z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
        return z ^ (z >> 31);
    }

private:
    void mix(uint64_t w) {
        m_h = (m_h ^ w) * 1099511628211ull;
        m_h ^= m_h >> 32;
    }
    uint64_t m_h = 14695981039346656037ull;
};

}  // namespace rg
