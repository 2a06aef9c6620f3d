// Shadows of the lights (seed 002 §4.10.4): the sun's cascaded shadow maps and the local lights'
// (scripts/shadows.lua). A lighting shader built with RG_SHADOWS reads the cascades
// (`sun_cascades`, written each frame by shaders/shadows/sun_cascades.comp) and either the maps
// (`sun_shadow0` .. one per cascade, each drawn by a shadow scene pass: a forward pass) or, with
// RG_SUN_MASK, the sun's visibility per pixel that the mask passes filtered from them before the
// lighting (`sun_visibility`: a deferred lighting pass), and rgEvaluateLight (lib/lighting.glsl)
// multiplies the sun's diffuse and specular illuminance by rgShadow.
//
// Filtering: percentage-closer soft shadows for a disk light (the sun of angular radius σ,
// lst:6): an 8-tap blocker search finds the occluder nearest the receiver, at depth d_b, the penumbra is
// then (d_r − d_b) · 2 tan σ wide at the receiver (similar triangles through the disk), and the
// PCF kernel covers it — contact-hardening: sharp where the caster touches, soft far from it.
// (PCSS's usual mean blocker depth over-widens the penumbra under a caster tilted against the
// light — the box's top at 45°: 0.42 m against the geometry's 0.256 m; the nearest gives 0.22 m.)
#ifndef RG_SHADOWS_GLSL
#define RG_SHADOWS_GLSL
#extension GL_EXT_control_flow_attributes : require

#ifndef RG_SHADOW_BINDING
#define RG_SHADOW_BINDING 10  // sun_shadow at 10, sun_cascades at 11
#endif
#define RG_MAX_CASCADES 4
// The PCF kernel's taps (also in the cascades' bias.w, which sun_cascades.comp writes).
#define RG_SUN_PCF_TAPS 16

// std430; shaders/shadows/sun_cascades.comp writes it.
struct RgCascades {
    mat4 viewProj[RG_MAX_CASCADES];  // world → the cascade's clip space (orthographic, depth 0..1)
    vec4 splitFar;    // view distance (m) where each cascade ends
    vec4 texelWorld;  // world size (m) of one texel of each cascade
    vec4 depthRange;  // metres along the light that depth 0..1 spans, per cascade
    vec4 info;        // x: cascades in use (0: no sun), y: the sun's light index, z: map size (texels), w: tan σ
    vec4 bias;        // x: receiver depth bias (m), y: normal offset (texels), z: softness (× the physical penumbra), w: PCF taps (RG_SUN_PCF_TAPS)
};

// ---- The local lights' shadow views (passes/gpu_scene_lights.cpp updateShadowViews) -------------------
// Each local light with `shadow = true` whose range reaches the view gets one perspective view (a
// spot of outer angle ≤ 60°) or six (a cube: +x, −x, +y, −y, +z, −z, each a little wider than
// 90° so filter taps near a face's edge stay on it), drawn into the layers of `local_shadow` by
// the scene pass with views = "lights". RG_MAX_SHADOW_VIEWS: lib/limits.h.
#include "lib/limits.h"
struct RgShadowView {
    mat4 viewProj;  // world → the view's clip space (perspective, depth 0..1)
    vec4 position;  // xyz: the light's position; w: the near plane (m)
    vec4 params;    // x: the far plane (m); y: tan of half the field of view; z: the light's radius (m); w: light index
};
// (Not in the sun's mask passes, which filter the sun alone: sun_classify.frag, sun_mask.frag.)
#if defined(RG_SHADOW_VIEWS) || \
    (defined(RG_SHADOWS) && defined(RG_SCENE_SHADOWED_LIGHTS) && !defined(RG_SUN_CASCADES_ONLY) && !defined(RG_SUN_MASK_WRITER))
#define RG_LOCAL_SHADOWS 1
#ifndef RG_SHADOW_VIEWS_BINDING
#define RG_SHADOW_VIEWS_BINDING 18
#endif
layout(set = RG_CAMERA_SET, binding = RG_SHADOW_VIEWS_BINDING, std430) readonly buffer ShadowViews {
    uvec4 count;                       // x: views this frame
    RgShadowView view[RG_MAX_SHADOW_VIEWS];
    ivec4 lightViews[];  // per light of the scene: first view (−1: none), how many
} rgShadowViews;

// The distance along view v's axis of the depth `d` its map holds (the perspective depth, linearised).
float rgShadowViewDistance(RgShadowView v, float d) {
    float nearPlane = v.position.w, farPlane = v.params.x;
    return nearPlane * farPlane / (farPlane - d * (farPlane - nearPlane));
}
#endif

