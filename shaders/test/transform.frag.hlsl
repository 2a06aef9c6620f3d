// transform.frag in HLSL (glslang's HLSL front end): the pattern texel for texel, mapped to
// (g, r, 1 - b, 1) * scale. Resources are bound by name, so they need no register; the
// texture becomes a combined image sampler.
Texture2D pattern;
cbuffer Params { float scale; };

float4 main(float4 position : SV_Position) : SV_Target {
    float4 c = pattern.Load(int3(int2(position.xy), 0));
    return float4(c.g, c.r, 1.0 - c.b, 1.0) * scale;
}
