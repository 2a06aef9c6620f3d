// Culling and level-of-detail choices the GPU makes for the camera's draws (shaders/passes/
// camera_cull.comp) and the sun's casters (shaders/shadows/cascade_cull.comp): the same tests as
// GpuScene::updateFrame's on the CPU (passes/gpu_scene_detail.h). Needs lib/scene.glsl with
// RG_SCENE_DRAWS.
#ifndef RG_CULLING_GLSL
#define RG_CULLING_GLSL

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

#endif