#ifdef RG_SHADOWS
// The maps: one per cascade, each a texture of its own (scripts/shadows.lua), so that the graph can
// place a cascade's map in the memory of the one before once that one's pixels are filtered.
#ifndef RG_SUN_CASCADES
#define RG_SUN_CASCADES 1
#endif
#ifndef RG_SUN_MAPS_BINDING
#define RG_SUN_MAPS_BINDING 28  // sun_shadow1 .. sun_shadow3 at 28, 29, 30 (sun_shadow0 at RG_SHADOW_BINDING)
#endif
#ifndef RG_SUN_VISIBILITY_BINDING
#define RG_SUN_VISIBILITY_BINDING 31  // sun_visibility_half at 32
#endif
// A uniform block (the passes read `sun_cascades` as = "uniform"): every pixel reads it at the
// same offsets, which lavapipe loads once for all the pixels it shades together — a storage
// buffer it reads lane by lane in a fragment shader (the mask passes' ~25 floats).
layout(set = 0, binding = RG_SHADOW_BINDING + 1, std140) uniform sun_cascades { RgCascades c; } rgCascades;
#if defined(RG_SUN_CASCADES_ONLY)
// The cascades alone (shaders/shadows/sun_classify.frag): no map.
#elif defined(RG_SUN_MASK_WRITER)
// The mask pass of one cascade (shaders/shadows/sun_mask.frag): that cascade's map, bound by the
// pass (bind = { sun_shadow = "sun_shadowN" }).
layout(set = 0, binding = RG_SHADOW_BINDING) uniform sampler2D sun_shadow;
#elif defined(RG_SUN_MASK)
// A deferred lighting pass (shadows.masked): the sun's visibility per pixel, filtered by the mask
// passes before the lighting; no map.
layout(set = 0, binding = RG_SUN_VISIBILITY_BINDING) uniform sampler2D sun_visibility;
layout(set = 0, binding = RG_SUN_VISIBILITY_BINDING + 1) uniform sampler2D sun_visibility_half;
#include "lib/upsample.glsl"
#else
// Every cascade's map (a forward pass, the debug views).
layout(set = 0, binding = RG_SHADOW_BINDING) uniform sampler2D sun_shadow0;
#if RG_SUN_CASCADES > 1
layout(set = 0, binding = RG_SUN_MAPS_BINDING) uniform sampler2D sun_shadow1;
#endif
#if RG_SUN_CASCADES > 2
layout(set = 0, binding = RG_SUN_MAPS_BINDING + 1) uniform sampler2D sun_shadow2;
#endif
#if RG_SUN_CASCADES > 3
layout(set = 0, binding = RG_SUN_MAPS_BINDING + 2) uniform sampler2D sun_shadow3;
#endif
#endif

// 16 points of a golden-angle spiral in the unit disk (equal area per point).
vec2 rgShadowTap(int k) {
    float r = sqrt((float(k) + 0.5) / 16.0);
    float a = float(k) * 2.39996323;
    return r * vec2(cos(a), sin(a));
}

// The cascade a point at view distance `viewDepth` falls in, RG_MAX_CASCADES beyond the last:
// the splits ascend, so it is how many of the used ones lie at or before it (no loop).
int rgCascadeOf(float viewDepth) {
    vec4 used = step(vec4(0.5, 1.5, 2.5, 3.5), vec4(rgCascades.c.info.x));
    float passed = dot(step(rgCascades.c.splitFar, vec4(viewDepth)), used);
    return passed < rgCascades.c.info.x - 0.5 ? int(passed) : RG_MAX_CASCADES;
}
// The cascade of world position P.
int rgCascadeAt(vec3 P) { return rgCascadeOf(rgViewDepth(P)); }

