#pragma once
// ContentHash: the one 64-bit content hash of rgraph's caches — SPIR-V modules, the once-per-build
// outputs (Executor::setOnceCache), baked lightmaps, generated layout headers, GPU scenes, watched
// files. XXH3 (Debian's libxxhash) in streaming mode: ~20 GB/s, so hashing a scene's megabytes of
// vertices and textures costs little. Every variable-length field is length-prefixed, so fields
// cannot run into each other; numbers go in as their bytes (little-endian on every target here).
#include <cstdint>
#include <cstdio>
#include <string>
#include <string_view>
#include <type_traits>

#include <xxhash.h>

namespace rg {

class ContentHash {
public:
    ContentHash() : m_state(XXH3_createState()) { XXH3_64bits_reset(m_state); }
    ~ContentHash() { XXH3_freeState(m_state); }
    ContentHash(const ContentHash& o) : m_state(XXH3_createState()) {
        XXH3_copyState(m_state, o.m_state);
    }
    ContentHash& operator=(const ContentHash& o) {
        if (this != &o) XXH3_copyState(m_state, o.m_state);
        return *this;
    }

    void bytes(const void* data, size_t n) {
        u64(n);
        XXH3_64bits_update(m_state, data, n);
    }
    void u64(uint64_t v) { XXH3_64bits_update(m_state, &v, sizeof v); }
    void f32(float v) { XXH3_64bits_update(m_state, &v, sizeof v); }
    // A fixed-size value of plain data, as its bytes (no padding in the types it is used with).
    template <class T>
    void pod(const T& v) {
        static_assert(std::is_trivially_copyable_v<T>);
        XXH3_64bits_update(m_state, &v, sizeof v);
    }
    void str(std::string_view s) { bytes(s.data(), s.size()); }
    uint64_t value() const { return XXH3_64bits_digest(m_state); }
    // The value as 16 hex digits: a cache file's or folder's name.
    std::string hex() const {
        char s[17];
        std::snprintf(s, sizeof s, "%016llx", static_cast<unsigned long long>(value()));
        return s;
    }

private:
    XXH3_state_t* m_state;
};

}  // namespace rg
