// Camera and scene of tests/golden/pipelines/shading.lua, shared by its passes.
#ifndef SHADING_COMMON_GLSL
#define SHADING_COMMON_GLSL

const vec3 kEye = vec3(0.0, 1.1, 3.6);
const vec3 kLookAt = vec3(0.0, 0.7, 0.0);
const float kTanHalfFov = 0.45;
const vec3 kSphereCentre = vec3(0.0, 0.8, 0.0);
const float kSphereRadius = 0.8;
const float kPi = 3.14159265358979;

// The sub-pixel offset of frame `frame` (a golden-ratio sequence in [-0.5, 0.5)^2) times `amount`.
vec2 jitterOffset(float frame, float amount) {
    return amount * (fract(vec2(0.5 + frame * 0.61803399, 0.5 + frame * 0.38196601)) - 0.5);
}

// The primary ray through a point of the framebuffer (pixels, y down).
vec3 cameraRay(vec2 pixel, vec2 size) {
    vec3 f = normalize(kLookAt - kEye);
    vec3 r = normalize(cross(f, vec3(0.0, 1.0, 0.0)));
    vec3 u = cross(r, f);
    vec2 ndc = pixel / size * 2.0 - 1.0;
    return normalize(f + r * (ndc.x * kTanHalfFov * size.x / size.y) - u * (ndc.y * kTanHalfFov));
}

// Distance along the ray to the sphere, or -1.
float hitSphere(vec3 o, vec3 d) {
    vec3 oc = o - kSphereCentre;
    float b = dot(oc, d);
    float c = dot(oc, oc) - kSphereRadius * kSphereRadius;
    float disc = b * b - c;
    if (disc < 0.0) return -1.0;
    float t = -b - sqrt(disc);
    return t > 1e-4 ? t : -1.0;
}

// Distance along the ray to the ground plane y = 0, or -1.
float hitGround(vec3 o, vec3 d) { return d.y < -1e-4 ? -o.y / d.y : -1.0; }

vec3 sunDirection(float elevationDegrees) {
    float e = radians(elevationDegrees);
    return normalize(vec3(0.6 * cos(e), sin(e), 0.8 * cos(e)));
}

vec3 sky(vec3 d) { return mix(vec3(0.55, 0.62, 0.75), vec3(0.18, 0.32, 0.62), clamp(d.y, 0.0, 1.0)); }

#endif