// Visibility of the sun (0 shadowed .. 1 lit) at world position P with normal N in cascade ci,
// whose map is `map`.
float rgSunShadowIn(sampler2D map, int ci, vec3 P, vec3 N) {
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
    // A point whose normal faces away from the sun is occluded by its own surface: 0, whatever
    // the map says. (Near the terminator the map's depth there is the near side of the same
    // surface, closer than the biases, and a lookup would call the point lit: a band of full sun
    // past the terminator.)
    if (nf >= 0.0) return 0.0;
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
        float d = textureLod(map, uv + o, 0.0).r;
        if (d < receiver + dot(slope, o)) { blockers += 1.0; blockerDepth = max(blockerDepth, d); }
    }
    // The kernel's radius at the receiver, in texels: half the penumbra (d_r − d_b) · 2 tan σ, so
    // that the disk of taps convolves the edge as the sun's disk does; at least a texel.
    float penumbra = clamp((receiver - blockerDepth) * range * tanSigma / texel, 1.0, 64.0);
    // No blocker: lit, without the kernel. An `if` would not spare the kernel on a CPU rasteriser
    // (lavapipe runs both sides of a branch for its block of pixels), but it leaves a loop as
    // soon as no pixel of the block is still in it — so the kernel is a loop the compiler must not
    // unroll ([[dont_unroll]]), left at its first tap where no pixel of the block found a blocker:
    // most of a sunlit frame (lighting_standard −4.5 to −9 ms at 1280×720, the same image). Its
    // bound is the constant, not the count in the cascades: with the bound read from memory,
    // lavapipe (Mesa 22.3) kept ~0.5 MiB per mask pass and frame that it never freed (a served
    // pipeline's memory grew by ~1.3 MiB a frame), the same image and time otherwise. The taps walk
    // the spiral of rgShadowTap by turning one step of the golden angle each (its sine and cosine
    // once, not per tap).
    const float golden = 2.39996323;
    const mat2 turn = mat2(cos(golden), sin(golden), -sin(golden), cos(golden));
    const int taps = RG_SUN_PCF_TAPS;
    vec2 direction = vec2(1.0, 0.0);
    float lit = 0.0;
    [[dont_unroll]] for (int k = 0; k < taps; ++k, direction = turn * direction) {
        if (blockers == 0.0) { lit = float(taps); break; }
        vec2 o = sqrt((float(k) + 0.5) / float(taps)) * direction * penumbra / size;
        float d = textureLod(map, uv + o, 0.0).r;
        lit += d < receiver + dot(slope, o) ? 0.0 : 1.0;
    }
    return lit / float(taps);
}

#if defined(RG_SUN_MASK)
// The sun's visibility at the shaded pixel, as the mask passes filtered it at its G-buffer normal:
// per pixel in `sun_visibility`, or at half resolution in `sun_visibility_half`, upsampled by view
// distance. The mode not in use leaves its mask cleared to lit (1; the half one at no distance,
// which upsamples to 1), so the smaller of the two is the one in use, whichever it is — no
// parameter to read, and a CPU rasteriser would run both sides of a branch anyway.
//
// With RG_SSAO_SUN (scripts/ao.lua, when the shadows module came first) the AO's blur copied the
// half-resolution mask into its own target's b, and the upsample is the AO's own (lib/ibl.glsl's
// rgAmbientOcclusion: the same call, computed once): ~3.5 ms of lighting_standard at 1280×720 on
// lavapipe.
float rgSunVisibility(vec3 P, vec3 N) {
    ivec2 pixel = ivec2(gl_FragCoord.xy);
#if defined(RG_SSAO) && defined(RG_SSAO_SUN)
    float halfResolution = rgUpsampleHalf4(ao_filtered, pixel, rgViewDepth(P)).b;
#else
    float halfResolution = rgUpsampleHalf(sun_visibility_half, pixel, rgViewDepth(P));
#endif
    return min(texelFetch(sun_visibility, pixel, 0).r, halfResolution);
}
#elif !defined(RG_SUN_MASK_WRITER) && !defined(RG_SUN_CASCADES_ONLY)
// The sun's visibility at P from the map of P's cascade, 1 beyond the shadow distance.
float rgSunShadow(vec3 P, vec3 N) {
    int ci = rgCascadeAt(P);
    float v = 1.0;
    if (ci == 0) v = rgSunShadowIn(sun_shadow0, 0, P, N);
#if RG_SUN_CASCADES > 1
    else if (ci == 1) v = rgSunShadowIn(sun_shadow1, 1, P, N);
#endif
#if RG_SUN_CASCADES > 2
    else if (ci == 2) v = rgSunShadowIn(sun_shadow2, 2, P, N);
#endif
#if RG_SUN_CASCADES > 3
    else if (ci == 3) v = rgSunShadowIn(sun_shadow3, 3, P, N);
#endif
    return v;
}
// The sun's visibility at P, once per shaded point (rgEvaluateLight's last argument).
float rgSunVisibility(vec3 P, vec3 N) { return rgCascades.c.info.x > 0.0 ? rgSunShadow(P, N) : 1.0; }
#endif

// The visibility of light i given the sun's (other lights cast no shadow yet).
float rgShadow(uint light, float sunVisibility) {
    return rgCascades.c.info.x > 0.0 && light == uint(rgCascades.c.info.y + 0.5) ? sunVisibility : 1.0;
}
#else
float rgSunVisibility(vec3 P, vec3 N) { return 1.0; }
float rgShadow(uint light, float sunVisibility) { return 1.0; }
#endif

