// Deterministic per-pixel test values for G-buffer layout tests. test_layout_gpu.cpp has a C++
// copy of every function: the values are built from integer hashes with exact float steps
// (an integer converted to float, scaled by a power of two), so GPU and CPU agree bit for bit.
#ifndef RG_TEST_LAYOUT_HASH_GLSL
#define RG_TEST_LAYOUT_HASH_GLSL

// lowbias32 (C. Wellons): a full-avalanche 32-bit integer hash.
uint rg_testHash(uint x) {
    x ^= x >> 16;
    x *= 0x7feb352du;
    x ^= x >> 15;
    x *= 0x846ca68bu;
    x ^= x >> 16;
    return x;
}
// 32 random bits for component k of channel `channel` at pixel p.
uint rg_testBits(uvec2 p, uint channel, uint k) {
    return rg_testHash(rg_testHash(p.x + 4096u * p.y) ^ ((channel * 4u + k) * 0x9e3779b9u));
}
// n / 8192 for an integer n in [lo, hi]: exact in float.
float rg_testSteps(uint h, int lo, int hi) { return float(int(h % uint(hi - lo + 1)) + lo) * (1.0 / 8192.0); }
// unorm and srgb inputs: [-0.1, 1.1], so some are clamped.
float rg_testUnorm(uvec2 p, uint channel, uint k) { return rg_testSteps(rg_testBits(p, channel, k), -819, 9011); }
// snorm inputs: [-1.1, 1.1].
float rg_testSnorm(uvec2 p, uint channel, uint k) { return rg_testSteps(rg_testBits(p, channel, k), -9011, 9011); }
// A direction, not normalised, components in [-1, 1] (never all zero).
vec3 rg_testDirection(uvec2 p, uint channel) {
    vec3 d = vec3(rg_testSteps(rg_testBits(p, channel, 0u), -8192, 8192), rg_testSteps(rg_testBits(p, channel, 1u), -8192, 8192),
                  rg_testSteps(rg_testBits(p, channel, 2u), -8192, 8192));
    return d == vec3(0.0) ? vec3(0.0, 0.0, 1.0) : d;
}
vec3 rg_testColour(uvec2 p, uint channel) {
    return vec3(rg_testUnorm(p, channel, 0u), rg_testUnorm(p, channel, 1u), rg_testUnorm(p, channel, 2u));
}
// uint inputs: [0, 2^bits], so the largest is clamped (bits < 32).
uint rg_testUint(uvec2 p, uint channel, uint k, uint bits) {
    uint h = rg_testBits(p, channel, k);
    return bits >= 32u ? h : h % ((1u << bits) + 1u);
}
// float inputs: n * 2^e, n in [-32768, 32767], e in [-12, 2]: |x| >= 2^-12 when not 0 (above the
// half-float subnormals, which a GPU may flush) and up to 131068 (clamped for 16-bit formats).
float rg_testFloat(uvec2 p, uint channel, uint k) {
    uint h = rg_testBits(p, channel, k);
    return ldexp(float(int(h & 0xffffu) - 32768), int((h >> 16) % 15u) - 12);
}
#endif
