// Local light probes (seed 002 §4.9.1.2, §4.9.3, §4.9.5, appendix F): the scene's probes
// (passes/gpu_scene.cpp createProbes: the `Probes` scene binding, in the order the composition
// visits them — priority, then the smaller first) and their parallax-corrected lookup. Probe k's
// capture is cube k of `probe_specular` (scripts/probes.lua), pre-filtered like the distant probe
// (mip = sqrt(linearRoughness) · (mips − 1)) with the captured visibility in alpha.
#ifndef RG_PROBES_GLSL
#define RG_PROBES_GLSL

#define RG_MAX_PROBES 8  // graph/scene/scene.h kMaxProbes
// The scene's probe count (rgraph defines it for passes with a scene): loops' constant bound.
#ifndef RG_SCENE_PROBES
#define RG_SCENE_PROBES RG_MAX_PROBES
#endif
#ifndef RG_PROBES_BINDING
#define RG_PROBES_BINDING 22
#endif

struct RgProbe {
    vec4 positionShape;  // xyz: capture point and proxy centre (world); w: 0 sphere, 1 box
    vec4 extentFade;     // xyz: the box's half extents (a sphere: radius in x); w: fade distance (m)
    vec4 axes[3];        // the box's local axes in world space
    vec4 influence;      // xyz: the influence box's half extents (a sphere: its radius in x), same centre and axes
};

// RG_NO_PROBE_BINDING: the functions alone, no scene binding (shaders/test/ibl_terms.comp).
#ifndef RG_NO_PROBE_BINDING
layout(set = 0, binding = RG_PROBES_BINDING, std140) uniform Probes {
    uvec4 count;
    RgProbe probe[RG_MAX_PROBES];
} rgProbes;
#endif

// The scene's probe shapes (rgraph defines it for passes with a scene: 1 spheres only, 2 boxes
// only, 3 both): with one shape the other's branch compiles away — both sides of a branch run on a
// CPU rasteriser (reflection_compose −1 to −2 ms at 1280×720 with the default scene's box).
#ifndef RG_SCENE_PROBE_SHAPES
#define RG_SCENE_PROBE_SHAPES 3
#endif
bool rgProbeIsBox(RgProbe p) {
#if RG_SCENE_PROBE_SHAPES == 1
    return false;
#elif RG_SCENE_PROBE_SHAPES == 2
    return true;
#else
    return p.positionShape.w > 0.5;
#endif
}

// World offset → the box's local frame (rotation only).
vec3 rgProbeLocal(RgProbe p, vec3 v) { return vec3(dot(p.axes[0].xyz, v), dot(p.axes[1].xyz, v), dot(p.axes[2].xyz, v)); }
vec3 rgProbeWorld(RgProbe p, vec3 v) { return v.x * p.axes[0].xyz + v.y * p.axes[1].xyz + v.z * p.axes[2].xyz; }

// Appendix F's influence: 1 inside the influence volume, fading over `fade` metres inside its
// boundary (a sphere's radius, a box's faces: distanceBoxPoint from the box shrunk by the fade), 0
// outside, through a smoothstep "for a nicer transition".
float rgProbeInfluence(RgProbe p, vec3 P) {
    vec3 d = P - p.positionShape.xyz;
    float fade = max(p.extentFade.w, 1e-4);
    float alpha;
    if (rgProbeIsBox(p)) {
        vec3 local = abs(rgProbeLocal(p, d));
        if (any(greaterThan(local, p.influence.xyz))) return 0.0;
        vec3 inner = max(p.influence.xyz - vec3(fade), vec3(0.0));
        alpha = 1.0 - clamp(length(max(local - inner, vec3(0.0))) / fade, 0.0, 1.0);
    } else {
        alpha = clamp((p.influence.x - length(d)) / fade, 0.0, 1.0);
    }
    return smoothstep(0.0, 1.0, alpha);
}

// §4.9.3 computeDistanceBaseRoughness: the lobe's footprint shrinks with the reflected surface's
// distance; clamped to the surface's roughness and blended back to it as roughness grows.
float rgDistanceBasedRoughness(float distanceReceiverIntersection, float distanceCentreIntersection, float linearRoughness) {
    float r = clamp(distanceReceiverIntersection / max(distanceCentreIntersection, 1e-4) * linearRoughness, 0.0, linearRoughness);
    return mix(r, linearRoughness, linearRoughness);
}

// Appendix F's parallax correction of the (dominant) reflection direction R (unit) from P against
// the probe's proxy: the direction from the capture point to where the ray leaves the proxy, and
// the roughness for that distance. False when P's ray misses the proxy (P outside it).
bool rgProbeParallax(RgProbe p, vec3 P, vec3 R, float linearRoughness, out vec3 direction, out float localRoughness) {
    vec3 o = P - p.positionShape.xyz;
    float tFar;
    vec3 hit;  // the exit point relative to the capture point (world axes)
    if (rgProbeIsBox(p)) {
        vec3 lo = rgProbeLocal(p, o), ld = rgProbeLocal(p, R);
        vec3 inv = 1.0 / mix(ld, vec3(1e-20), equal(ld, vec3(0.0)));
        vec3 t0 = (-p.extentFade.xyz - lo) * inv, t1 = (p.extentFade.xyz - lo) * inv;
        vec3 tMax = max(t0, t1), tMin = min(t0, t1);
        tFar = min(tMax.x, min(tMax.y, tMax.z));
        if (tFar <= max(tMin.x, max(tMin.y, tMin.z))) return false;
        hit = rgProbeWorld(p, lo + tFar * ld);
    } else {  // sphereRayIntersect: the far root of |o + t R|² = r²
        float b = dot(o, R);
        float c = dot(o, o) - p.extentFade.x * p.extentFade.x;
        float disc = b * b - c;
        if (disc < 0.0) return false;
        tFar = -b + sqrt(disc);
        hit = o + tFar * R;
    }
    if (tFar <= 0.0) return false;
    localRoughness = rgDistanceBasedRoughness(tFar, length(hit), linearRoughness);
    // "Limit artifacts introduced with high roughness": towards the uncorrected direction.
    direction = mix(normalize(hit), R, linearRoughness);
    return true;
}

#endif