// Visibility (0 shadowed .. 1 lit) of local light `light` at P with normal N, from its shadow
// views — 1 for a light without (no shadow, out of view this frame, or beyond the layers the
// pipeline declared). Percentage-closer soft shadows: a blocker search, then PCF over the half
// penumbra a light of its radius gives at the receiver, (d_r − d_b) / d_b · radius (similar
// triangles through the light's disk), at least a texel: hard-edged, filtered, for a punctual
// light. Here d_b is PCSS's mean blocker distance: under the box of tests/gpu/test_shadows.cpp it
// gives the geometric penumbra within 2 % (the nearest blocker, the sun's choice, gave 0.59 of it:
// the cube face's depth axis is not the ray). Depths compare as distances along the view's axis.
#ifndef RG_LOCAL_SHADOW_NORMAL_OFFSET
#define RG_LOCAL_SHADOW_NORMAL_OFFSET 1.5  // texels at the receiver
#endif
#ifndef RG_LOCAL_SHADOW_BIAS
#define RG_LOCAL_SHADOW_BIAS 1.5           // texels at the receiver
#endif
#if defined(RG_SHADOWS) && defined(RG_LOCAL_SHADOWS)
#ifndef RG_LOCAL_SHADOW_BINDING
#define RG_LOCAL_SHADOW_BINDING 19
#endif
layout(set = 0, binding = RG_LOCAL_SHADOW_BINDING) uniform sampler2DArray local_shadow;

float rgLocalShadow(uint light, vec3 P, vec3 N) {
    ivec4 lv = rgShadowViews.lightViews[light];
    vec3 a = P - rgShadowViews.view[max(lv.x, 0)].position.xyz;
    vec3 m = abs(a);
    // A cube's face: the major axis of the direction from the light.
    int face = lv.y < 6 ? 0 : m.x >= m.y && m.x >= m.z ? (a.x > 0.0 ? 0 : 1) : m.y >= m.z ? (a.y > 0.0 ? 2 : 3) : (a.z > 0.0 ? 4 : 5);
    int vi = max(lv.x, 0) + face;
    ivec3 mapSize = textureSize(local_shadow, 0);
    RgShadowView v = rgShadowViews.view[min(vi, RG_MAX_SHADOW_VIEWS - 1)];
    float size = float(mapSize.x);
    float nearPlane = v.position.w;
    float receiverDistance = max((v.viewProj * vec4(P, 1.0)).w, nearPlane);
    float texel = 2.0 * v.params.y * receiverDistance / size;  // metres a texel spans at the receiver
    vec4 clip = v.viewProj * vec4(P + N * (RG_LOCAL_SHADOW_NORMAL_OFFSET * texel), 1.0);
    vec2 uv = clip.xy / clip.w * 0.5 + 0.5;
    float receiver = clip.w - RG_LOCAL_SHADOW_BIAS * texel;
#if RG_SCENE_SHADOWED_LIGHTS > 1
    float radius = v.params.z;
    float searchTexels = clamp(radius / texel, 1.0, 64.0);
    float blockers = 0.0, blockerDistance = 0.0;
    for (int k = 0; k < 16; k += 2) {
        float d = textureLod(local_shadow, vec3(uv + rgShadowTap(k) * searchTexels / size, float(vi)), 0.0).r;
        float z = rgShadowViewDistance(v, d);
        if (z < receiver) { blockers += 1.0; blockerDistance += z; }
    }
    blockerDistance /= max(blockers, 1.0);
    float penumbra = clamp(radius * (receiver - blockerDistance) / max(blockerDistance, nearPlane) / texel, 1.0, 64.0);
    const int taps = 16, tapStep = 1;
#else
    // Only punctual lights cast shadows in this scene: no penumbra to find, a 1.5-texel kernel of
    // 8 taps (every other of the spiral) filters the edge.
    float penumbra = 1.5;
    const int taps = 16, tapStep = 2;
#endif
    float lit = 0.0;
    for (int k = 0; k < taps; k += tapStep) {
        float d = textureLod(local_shadow, vec3(uv + rgShadowTap(k) * penumbra / size, float(vi)), 0.0).r;
        lit += rgShadowViewDistance(v, d) < receiver ? 0.0 : 1.0;
    }
    bool valid = lv.y > 0 && vi < mapSize.z && clip.w > nearPlane;
    return valid ? lit * float(tapStep) / float(taps) : 1.0;
}
#else
float rgLocalShadow(uint light, vec3 P, vec3 N) { return 1.0; }
#endif

#endif
