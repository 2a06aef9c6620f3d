// Culling and level-of-detail choices the GPU makes for the camera's draws (shaders/passes/
// camera_cull.comp) and the shadow views' casters (shaders/shadows/cascade_cull.comp,
// local_cull.comp): the same tests as GpuScene::cullForCamera's on the CPU
// (passes/gpu_scene_detail.h). Needs lib/scene.glsl with RG_SCENE_DRAWS.
#ifndef RG_CULLING_GLSL
#define RG_CULLING_GLSL

// An indexed indirect draw's command (VkDrawIndexedIndirectCommand).
struct DrawIndexedIndirect { uint indexCount, instanceCount, firstIndex; int vertexOffset; uint firstInstance; };

// Scene draw d (its RgDraw `record`) joins indirect command k at level `level`: its index takes
// the next slot of the command's region of instances, which starts at `first` (an atomic add on
// the command's instance count), and the first to join writes the rest of the command. A macro,
// for the culling shaders' own blocks: `commands` (DrawIndexedIndirect command[]) and
// `instances` (uint draw[]).
#define rgJoinCommand(k, first, record, d, level)                                \
    {                                                                            \
        const uint joined = atomicAdd(commands.command[k].instanceCount, 1u);    \
        instances.draw[(first) + joined] = (d);                                  \
        if (joined == 0u) {                                                      \
            commands.command[k].indexCount = (record).lodCount[level];           \
            commands.command[k].firstIndex = (record).lodFirst[level];           \
            commands.command[k].vertexOffset = int((record).info.x);             \
            commands.command[k].firstInstance = (first);                         \
        }                                                                        \
    }

// The six planes (a, b, c, d: inside where a x + b y + c z + d >= 0) of a clip-space frustum with
// depth 0..1 (Gribb & Hartmann), normalised.
vec4[6] rgFrustumPlanes(mat4 m) {
    const vec4 r0 = vec4(m[0][0], m[1][0], m[2][0], m[3][0]), r1 = vec4(m[0][1], m[1][1], m[2][1], m[3][1]),
               r2 = vec4(m[0][2], m[1][2], m[2][2], m[3][2]), r3 = vec4(m[0][3], m[1][3], m[2][3], m[3][3]);
    vec4 p[6] = vec4[](r3 + r0, r3 - r0, r3 + r1, r3 - r1, r2, r3 - r2);
    for (int i = 0; i < 6; ++i) p[i] /= max(length(p[i].xyz), 1e-20);
    return p;
}

// False when the box lies wholly outside one of the planes (its corner furthest along the plane's
// normal is behind it); conservative near the frustum's edges.
bool rgBoxMeetsFrustum(vec4 planes[6], vec3 lo, vec3 hi) {
    for (int i = 0; i < 6; ++i) {
        const vec3 corner = mix(lo, hi, greaterThanEqual(planes[i].xyz, vec3(0.0)));
        if (dot(planes[i].xyz, corner) + planes[i].w < 0.0) return false;
    }
    return true;
}

// The level of detail the camera draws `draw` with: the coarsest whose error spans at most
// `spare` pixels at the nearest view depth of its box (level 0 where the box reaches the near
// plane, or where the scene's passes draw the full meshes). The camera's passes take spare 1; the sun's cascades 1.01, so that rounding never
// leaves a caster finer than the camera's choice for it.
uint rgCameraLevel(RgDraw draw, float spare) {
    if (sceneDraws.header.y != 0u) return 0u;  // a pass traces the full meshes (drawFullMeshes)
    // The box's nearest depth: its centre's less the half extents along |forward| (the smallest of
    // the linear function over its corners), as the CPU computes it.
    const vec3 forward = -vec3(camera.view[0][2], camera.view[1][2], camera.view[2][2]);
    const vec3 centre = 0.5 * (draw.boxMin.xyz + draw.boxMax.xyz), extent = 0.5 * (draw.boxMax.xyz - draw.boxMin.xyz);
    const float nearest = dot(centre - camera.position.xyz, forward) - dot(extent, abs(forward));
    const bool orthographic = rgCameraOrthographic();
    if (!orthographic && nearest <= rgViewDistance(0.0)) return 0u;
    const float pixelsPerMetre = abs(camera.proj[1][1]) * camera.viewport.y * 0.5 / (orthographic ? 1.0 : nearest);
    uint level = 0u;
    for (uint l = 1u; l < min(draw.info.w, 4u); ++l)
        if (draw.lodError[l] * pixelsPerMetre <= spare) level = l;
    return level;
}

