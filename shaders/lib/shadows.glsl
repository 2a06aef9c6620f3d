// Shadows of the lights (seed 002 §4.10.4): today the sun's cascaded shadow map
// (scripts/shadows.lua). A lighting shader built with RG_SHADOWS reads the cascades
// (`sun_cascades`, written each frame by shaders/shadows/sun_cascades.comp) and the map
// (`sun_shadow`, one layer per cascade, drawn by the shadow scene pass), and rgEvaluateLight
// (lib/lighting.glsl) multiplies the sun's diffuse and specular illuminance by rgShadow.
//
// Filtering: percentage-closer soft shadows for a disk light (the sun of angular radius σ,
// lst:6): an 8-tap blocker search finds the occluder nearest the receiver, at depth d_b, the penumbra is
// then (d_r − d_b) · 2 tan σ wide at the receiver (similar triangles through the disk), and the
// PCF kernel covers it — contact-hardening: sharp where the caster touches, soft far from it.
// (PCSS's usual mean blocker depth over-widens the penumbra under a caster tilted against the
// light — the box's top at 45°: 0.42 m against the geometry's 0.256 m; the nearest gives 0.22 m.)
#ifndef RG_SHADOWS_GLSL
#define RG_SHADOWS_GLSL

#ifndef RG_SHADOW_BINDING
#define RG_SHADOW_BINDING 10  // sun_shadow at 10, sun_cascades at 11
#endif
#define RG_MAX_CASCADES 4

// std430; shaders/shadows/sun_cascades.comp writes it.
struct RgCascades {
    mat4 viewProj[RG_MAX_CASCADES];  // world → the cascade's clip space (orthographic, depth 0..1)
    vec4 splitFar;    // view distance (m) where each cascade ends
    vec4 texelWorld;  // world size (m) of one texel of each cascade
    vec4 depthRange;  // metres along the light that depth 0..1 spans, per cascade
    vec4 info;        // x: cascades in use (0: no sun), y: the sun's light index, z: map size (texels), w: tan σ
    vec4 bias;        // x: receiver depth bias (m), y: normal offset (texels), z: softness (× the physical penumbra)
};

#ifdef RG_SHADOWS
layout(set = 0, binding = RG_SHADOW_BINDING) uniform sampler2DArray sun_shadow;
layout(set = 0, binding = RG_SHADOW_BINDING + 1, std430) readonly buffer sun_cascades { RgCascades c; } rgCascades;

// 16 points of a golden-angle spiral in the unit disk (equal area per point).
vec2 rgShadowTap(int k) {
    float r = sqrt((float(k) + 0.5) / 16.0);
    float a = float(k) * 2.39996323;
    return r * vec2(cos(a), sin(a));
}

// The cascade a point at view distance `viewDepth` falls in, RG_MAX_CASCADES beyond the last.
int rgCascadeOf(float viewDepth) {
    int count = int(rgCascades.c.info.x + 0.5);
    for (int i = 0; i < count; ++i)
        if (viewDepth < rgCascades.c.splitFar[i]) return i;
    return RG_MAX_CASCADES;
}

// Visibility of the sun (0 shadowed .. 1 lit) at world position P with normal N.
float rgSunShadow(vec3 P, vec3 N) {
    float viewDepth = -(camera.view * vec4(P, 1.0)).z;
    int ci = rgCascadeOf(viewDepth);
    if (ci >= RG_MAX_CASCADES) return 1.0;  // beyond the shadow distance
    float texel = rgCascades.c.texelWorld[ci];
    float size = rgCascades.c.info.z;
    // Normal offset: move the lookup off the surface by a few texels (no acne at grazing light).
    vec3 Po = P + N * (rgCascades.c.bias.y * texel);
    mat4 m = rgCascades.c.viewProj[ci];
    vec4 clip = m * vec4(Po, 1.0);
    vec2 uv = clip.xy * 0.5 + 0.5;
    float range = rgCascades.c.depthRange[ci];
    float receiver = clip.z - rgCascades.c.bias.x / range;
    // The receiver's plane in the map (receiver-plane depth bias): the depth a tap at uv offset
    // δ compares against is receiver + dot(slope, δ), so a wide kernel over a surface tilted
    // against the light does not shadow the surface itself. The rows of the cascade's matrix are
    // the light's axes x/r, y/r and its direction f/range; a surface facing the light has n_f < 0.
    vec3 row0 = vec3(m[0][0], m[1][0], m[2][0]), row1 = vec3(m[0][1], m[1][1], m[2][1]), row2 = vec3(m[0][2], m[1][2], m[2][2]);
    float r = 1.0 / length(row0);
    vec2 nxy = vec2(dot(N, row0), dot(N, row1)) * r;  // N · x, N · y
    float nf = dot(N, row2) * range;                  // N · f
    nf = sign(nf) * max(abs(nf), 0.2);                // grazing: a bounded slope
    // A uv offset δ is 2r·δ metres across the light; the plane's depth changes by −(N·Δ)/(N·f).
    vec2 slope = -2.0 * r * nxy / (nf * range);
    // Blocker search over the widest penumbra a caster at the top of the depth range could cast
    // (radius: distance to the caster × tan σ — half the penumbra's width).
    float tanSigma = rgCascades.c.info.w * rgCascades.c.bias.z;
    float searchTexels = clamp(receiver * range * tanSigma / texel, 1.0, 64.0);
    float blockers = 0.0, blockerDepth = 0.0;
    for (int k = 0; k < 16; k += 2) {  // every other tap of the spiral: 8 spread over the disk
        vec2 o = rgShadowTap(k) * searchTexels / size;
        float d = textureLod(sun_shadow, vec3(uv + o, float(ci)), 0.0).r;
        if (d < receiver + dot(slope, o)) { blockers += 1.0; blockerDepth = max(blockerDepth, d); }
    }
    if (blockers == 0.0) return 1.0;
    // The kernel's radius at the receiver, in texels: half the penumbra (d_r − d_b) · 2 tan σ, so
    // that the disk of taps convolves the edge as the sun's disk does; at least a texel.
    float penumbra = clamp((receiver - blockerDepth) * range * tanSigma / texel, 1.0, 64.0);
    float lit = 0.0;
    for (int k = 0; k < 16; ++k) {
        vec2 o = rgShadowTap(k) * penumbra / size;
        float d = textureLod(sun_shadow, vec3(uv + o, float(ci)), 0.0).r;
        lit += d < receiver + dot(slope, o) ? 0.0 : 1.0;
    }
    return lit / 16.0;
}

// The sun's visibility at P, once per shaded point (rgEvaluateLight's last argument).
float rgSunVisibility(vec3 P, vec3 N) { return rgCascades.c.info.x > 0.0 ? rgSunShadow(P, N) : 1.0; }

// The visibility of light i given the sun's (other lights cast no shadow yet).
float rgShadow(uint light, float sunVisibility) {
    return rgCascades.c.info.x > 0.0 && light == uint(rgCascades.c.info.y + 0.5) ? sunVisibility : 1.0;
}
#else
float rgSunVisibility(vec3 P, vec3 N) { return 1.0; }
float rgShadow(uint light, float sunVisibility) { return 1.0; }
#endif

#endif
