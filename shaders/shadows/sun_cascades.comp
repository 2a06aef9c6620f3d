#version 460
// The sun's shadow cascades for this frame (seed 002 §4.10.4; lib/shadows.glsl reads them).
//  - splits: the practical scheme, λ · log + (1 − λ) · uniform between the camera's near plane and
//    Params.shadow_distance (Params.shadow_split_lambda = λ);
//  - each cascade covers the bounding sphere of its slice of the view frustum — its radius depends
//    only on the slice and the field of view, so it does not change as the camera turns or moves;
//  - the sphere's centre is snapped to whole texels in the light's frame, so a moving camera moves
//    the map by whole texels and shadow edges stay still;
//  - depth spans the scene's bounds along the light (every caster between the sun and the slice).
// One invocation; RG_CASCADES (1..4) and RG_SHADOW_SIZE (texels) come from scripts/shadows.lua.
#include "lib/scene.glsl"
#include "lib/shadows.glsl"
#define RG_GLOBAL_LIGHTS  // the scene's GlobalLights list: the sun is among the few lights there
#include "lib/light_tiles.glsl"

layout(local_size_x = 1) in;
layout(set = 0, binding = 0, std430) writeonly buffer sun_cascades { RgCascades c; } out_;
layout(set = 0, binding = 1) uniform Params {
    float shadow_distance;
    float shadow_split_lambda;
    float shadow_depth_bias;
    float shadow_normal_offset;
    float shadow_softness;
} params;

void main() {
    RgCascades r;
    for (int i = 0; i < RG_MAX_CASCADES; ++i) r.viewProj[i] = mat4(1.0);
    r.splitFar = vec4(0.0);
    r.texelWorld = vec4(1.0);
    r.depthRange = vec4(1.0);
    r.info = vec4(0.0, 0.0, float(RG_SHADOW_SIZE), 0.0);
    r.bias = vec4(params.shadow_depth_bias, params.shadow_normal_offset, params.shadow_softness, float(RG_SUN_PCF_TAPS));
    int sun = -1;
    for (uint k = 0u; k < globalLights.count.x; ++k)
        if (int(lights.light[globalLights.light[k]].positionType.w + 0.5) == RG_LIGHT_SUN) { sun = int(globalLights.light[k]); break; }
    if (sun < 0) { out_.c = r; return; }
    RgLight light = lights.light[sun];
    vec3 f = normalize(light.directionRange.xyz);  // the way the light travels
    vec3 x = normalize(cross(f, abs(f.y) < 0.99 ? vec3(0.0, 1.0, 0.0) : vec3(1.0, 0.0, 0.0)));
    vec3 y = cross(x, f);

    // The camera: near and far planes and the field of view (a perspective's tangents, an
    // orthographic view's half extents) from its projection (depth 0..1).
    bool ortho = rgCameraOrthographic();
    float near = camera.proj[3][2] / camera.proj[2][2];
    float far = ortho ? (camera.proj[3][2] - 1.0) / camera.proj[2][2] : camera.proj[3][2] / (camera.proj[2][2] + 1.0);
    float tanX = 1.0 / abs(camera.proj[0][0]), tanY = 1.0 / abs(camera.proj[1][1]);
    float k2 = tanX * tanX + tanY * tanY;
    mat4 invView = inverse(camera.view);
    float end = min(params.shadow_distance, far);
    const int count = RG_CASCADES;
    float start = near;
    for (int i = 0; i < count; ++i) {
        float t = float(i + 1) / float(count);
        float split = mix(near + (end - near) * t, near * pow(end / near, t), params.shadow_split_lambda);
        // The slice's bounding sphere (centre on the view axis at distance cz).
        float cz, radius;
        if (ortho) {  // a box of the view's half extents between start and split
            cz = 0.5 * (split + start);
            radius = sqrt(k2 + 0.25 * (split - start) * (split - start));
        } else if (k2 >= (split - start) / (split + start)) {
            cz = split;
            radius = split * sqrt(k2);
        } else {
            cz = 0.5 * (split + start) * (1.0 + k2);
            radius = 0.5 * sqrt((split - start) * (split - start) + 2.0 * (split * split + start * start) * k2 +
                                (split + start) * (split + start) * k2 * k2);
        }
        vec3 centre = (invView * vec4(0.0, 0.0, -cz, 1.0)).xyz;
        float texel = 2.0 * radius / float(RG_SHADOW_SIZE);
        float cx = floor(dot(centre, x) / texel + 0.5) * texel;
        float cy = floor(dot(centre, y) / texel + 0.5) * texel;
        // Depth: from the scene's bounds nearest the sun to the farthest of bounds and sphere.
        float dmin = dot(centre, f) - radius, dmax = dot(centre, f) + radius;
        for (int b = 0; b < 8; ++b) {
            vec3 corner = vec3((b & 1) != 0 ? camera.sceneMax.x : camera.sceneMin.x, (b & 2) != 0 ? camera.sceneMax.y : camera.sceneMin.y,
                               (b & 4) != 0 ? camera.sceneMax.z : camera.sceneMin.z);
            dmin = min(dmin, dot(corner, f));
            dmax = max(dmax, dot(corner, f));
        }
        dmin -= 0.01;
        dmax += 0.01;
        float range = dmax - dmin;
        r.viewProj[i] = transpose(mat4(vec4(x / radius, -cx / radius), vec4(y / radius, -cy / radius),
                                       vec4(f / range, -dmin / range), vec4(0.0, 0.0, 0.0, 1.0)));
        r.splitFar[i] = split;
        r.texelWorld[i] = texel;
        r.depthRange[i] = range;
        start = split;
    }
    r.info.x = float(count);
    r.info.y = float(sun);
    r.info.w = light.params.z / max(light.params.w, 1e-6);  // tan σ from sin σ, cos σ (lst:6)
    out_.c = r;
}
