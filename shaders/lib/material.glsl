// The material interface of scene draws (set 1: the scene's materials and one texture set, filled
// by passes/gpu_scene_materials.cpp) and the sampled surface every material's surface function
// receives.
#ifndef RG_MATERIAL_GLSL
#define RG_MATERIAL_GLSL

struct RgMaterialData {
    vec4 baseColorOpacity;  // linear base colour, opacity
    vec4 emissive;          // rgb: nits (cd/m²)
    vec4 factors;           // smoothness, metalMask, reflectance, ao
    vec4 factors2;          // normalScale, occlusionStrength, alphaCutoff, alphaMode (0 opaque, 1 mask, 2 blend)
    vec4 diffuseColor;      // two-colour model (tbl:3); w: 1 for a two-colour material
    vec4 f0;                // two-colour model
    vec4 uvTransform[16];   // per texture (5 standard, 3 of the model's own): two rows of the affine uv matrix; w of the first row: texCoord, of the second: the image's layer
    vec4 custom[4];         // game-team material parameters, in declaration order
};
// The draw's material. Drawn by the CPU (one material a draw, instanced or not): the material's
// own window of the scene's materials, bound at its offset (binding 0), so its loads are uniform
// over the draw. Drawn from the GPU's instance lists (RG_CAMERA_INSTANCES: one call draws a camera
// run of many materials, GpuScene::CameraRun): the run's window of RG_MATERIAL_WINDOW materials
// (binding 9), read at the instance's index within it, which scene.vert passes flat. Both are
// uniform blocks: lavapipe (Mesa 22.3) leaves a storage buffer's loads out of a fragment shader's
// helper invocations, whose texture derivatives then read zeros (sparkles along triangle edges),
// and its storage-buffer loads cost the G-buffer ~3 ms more at 1280×720 than a uniform block's.
#ifdef RG_CAMERA_INSTANCES
#ifndef RG_MATERIAL_WINDOW
#define RG_MATERIAL_WINDOW 39  // 16 KiB, every device's maxUniformBufferRange
#endif
layout(set = 1, binding = 9, std140) uniform MaterialWindow { RgMaterialData m[RG_MATERIAL_WINDOW]; } rgMaterials;
layout(location = 9) flat in uint rgMaterialIndex;
// `material.NAME`: the draw's parameters, as surface functions read them.
#define material rgMaterials.m[rgMaterialIndex]
#else
layout(set = 1, binding = 0, std140) uniform MaterialData { RgMaterialData data; } rgMaterial;
#define material rgMaterial.data
#endif
// The material's textures: each the array of its images' shape (size, mips, encoding), the image
// one layer of it (rgTextureCoord) — materials whose images differ only in layer share these.
layout(set = 1, binding = 1) uniform sampler2DArray baseColorTex;
layout(set = 1, binding = 2) uniform sampler2DArray metallicRoughnessTex;
layout(set = 1, binding = 3) uniform sampler2DArray normalTex;
layout(set = 1, binding = 4) uniform sampler2DArray occlusionTex;
layout(set = 1, binding = 5) uniform sampler2DArray emissiveTex;
// The material model's own textures (rg.material's `textures`, in sorted name order): its surface
// function reads texture i as NAME(s), which the generated shader defines as
// rgMaterialTexture<i>(s) — white where the scene material has none.
layout(set = 1, binding = 6) uniform sampler2DArray materialTexture0;
layout(set = 1, binding = 7) uniform sampler2DArray materialTexture1;
layout(set = 1, binding = 8) uniform sampler2DArray materialTexture2;

// What a surface function starts from: the material's parameters with its textures applied.
struct RgSurface {
    vec3 position;      // world
    vec3 normal;        // world, unit, normal map applied, facing the viewer
    vec3 baseColor;     // linear
    float opacity;
    float smoothness;
    float metalMask;
    float reflectance;
    float ao;
    vec3 emissive;      // nits
    vec3 diffuseColor;  // two-colour model (tbl:3), linear, times the base colour texture
    vec3 f0;            // two-colour model: specular colour at normal incidence
    bool twoColour;     // the material is a two-colour one (its lighting takes diffuseColor and f0)
    // 1 where `emissive` holds only baked radiosity (the scene's lightmap; a surface without
    // emission of its own): the lighting occludes it by AO as it would the probe's diffuse
    // (seed 002 §4.10.3). Written to GB2.reserved by the standard surface function.
    float radiosity;
    vec2 uv0, uv1;  // the vertex's two uv sets, for the model's own textures (rgMaterialTexture)
    // The normal map's frame: tangent, bitangent and the interpolated vertex normal (flipped on a
    // back face) as columns — for a second normal map of the model's own (a clear coat's).
    mat3 tangentFrame;
};

