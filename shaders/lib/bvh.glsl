// Ray casts against the scene's opaque triangles (passes/gpu_scene_geometry.cpp bvhBuffer, built by
// graph/scene/bvh.cpp): the reference mode's shadow rays. Bound as the scene's `SceneBvh`.
// Layout: header (nodes, triangles, depth), then per node two vec4s — (min.xyz, a), (max.xyz,
// count), a and count as uint bits: count > 0 a leaf of `count` triangles from triangle a, else
// an interior node whose first child follows it and whose second is node a — then three vec4s
// per triangle.
#ifndef RG_BVH_GLSL
#define RG_BVH_GLSL

#ifndef RG_BVH_BINDING
#define RG_BVH_BINDING 20
#endif
#define RG_BVH_STACK 48  // graph/scene/bvh.cpp stops splitting at depth 40

layout(set = 0, binding = RG_BVH_BINDING, std430) readonly buffer SceneBvh {
    uvec4 header;
    vec4 data[];
} rgBvh;

// Whether anything of the scene lies on the ray o + t d for 0 < t < tMax (d unit).
bool rgOccluded(vec3 o, vec3 d, float tMax) {
    uint nodes = rgBvh.header.x;
    if (nodes == 0u || tMax <= 0.0) return false;
    vec3 inv = 1.0 / mix(d, vec3(1e-20), equal(d, vec3(0.0)));
    uint stack[RG_BVH_STACK];
    int top = 0;
    uint node = 0u;
    for (;;) {
        vec4 a = rgBvh.data[2u * node], b = rgBvh.data[2u * node + 1u];
        vec3 t0 = (a.xyz - o) * inv, t1 = (b.xyz - o) * inv;
        vec3 tn = min(t0, t1), tf = max(t0, t1);
        float enter = max(max(tn.x, tn.y), max(tn.z, 0.0)), exit = min(min(tf.x, tf.y), min(tf.z, tMax));
        bool visit = enter <= exit;
        uint count = floatBitsToUint(b.w), first = floatBitsToUint(a.w);
        if (visit && count == 0u && top < RG_BVH_STACK) {
            stack[top++] = first;
            node = node + 1u;
            continue;
        }
        if (visit) {
            for (uint t = first; t < first + count; ++t) {
                uint base = 2u * nodes + 3u * t;
                vec3 v0 = rgBvh.data[base].xyz, e1 = rgBvh.data[base + 1u].xyz - v0, e2 = rgBvh.data[base + 2u].xyz - v0;
                vec3 p = cross(d, e2);
                float det = dot(e1, p);
                if (abs(det) < 1e-12) continue;
                float invDet = 1.0 / det;
                vec3 s = o - v0;
                float u = dot(s, p) * invDet;
                vec3 q = cross(s, e1);
                float v = dot(d, q) * invDet, h = dot(e2, q) * invDet;
                if (u >= 0.0 && v >= 0.0 && u + v <= 1.0 && h > 0.0 && h < tMax) return true;
            }
        }
        if (top == 0) return false;
        node = stack[--top];
    }
}

#endif
