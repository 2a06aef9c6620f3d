// The environment's equirectangular mapping and cube-map helpers, shared by the sky, the
// environment filtering passes (shaders/ibl/) and the reference integrator. The mapping is
// graph/scene/environment.h's, in the same words:
//   u = 0.5 + atan(d.x, −d.z) / 2π,  v = acos(d.y) / π   (v = 0 at the zenith).
// A shader that declares `uniform sampler2D SceneEnvironment` gets the scene's environment
// (equirectangular RGBA32F, luminance in nits, world orientation; black without one).
#ifndef RG_ENVIRONMENT_GLSL
#define RG_ENVIRONMENT_GLSL

#ifndef RG_PI
#define RG_PI 3.14159265358979
#endif

vec2 rgEquirectUv(vec3 d) {
    return vec2(0.5 + atan(d.x, -d.z) / (2.0 * RG_PI), acos(clamp(d.y, -1.0, 1.0)) / RG_PI);
}

vec3 rgEquirectDirection(vec2 uv) {
    float phi = (uv.x - 0.5) * 2.0 * RG_PI, theta = uv.y * RG_PI;
    return vec3(sin(theta) * sin(phi), cos(theta), -sin(theta) * cos(phi));
}

// The world direction through texel centre `uv` (0..1) of cube face `face` (Vulkan's face order
// +X, −X, +Y, −Y, +Z, −Z and its s/t conventions, so that sampling the cube in that direction
// returns that texel).
vec3 rgCubeDirection(uint face, vec2 uv) {
    vec2 st = uv * 2.0 - 1.0;
    vec3 d;
    if (face == 0u) d = vec3(1.0, -st.y, -st.x);
    else if (face == 1u) d = vec3(-1.0, -st.y, st.x);
    else if (face == 2u) d = vec3(st.x, 1.0, st.y);
    else if (face == 3u) d = vec3(st.x, -1.0, -st.y);
    else if (face == 4u) d = vec3(st.x, -st.y, 1.0);
    else d = vec3(-st.x, -st.y, -1.0);
    return normalize(d);
}

// Solid angle of the cube texel around `uv` on a face of `size` texels: ∫ dA cos/r² of the
// texel's square, exact (the standard arctangent form of the area element's integral).
float rgCubeTexelSolidAngle(vec2 uv, float size) {
    float h = 1.0 / size;
    vec2 a = uv * 2.0 - 1.0 - h, b = a + 2.0 * h;
#define RG_AREA(x, y) atan((x) * (y), sqrt((x) * (x) + (y) * (y) + 1.0))
    return RG_AREA(a.x, a.y) - RG_AREA(a.x, b.y) - RG_AREA(b.x, a.y) + RG_AREA(b.x, b.y);
#undef RG_AREA
}

// ---- Order-2 spherical harmonics (9 coefficients) of a radiance field -------------------------
// Real SH basis Y_lm (Ramamoorthi & Hanrahan 2001's constants); the irradiance of a cosine lobe
// around n is Σ Â_l L_lm Y_lm(n) with Â_0 = π, Â_1 = 2π/3, Â_2 = π/4 (their eq. 8).
void rgShBasis(vec3 d, out float y[9]) {
    y[0] = 0.282095;
    y[1] = 0.488603 * d.y;
    y[2] = 0.488603 * d.z;
    y[3] = 0.488603 * d.x;
    y[4] = 1.092548 * d.x * d.y;
    y[5] = 1.092548 * d.y * d.z;
    y[6] = 0.315392 * (3.0 * d.z * d.z - 1.0);
    y[7] = 1.092548 * d.x * d.z;
    y[8] = 0.546274 * (d.x * d.x - d.y * d.y);
}

// Irradiance (lux) at a surface facing n from radiance SH coefficients sh[0..8] (rgb in xyz).
vec3 rgShIrradiance(vec4 sh[9], vec3 n) {
    float y[9];
    rgShBasis(n, y);
    const float A0 = RG_PI, A1 = 2.0 * RG_PI / 3.0, A2 = RG_PI / 4.0;
    vec3 e = A0 * y[0] * sh[0].rgb;
    for (int i = 1; i < 4; ++i) e += A1 * y[i] * sh[i].rgb;
    for (int i = 4; i < 9; ++i) e += A2 * y[i] * sh[i].rgb;
    return max(e, vec3(0.0));  // ringing of a strong, small source can go negative
}

#endif