// Which of the five textures the material has (bits 1 base colour, 2 metallic-roughness,
// 4 normal, 8 occlusion, 16 emissive; 64, 128, 256 the model's own textures 0, 1, 2): the scene
// pass compiles one variant per combination its
// draws use, so an absent texture is not sampled — its default (white; the flat normal) would
// leave the surface exactly as the factors give it, and on a CPU rasteriser the five filtered
// samples of tiny triangles are most of the G-buffer's cost. Without it, every texture is sampled.
#ifndef RG_TEXTURES
#define RG_TEXTURES 479
#endif
// 1 for an alpha-tested material's variant: the only one whose fragment shader may discard
// (passes/scene_pass.cpp variantKey: a shader that can discard loses the early depth test).
#ifndef RG_ALPHA_MASK
#define RG_ALPHA_MASK 0
#endif

// Where texture `texture` of the material is read: its uv (the set it takes, transformed) and its
// layer in the array of its shape (passes/gpu_scene_materials.cpp uploadImages).
vec3 rgTextureCoord(int texture, vec2 uv0, vec2 uv1) {
    vec4 r0 = material.uvTransform[2 * texture], r1 = material.uvTransform[2 * texture + 1];
    vec2 uv = r0.w > 0.5 ? uv1 : uv0;
    return vec3(dot(r0.xyz, vec3(uv, 1.0)), dot(r1.xyz, vec3(uv, 1.0)), r1.w);
}

// Texture `slot` of the material (bit `bit` of RG_TEXTURES), or its default when it has none.
#define rgSampleMaterialTexture(tex, bit, slot, uv0, uv1, absent) \
    (((RG_TEXTURES) & (bit)) != 0 ? texture(tex, rgTextureCoord(slot, uv0, uv1)) : (absent))

// The material model's own texture i (0, 1, 2) at the surface's uv, white without one; whether the
// scene material has it (a surface function reads it as NAME_present).
#define rgHasMaterialTexture0 (((RG_TEXTURES) & 64) != 0)
#define rgHasMaterialTexture1 (((RG_TEXTURES) & 128) != 0)
#define rgHasMaterialTexture2 (((RG_TEXTURES) & 256) != 0)
#define rgMaterialTexture0(s) rgSampleMaterialTexture(materialTexture0, 64, 5, (s).uv0, (s).uv1, vec4(1.0))
#define rgMaterialTexture1(s) rgSampleMaterialTexture(materialTexture1, 128, 6, (s).uv0, (s).uv1, vec4(1.0))
#define rgMaterialTexture2(s) rgSampleMaterialTexture(materialTexture2, 256, 7, (s).uv0, (s).uv1, vec4(1.0))

// The surface's tangent frame (tangent, bitangent, normal as columns) from the interpolated
// vertex normal and tangent, facing the viewer: the normal map's frame, and the baked lightmap's
// (graph/bake builds the same). Gram-Schmidt; a degenerate tangent (at a sphere's pole, or none at
// all) falls back to any vector perpendicular to n, so no NaN reaches the G-buffer.
mat3 rgTangentFrame(vec3 normal, vec4 tangent, bool frontFacing) {
    vec3 n = normalize(normal);
    if (!frontFacing) n = -n;
    vec3 t = tangent.xyz - n * dot(n, tangent.xyz);
    float tl = dot(t, t);
    vec3 anyT = normalize(abs(n.x) < 0.9 ? cross(n, vec3(1.0, 0.0, 0.0)) : cross(n, vec3(0.0, 1.0, 0.0)));
    t = tl > 1e-12 ? t * inversesqrt(tl) : anyT;
    return mat3(t, cross(n, t) * tangent.w, n);
}