// Whether any of a world box may show over the depth drawn so far (two-phase occlusion culling:
// shaders/passes/camera_cull.comp): `hiz` the farthest-depth pyramid of it (passes/hiz.comp with
// RG_HIZ_FARTHEST; its mip 0 may be coarser than the screen). The box's corners projected bound
// the pixels it can cover — two pixels wider each way: half a pixel for the pixel centres, half
// for the jitter, the rest for the rounding of the texel below — and its nearest depth; the pyramid's finest mip over which those
// pixels span at most 2 × 2 texels gives the farthest depth drawn over all of them. False only
// when the box's nearest depth lies beyond it: every fragment of the box then fails the depth
// test against what is drawn (depth 0..1, nearer less). A box reaching the near plane may show.
bool rgBoxMayShow(sampler2D hiz, mat4 viewProj, vec3 lo, vec3 hi) {
    vec2 ndcMin = vec2(1e30), ndcMax = vec2(-1e30);
    float nearest = 1.0;
    for (int i = 0; i < 8; ++i) {
        const vec3 corner = vec3((i & 1) != 0 ? hi.x : lo.x, (i & 2) != 0 ? hi.y : lo.y, (i & 4) != 0 ? hi.z : lo.z);
        const vec4 clip = viewProj * vec4(corner, 1.0);
        if (clip.w <= 1e-6 || clip.z < 0.0) return true;
        const vec3 ndc = clip.xyz / clip.w;
        ndcMin = min(ndcMin, ndc.xy);
        ndcMax = max(ndcMax, ndc.xy);
        nearest = min(nearest, ndc.z);
    }
    const vec2 pixels = camera.viewport.xy;
    const ivec2 size0 = textureSize(hiz, 0);
    // Pixel x lies in mip-0 texel floor(x · size0 / pixels) (hiz.comp's blocks), in mip m in that
    // texel's >> m, the last texel of a mip taking the odd one left over.
    const vec2 toTexels = vec2(size0) / pixels;
    // Clamped as floats: a corner near the camera's plane projects far outside the screen, beyond
    // what an int holds.
    const vec2 top = vec2(size0 - 1);
    const ivec2 t0 = ivec2(clamp(floor(((ndcMin * 0.5 + 0.5) * pixels - 2.0) * toTexels), vec2(0.0), top));
    const ivec2 t1 = ivec2(clamp(floor(((ndcMax * 0.5 + 0.5) * pixels + 2.0) * toTexels), vec2(0.0), top));
    const int levels = textureQueryLevels(hiz);
    int m = 0;
    while (m + 1 < levels && any(greaterThan((t1 >> m) - (t0 >> m), ivec2(1)))) ++m;
    // The mip's size from mip 0's (Vulkan's rule): lavapipe (Mesa 22.3) answered textureSize at a
    // level chosen at run time with sizes past the mip's, and the reads fell outside it.
    const ivec2 last = max(size0 >> m, ivec2(1)) - 1;
    const ivec2 a = min(t0 >> m, last), b = min(t1 >> m, last);
    float farthest = 0.0;
    for (int y = a.y; y <= b.y; ++y)
        for (int x = a.x; x <= b.x; ++x) farthest = max(farthest, texelFetch(hiz, ivec2(x, y), m).r);
    // A margin for the rounding of the two depth computations (the rasteriser's and this).
    return nearest <= farthest + 1e-6;
}

#endif
