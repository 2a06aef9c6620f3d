// pattern.comp in HLSL (glslang's HLSL front end): the same ramp and checker, exact in RGBA16F.
// A storage image declares its format with vk::image_format, as GLSL's layout(rgba16f) does.
[[vk::image_format("rgba16f")]] RWTexture2D<float4> pattern;

[numthreads(8, 8, 1)]
void main(uint3 id : SV_DispatchThreadID) {
    uint2 size;
    pattern.GetDimensions(size.x, size.y);
    if (id.x >= size.x || id.y >= size.y) return;
    int2 p = int2(id.xy);
    float checker = float(((p.x >> 3) + (p.y >> 3)) & 1);
    pattern[p] = float4(float(p.x & 63) / 64.0, float(p.y & 63) / 64.0, checker, 1.0);
}