// Specular anti-aliasing (seed 002 §5.3: aliasing comes from estimating a pixel's integral of
// L(v) with one sample; besides supersampling, pre-filtering). The NDF is filtered over the
// normals the pixel's footprint covers by adding their variance to the GGX roughness's α², so a
// glossy highlight on dense normal detail, or on a surface curving faster than a pixel resolves,
// widens and dims instead of sparkling. The variance, per slope axis:
//   - inside the normal map's filter footprint, from the filtered normal's length (Toksvig,
//     "Mipmapping normal maps", 2005): the box-filtered mips average unit normals into a shorter
//     one, |n̄| ≈ 1 − ⟨θ²⟩/2, so (1 − |n̄|) / |n̄| ≈ ⟨θ²⟩/2. The length is taken relative to the
//     base level's at the same place: the bilinear blend of neighbouring texels shortens the
//     normal by itself, and that is interpolation, not an average over the pixel;
//   - across the pixel, from the screen-space derivatives of the shading normal (Kaplanyan,
//     Hill, Patney & Lefohn, "Filtering Distributions of Normals for Shading Antialiasing", HPG
//     2016): a normal varying linearly over a box pixel varies by ⟨θ²⟩ = (|∂n/∂x|² + |∂n/∂y|²)/12,
//     so RG_SPECULAR_AA_VARIANCE (σ², 1/24 for the box) × (|∂n/∂x|² + |∂n/∂y|²), at most
//     RG_SPECULAR_AA_THRESHOLD (κ, Kaplanyan's 0.18).
// α'² = min(α² + v_map + v_screen, 1). Beckmann's α² is twice the slope variance; GGX's heavier
// tails take it once: against a 4×4 supersampled render in HDR (tests/cli/specular_aa.py's floor)
// twice gave an RMSE of 15 611 and a mean relative error of 0.405, once 16 158 and 0.346 (without:
// 29 429, 0.303). Frostbite's smoothness is 1 − √α: the result goes back as 1 − (α'²)^¼. On with
// RG_SPECULAR_AA: the pipeline's `specular_aa` parameters (scripts/render_loop.lua) compile it in.
#ifndef RG_SPECULAR_AA
#define RG_SPECULAR_AA 0
#endif
#ifndef RG_SPECULAR_AA_VARIANCE
#define RG_SPECULAR_AA_VARIANCE 0.0417
#endif
#ifndef RG_SPECULAR_AA_THRESHOLD
#define RG_SPECULAR_AA_THRESHOLD 0.18
#endif
float rgSpecularAntialiasing(float smoothness, vec3 n, float mapLength) {
    vec3 dx = dFdx(n), dy = dFdy(n);
    float screen = min(float(RG_SPECULAR_AA_VARIANCE) * (dot(dx, dx) + dot(dy, dy)), float(RG_SPECULAR_AA_THRESHOLD));
    float map = max((1.0 - mapLength) / max(mapLength, 1e-3), 0.0);
    float roughness = 1.0 - smoothness;
    float alpha2 = min(roughness * roughness * roughness * roughness + screen + map, 1.0);
    return 1.0 - sqrt(sqrt(alpha2));
}

// vertexColor: the mesh's COLOR_0 (white without), a factor of the base colour and opacity as
// glTF defines it (and of the two-colour material's diffuse colour).
RgSurface rgSampleSurface(vec3 position, vec3 normal, vec4 tangent, vec2 uv0, vec2 uv1, vec4 vertexColor, bool frontFacing) {
    RgSurface s;
    s.position = position;
    vec4 base = rgSampleMaterialTexture(baseColorTex, 1, 0, uv0, uv1, vec4(1.0)) * vertexColor;
    s.baseColor = material.baseColorOpacity.rgb * base.rgb;
    s.opacity = material.baseColorOpacity.a * base.a;
    vec4 mr = rgSampleMaterialTexture(metallicRoughnessTex, 2, 1, uv0, uv1, vec4(1.0));
    // glTF: roughness in G, metallic in B; smoothness = 1 − roughness.
    s.smoothness = 1.0 - (1.0 - material.factors.x) * mr.g;
    s.metalMask = material.factors.y * mr.b;
    s.reflectance = material.factors.z;
    float occlusion = rgSampleMaterialTexture(occlusionTex, 8, 3, uv0, uv1, vec4(1.0)).r;
    s.ao = material.factors.w * mix(1.0, occlusion, material.factors2.y);
    s.emissive = material.emissive.rgb * rgSampleMaterialTexture(emissiveTex, 16, 4, uv0, uv1, vec4(1.0)).rgb;
    s.diffuseColor = material.diffuseColor.rgb * base.rgb;
    s.f0 = material.f0.rgb;
    s.twoColour = material.diffuseColor.w > 0.5;
    s.radiosity = 0.0;
    s.uv0 = uv0;
    s.uv1 = uv1;
    vec3 m = rgSampleMaterialTexture(normalTex, 4, 2, uv0, uv1, vec4(0.5, 0.5, 1.0, 1.0)).xyz * 2.0 - 1.0;
#if RG_SPECULAR_AA
    // How much shorter than the base level's the filtered normal is (rgSpecularAntialiasing).
    float mapLength = 1.0;
#if ((RG_TEXTURES) & 4) != 0
    mapLength = min(length(m) / max(length(textureLod(normalTex, rgTextureCoord(2, uv0, uv1), 0.0).xyz * 2.0 - 1.0), 1e-3), 1.0);
#endif
#endif
    m.xy *= material.factors2.x;
    s.tangentFrame = rgTangentFrame(normal, tangent, frontFacing);
    s.normal = normalize(s.tangentFrame * m);
#if RG_SPECULAR_AA
    s.smoothness = rgSpecularAntialiasing(s.smoothness, s.normal, mapLength);
#endif
    return s;
}

#endif
