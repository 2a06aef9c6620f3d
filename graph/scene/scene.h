// The CPU scene: plain data that a glTF file or a Lua scene script becomes, before anything goes
// to the GPU. No Vulkan here.
//
// Units and conventions (DESIGN.md §5):
// - 1 unit = 1 metre, time in seconds, angles in radians unless a name says otherwise.
// - Colours are linear Rec.709. Light intensities keep the photometric unit they were declared in
//   (lm, cd, lux, nits, ev100); nothing here converts them (the lighting code does, seed 000 tbl:9,
//   tbl:12, eq:12).
// - Right-handed, +Y up; a camera and a light look along their local -Z, as in glTF.
// - Triangles are counter-clockwise when seen from their front side.
// - Texture coordinates follow glTF: (0, 0) is the top-left texel, v grows downwards.
// - Tangents (xyz) point along +u; tangent.w is the handedness: the bitangent is
//   cross(normal, tangent.xyz) * tangent.w and points along -v (up in the image), which is the
//   glTF / MikkTSpace convention that normal maps (+Y up) are authored for.
//
// Ownership: a Scene owns all of its data (vertices, decoded pixels); indices between its arrays
// (Primitive::material, TextureRef::image/sampler, Node::mesh) are plain integers into the same
// Scene. Threading: the loaders share no state; call them from any thread.
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/type_precision.hpp>

#include "core/result.h"
#include "core/value.h"
#include "image/image.h"

namespace rg {

// ---------------------------------------------------------------------------------------------
// Geometry

struct Vertex {
    glm::vec3 position{0.0f};
    glm::vec3 normal{0.0f, 0.0f, 1.0f};
    glm::vec4 tangent{1.0f, 0.0f, 0.0f, 1.0f};  // xyz along +u, w = handedness (±1), see above
    glm::vec2 uv0{0.0f};
    glm::vec2 uv1{0.0f};
    // glTF's COLOR_0, linear RGBA as 16-bit unorm (white: none): multiplies the material's base
    // colour (and diffuse colour) and opacity (lib/material.glsl rgSampleSurface).
    glm::u16vec4 color{65535, 65535, 65535, 65535};
};

// A triangle list: every 3 indices are one counter-clockwise triangle.
// A coarser index list over a primitive's vertices and its geometric error: the farthest its
// surface lies from the full one (metres, in the primitive's own space).
struct PrimitiveLod {
    std::vector<uint32_t> indices;
    float error = 0.0f;
};

struct Primitive {
    std::vector<Vertex> vertices;
    std::vector<uint32_t> indices;
    // Levels of detail, finest first: a generated sphere's exact ones (rows of its vertices
    // dropped), else meshoptimizer's with their measured errors (mesh_lod.h); passes that draw it
    // from a view take the coarsest whose error, projected, stays within a pixel or texel
    // (passes/gpu_scene.h DrawItem::lods).
    std::vector<PrimitiveLod> lods;
    uint32_t material = 0;  // index into Scene::materials
    // Whether uv1 is a lightmap parameterisation: charts inside [0, 1]², not overlapping, with a
    // gutter between them (glTF TEXCOORD_1, or the Lua scene's generated shapes).
    bool lightmapUv = false;
};

struct Mesh {
    std::string name;
    std::vector<Primitive> primitives;  // triangle lists
    // Points and line segments (glTF modes POINTS, and LINES, LINE_LOOP, LINE_STRIP as segment
    // lists: every 2 indices one segment): drawn one pixel wide by the `scene` pass kind's
    // `lines` mode, unlit (their material's base colour shown as glTF's emissive is, plus its
    // emission), as glTF viewers draw them. They have no levels of detail, no lightmap uvs, cast
    // no shadows and no ray meets them. Their vertices' normals and tangents are not used.
    std::vector<Primitive> lines;
    std::vector<Primitive> points;
};

// ---------------------------------------------------------------------------------------------
// Textures and images

struct TextureRef {
    int32_t image = -1;     // index into Scene::images; -1: no texture
    int32_t sampler = -1;   // index into Scene::samplers; -1: the default (linear, repeat)
    uint32_t texCoord = 0;  // 0: Vertex::uv0, 1: Vertex::uv1
    // KHR_texture_transform as a uv matrix: uv' = (transform * vec3(uv, 1)).xy, i.e.
    // translation(offset) * rotation(rotation) * scale(scale) with glTF's rotation sign.
    glm::mat3 transform{1.0f};

    bool valid() const { return image >= 0; }
};

// A decoded texture. `pixels` holds the values the file holds, as floats in [0, 1], always four
// channels (RGBA; grey and grey+alpha are expanded, a missing alpha is 1). When `srgb` is true the
// colour channels are sRGB-encoded (upload as an *_SRGB format, or srgbDecode() them; alpha is
// always linear); base colour and emissive textures are sRGB (glTF), every other map is linear.
struct SceneImage {
    std::string name;
    rg::Image pixels;  // level 0
    bool srgb = false;
    uint32_t mipLevels = 1;  // floor(log2(max(width, height))) + 1 once generateMips() ran
    // Levels 1 .. mipLevels-1 (level 0 is `pixels`), each max(1, floor(previous / 2)) wide and
    // high, box-filtered from the previous level; sRGB images are filtered in linear space and
    // re-encoded. Same channel layout and encoding as `pixels`.
    std::vector<rg::Image> mips;

    const rg::Image& level(uint32_t i) const { return i == 0 ? pixels : mips.at(i - 1); }
};

enum class Filter : uint8_t { Nearest, Linear };
enum class MipmapMode : uint8_t { Nearest, Linear };
enum class Wrap : uint8_t { Repeat, ClampToEdge, MirroredRepeat };

struct SamplerDesc {
    Filter magFilter = Filter::Linear;
    Filter minFilter = Filter::Linear;
    MipmapMode mipmapMode = MipmapMode::Linear;
    Wrap wrapS = Wrap::Repeat;
    Wrap wrapT = Wrap::Repeat;
    bool operator==(const SamplerDesc&) const = default;
};

// ---------------------------------------------------------------------------------------------
// Materials (seed 000 §3.2.1)

enum class AlphaMode : uint8_t { Opaque, Mask, Blend };

struct Material {
    std::string name;
    // The pipeline material it maps to ("standard", "two_colour", or a game-team material such as
    // "clear_coat"); the pipeline gives the materialId.
    std::string model = "standard";

    // Disney base material (tbl:2). Factors; a texture, when present, multiplies them.
    glm::vec3 baseColor{0.5f};  // linear; diffuse albedo (dielectrics) or f0 (metals)
    float smoothness = 0.5f;    // 1 - perceptual roughness (glTF roughness); alpha = (1 - s)^2
    float metalMask = 0.0f;     // glTF metallic
    float reflectance = 0.5f;   // dielectric f0 = 0.16 * reflectance^2 (0.5 -> 4 %)
    float ao = 1.0f;            // ambient occlusion factor
    // Emitted luminance in nits (cd/m²), linear RGB (or, with emissiveEv, a colour relative to
    // the exposure). From glTF: emissiveFactor (× the emissive texture) ×
    // KHR_materials_emissive_strength, relative to the exposure (kGltfEmissiveEc).
    glm::vec3 emissive{0.0f};
    // Emission given relative to the camera's exposure instead (seed 002 §5.1.3): `emissive` is a
    // colour at `emissiveEc` stops, its luminance emissive · 2^(EV100 + emissiveEc − 3) with the
    // EV100 the frame is pre-exposed with (the last frame's), so it keeps its place on screen as
    // exposure adapts. 2^(EV100 − 3) is the average luminance that EV100 meters (seed 000 eq:12).
    bool emissiveEv = false;
    float emissiveEc = 0.0f;
    float opacity = 1.0f;  // base colour alpha (glTF baseColorFactor.a)

    // Two-colour base material (tbl:3), used when model == "two_colour".
    glm::vec3 diffuseColor{0.5f};
    glm::vec3 f0{0.04f};

    TextureRef baseColorTex;          // sRGB; rgb × baseColor, a × opacity
    TextureRef metallicRoughnessTex;  // linear; g = roughness (× (1 - smoothness)), b = metallic
    TextureRef normalTex;             // linear tangent-space normal map
    TextureRef occlusionTex;          // linear; r = occlusion
    TextureRef emissiveTex;           // sRGB; rgb × emissive
    float normalScale = 1.0f;
    float occlusionStrength = 1.0f;

    AlphaMode alphaMode = AlphaMode::Opaque;
    float alphaCutoff = 0.5f;
    bool doubleSided = false;

    Value extra;  // a table of other parameters for game-team materials (clear coat, foliage, ...)
    // A game-team material's own textures by the names its pipeline material declares
    // (rg.material's `textures`; the clear coat's coat maps, the two-colour material's
    // specular-glossiness map); each multiplies what its surface function says. When the scene
    // loads, the names are checked against the model's and every one it lacks is added without an
    // image (white), so the map's order is the model's slot order.
    std::map<std::string, TextureRef> textures;
    // Every texture reference it has: the five maps, then its model's own in name order (the
    // order of their bindings and RG_TEXTURES bits, passes/scene_pass_detail.h variantKey).
    std::vector<TextureRef*> textureRefs() {
        std::vector<TextureRef*> out = {&baseColorTex, &metallicRoughnessTex, &normalTex,
                                        &occlusionTex, &emissiveTex};
        for (auto& [name, ref] : textures) out.push_back(&ref);
        return out;
    }
    std::vector<const TextureRef*> textureRefs() const {
        std::vector<TextureRef*> refs = const_cast<Material*>(this)->textureRefs();
        return {refs.begin(), refs.end()};
    }
    // Where it was declared, for errors found once the pipeline is known: "file:line:
    // scene.material.NAME" (Lua scenes) or "file: material 'NAME'" (glTF); empty when made in code.
    std::string origin;
};

// ---------------------------------------------------------------------------------------------
// Nodes, lights, cameras, environment

// A glTF animation (glTF 2.0 §3.11) as the loader read it: its keyframe samplers and every glTF
// node of the file with its parent, its rest transform and the samplers that drive its
// translation, rotation and scale. The scene nodes under the nodes it moves share it
// (Node::animation) and are placed by world() each frame; it loops over its duration.
struct Animation {
    enum class Interpolation : uint8_t { Step, Linear, CubicSpline };
    struct Sampler {
        std::vector<float> times;  // ascending, seconds
        // One value per key (xyz; a rotation's quaternion x, y, z, w); CUBICSPLINE: three per key
        // (in-tangent, value, out-tangent).
        std::vector<glm::vec4> values;
        Interpolation interpolation = Interpolation::Linear;
        bool rotation = false;  // slerped and normalised
    };
    struct GltfNode {
        int32_t parent = -1;
        glm::vec3 translation{0.0f}, scale{1.0f};
        glm::vec4 rotation{0.0f, 0.0f, 0.0f, 1.0f};  // x, y, z, w
        std::optional<glm::mat4> matrix;             // a node given by matrix (never animated)
        int32_t sampler[3] = {-1, -1, -1};           // translation, rotation, scale
    };
    std::string name;
    std::vector<Sampler> samplers;
    std::vector<GltfNode> nodes;
    float duration = 0.0f;  // the last key of any sampler
    // glTF node `node`'s world transform in the file at `seconds` (modulo the duration).
    glm::mat4 world(size_t node, double seconds) const;
    // Sampler s's value at t (inside [0, duration]).
    glm::vec4 sample(size_t s, float t) const;
};

// The flattened hierarchy: one entry per node that draws a mesh, with its world transform.
struct Node {
    std::string name;
    glm::mat4 world{1.0f};
    int32_t mesh = -1;  // index into Scene::meshes
    // Where the node's uv1 square lands in the scene's lightmap atlas: atlas uv = uv1 * xy + zw
    // (packLightmap); zero when the node has no lightmap.
    glm::vec4 lightmapRect{0.0f};
    // Whether it is drawn into the rasterised shadow maps (the sun's cascades, the local lights'
    // views). Off for a surface nothing can stand behind — a ground plane under a sky — it spares
    // the maps its depth fill; it still receives shadows, and the ray casts (the reference mode,
    // the probe capture's shadow rays, the lightmap bake) still see it.
    bool castShadows = true;
    // An area light's emissive shape (runtime/light_shapes.h): drawn, but left out of every ray
    // cast (the BVH of the probe capture's and the reference's shadow rays).
    bool lightShape = false;
    // A node that moves after the scene loads: along `path`, or as the library's
    // Renderer::setTransform places it. Its draws carry this frame's and the last frame's
    // transforms (the motion target the G-buffer and forward passes write); `world` is where the
    // first frame has it. What is computed once leaves it out (probe captures, the ray casts'
    // hierarchy), and a lightmap refuses it.
    bool dynamic = false;
    // A move (a Lua scene object's `path`): keys in time order; at time t (seconds, a frame's
    // ctx.time) the placement's position and rotation (radians about X, then Y, then Z) pass
    // through the keys on Catmull-Rom curves, as a camera's path does, and the node's world
    // transform is translate(position) · rotate(rotation) · `placed`.
    struct Key {
        float time = 0.0f;
        glm::vec3 position{0.0f}, rotation{0.0f};
    };
    std::vector<Key> path;
    glm::mat4 placed{1.0f};  // below the path's placement: the object's scale, a glTF node's own
    // A glTF animation that moves it (it, or a node above it in the file): then below the path's
    // placement (or as its whole transform without a path) it is animationPlacement ·
    // animation->world(animationNode, t) · animationLocal — the placement of the file in the
    // scene, its glTF node's world in the file, and what lies below that node (an
    // EXT_mesh_gpu_instancing instance's transform).
    std::shared_ptr<const Animation> animation;
    int32_t animationNode = -1;
    glm::mat4 animationPlacement{1.0f}, animationLocal{1.0f};
    // The node's world transform at `seconds` along its path and animation (`world` without).
    glm::mat4 at(double seconds) const;
};

enum class LightType : uint8_t {
    Point,        // punctual; lm or cd (seed 000 tbl:8)
    Spot,         // punctual; lm or cd
    Directional,  // the sun: a disk light of angular radius sunAngularRadius, in lux
    Sphere,       // area lights: lm, nits or ev100
    Disk,
    Rect,
    Tube,
};
const char* lightTypeName(LightType t);  // "point", "spot", "sun", "sphere", "disk", "rect", "tube"

struct Light {
    std::string name;
    LightType type = LightType::Point;
    glm::vec3 position{0.0f};  // metres (unused by the sun)
    // Unit vector the light points along (the way its light travels): a spot's axis, a disk's or
    // a rect's emitting side, the sun's rays (from the sun towards the scene), a tube's axis.
    glm::vec3 direction{0.0f, -1.0f, 0.0f};
    glm::vec3 up{0.0f, 1.0f, 0.0f};  // rect lights: the direction of `height`
    glm::vec3 color{1.0f};           // linear RGB, multiplies the intensity
    float temperatureK = 0.0f;       // kelvin; 0 = use color (lights::colorTemperatureXy's ranges)
    bool daylight = false;           // temperatureK on the CIE daylight locus, not the black body's
    float intensity = 1.0f;          // in `unit`
    std::string unit = "lm";         // "lm", "cd", "lux", "nits", "ev100" (as declared)
    float radius = 0.0f;             // sphere, disk, tube (metres)
    float width = 0.0f, height = 0.0f;  // rect (metres)
    float length = 0.0f;                // tube (metres)
    float innerAngle = 0.0f;            // spot half-angles (radians); a disk's cone when `cone`
    float outerAngle = 0.785398f;
    // A disk light with a cone (seed 000 lst:9, "the disk is like a spot"): its illuminance is
    // attenuated as a spot's by innerAngle/outerAngle, seen from the apex of the cone of half-angle
    // outerAngle through its rim (lighting::diskVirtualPosition). Not physical: the seed's way of
    // giving the disk a spot's smooth edge.
    bool cone = false;
    float range = 0.0f;  // metres; 0 = unlimited (windowed falloff otherwise)
    std::string ies;     // path of an IES (LM-63) profile, "" for none
    // How the profile sets the intensity (seed 000 §4.5, eq:27, lst:5): "mask" (the declared
    // intensity shaped by I / I_max), "intensity" (the profile's own candela), "" = the scene's
    // default (passes::GpuSceneOptions::iesMode, itself "mask").
    std::string iesMode;
    // A spot in lumens: false = Frostbite's default, eq:17 (I = Φ / π, the cone only masks),
    // true = eq:16's exact cone (I = Φ / 2π(1 − cos θ_outer)).
    bool exactCone = false;
    float sunAngularRadius = 0.00465f;  // radians (the sun seen from the earth: 0.2664°)
    // The sun taken out of the scene's environment image (takeEnvironmentSun), not declared.
    bool fromEnvironment = false;
    // Sphere, disk, rect and tube lights: drawn as their emissive shape at the light's luminance
    // (seed 002 §4.8; runtime/light_shapes.h).
    bool visible = true;
    // A local light that casts shadows (a shadow map per frame while its range reaches the view:
    // scripts/shadows.lua's local maps). The sun's shadow is the pipeline's (`sun_shadows`).
    bool castShadows = false;
    // Baked into the scene's lightmap (scene.lightmap): its direct and indirect light are in the
    // lightmap and the real-time light loop skips it. A light that is not baked stays dynamic: the
    // lightmap holds only its indirect light (what it bounces off the scene's surfaces).
    bool baked = false;
};

// A physical camera (seed 002 §5.2). Exposure comes from aperture, shutter and ISO.
struct Camera {
    std::string name;
    glm::vec3 position{0.0f, 0.0f, 5.0f};
    glm::vec3 target{0.0f};
    glm::vec3 up{0.0f, 1.0f, 0.0f};
    float verticalFov = 0.785398f;  // radians
    bool orthographic = false;      // a parallel projection of `orthoHeight` metres (glTF: 2 ymag)
    float orthoHeight = 2.0f;
    float focalLength = 0.0f;                     // metres; 0 = derived from verticalFov
    float sensorHeight = 0.024f;                  // metres (full frame)
    float nearPlane = 0.05f, farPlane = 1000.0f;  // metres
    float aperture = 16.0f;                       // f-number N
    float shutter = 0.008f;                       // seconds (1/125)
    float iso = 100.0f;
    float exposureCompensation = 0.0f;  // EV
    // A camera move (scene.camera's `path`): keys in time order; at time t (seconds, a frame's
    // ctx.time) the position and target pass through the keys on Catmull-Rom curves (tangents
    // from the neighbouring keys; held before the first and after the last). Empty: it stands.
    struct Key {
        float time = 0.0f;
        glm::vec3 position{0.0f}, target{0.0f};
    };
    std::vector<Key> path;
    // This camera at `seconds` along its path (itself when it has none).
    Camera at(double seconds) const;
};

struct Environment {
    std::string name;
    std::string kind = "sky";   // "sky" (procedural), "hdr" (equirectangular file), "color"
    std::string file;           // "hdr": the .hdr/.exr path (resolved, absolute)
    glm::vec3 color{1.0f};      // "color": linear RGB
    float intensity = 1.0f;     // multiplies the file / colour / sky, in `unit`
    std::string unit = "nits";  // sky and image-based light: luminance (tbl:8)
    float rotation = 0.0f;      // radians about +Y
    float turbidity = 2.5f;     // "sky": Preetham's atmospheric turbidity (2 clear .. 10 hazy)
    // "hdr": what becomes of a sun in the image (seed 002 §4.9.1.1; environment.h
    // findEnvironmentSun): "light" — taken out of the image and added to the scene as a sun light
    // of its direction, illuminance and angular size; "remove" — taken out, the scene's own sun
    // stands for it; "keep" — left in the image; "auto" (the default) — "remove" when the scene
    // has a sun light of its own, else "light". Never counted twice.
    std::string sun = "auto";
    // What environmentImage returns, kept by takeEnvironmentSun, which had to read the file and
    // find the sun anyway (the sun taken out unless "keep"): the file is read once per load.
    std::shared_ptr<const Image> image;
};
// Environment::sun's values (the Lua field, glTF extras, --environment-sun).
inline const std::vector<std::string> kEnvironmentSunModes = {"auto", "light", "remove", "keep"};

// A deferred decal (seed 000 §3.3): a box that, where it encloses the G-buffer's surface, blends
// the common parameters — Normal (towards the box's +Y axis), BaseColor, Smoothness, and on
// materialId 0 only MetalMask and Reflectance — with linear alpha blending. MaterialId and
// MaterialData are never touched (they do not blend).
struct Decal {
    std::string name;
    glm::mat4 world{1.0f};  // unit box [-0.5, 0.5]^3 to world (position, rotation, size)
    float opacity = 1.0f;
    bool hasBaseColor = false, hasSmoothness = false, hasMetalMask = false, hasReflectance = false;
    bool normal = false;  // blend the normal towards the box's +Y axis
    glm::vec3 baseColor{1.0f};
    float smoothness = 0.5f, metalMask = 0.0f, reflectance = 0.5f;
};

// A local light probe (seed 002 §4.9.1.2, §4.9.3, appendix F): the scene as seen from `position`,
// captured into a cube (diffuse only, metals with f0 as albedo, visibility in alpha) and
// reflected by the surfaces inside its shape: a sphere of `radius` or a box of `size` (turned by
// `rotation`): the proxy its reflections are parallax-corrected against, and — unless an influence
// of its own is given (`influence`: a sphere's radius or a box's size, same centre and axes) —
// the volume it reflects in, fading to nothing over `fade` metres inside that volume's boundary. Where several hold a point,
// the higher `priority` goes first, then the smaller.
inline constexpr size_t kMaxProbes = 8;  // shaders/lib/probes.glsl RG_MAX_PROBES
struct Probe {
    std::string name;
    std::string origin;  // FILE:LINE of the declaration
    bool box = false;
    glm::vec3 position{0.0f};
    float radius = 1.0f;            // sphere
    glm::vec3 size{1.0f};           // box: full extent along its local axes (metres)
    glm::mat3 rotation{1.0f};       // box: local axes in world space
    float influenceRadius = 0.0f;   // sphere: 0 = the proxy's radius
    glm::vec3 influenceSize{0.0f};  // box: 0 = the proxy's size
    float fade = 0.25f;             // metres
    int priority = 0;
    // The influence volume's half extents (a sphere: its radius on every axis), the proxy's unless given.
    glm::vec3 influenceHalfExtents() const {
        if (box) return 0.5f * (influenceSize.x > 0.0f ? influenceSize : size);
        return glm::vec3(influenceRadius > 0.0f ? influenceRadius : radius);
    }
};

// Baked global illumination (seed 003, "SG Lightmaps"): the settings of the scene's lightmap,
// declared by scene.lightmap. graph/bake bakes it (rgraph bake); the G-buffer pass reads it.
struct LightmapSettings {
    std::string name;
    std::string origin;    // FILE:LINE of the declaration
    float density = 4.0f;  // lightmap texels per metre of surface
    int lobes = 9;         // SG lobes per texel: 5, 6, 9 or 12 (seed 003 "Light Map Data")
    int samples = 128;     // paths per texel
    int bounces = 2;       // indirect bounces after the first hit (>= 2 gives two-bounce GI)
    int maxSize = 2048;  // the atlas's largest side; a scene too large for it gets a lower density
};

// A baked SG lightmap (graph/bake): per texel, the radiance arriving over the upper hemisphere as
// N spherical Gaussians G_k(x) = A_k e^{λ (μ_k · x − 1)} in the texel's tangent frame (z the
// normal); only the amplitudes A_k (RGB, ≥ 0, nits) vary per texel. Nodes map into it by
// Node::lightmapRect.
struct Lightmap {
    uint32_t width = 0, height = 0;
    std::vector<glm::vec3> axes;                // μ_k, tangent space
    float sharpness = 0.0f;                     // λ
    std::vector<std::vector<glm::vec3>> lobes;  // [k][y * width + x]: A_k
    // The amplitudes the fit gives a uniform 1-nit hemisphere: what the specular term divides by,
    // so that the lobes' ripple and the part of a wide lobe below the horizon cancel out.
    std::vector<float> unit;
    std::vector<uint8_t> coverage;  // 1: a surface's texel (0: border or gutter, dilated)
    float density = 0.0f;           // texels per metre
    std::string key;                // the content hash it was baked for
};

struct Scene {
    std::vector<Mesh> meshes;
    std::vector<Decal> decals;
    std::vector<Probe> probes;
    std::vector<Material> materials;
    std::vector<SceneImage> images;
    std::vector<SamplerDesc> samplers;
    std::vector<Node> nodes;
    std::vector<Light> lights;
    std::vector<Camera> cameras;
    std::optional<Environment> environment;
    std::optional<LightmapSettings> lightmap;
    std::shared_ptr<const Lightmap>
        bakedLightmap;               // the lightmap the G-buffer pass reads (none: not used)
    std::vector<std::string> files;  // every file read (absolute paths), for hot reload
    // What the loaders skipped or changed without failing, a line each (an orthographic camera,
    // an extension ignored, a coloured specular kept as its mean): `render --verbose` prints them.
    std::vector<std::string> warnings;
    glm::vec3 boundsMin{0.0f}, boundsMax{0.0f};  // world-space box around every node's mesh
    // What building levels of detail did (mesh_lod.h buildMeshLods), summed over its calls.
    struct LodStats {
        size_t primitives = 0;  // primitives given levels
        size_t levels = 0;      // levels built or read in all
        size_t cached = 0;      // primitives whose levels came from a cache (memory or file)
        double ms = 0.0;        // time spent, cache look-ups included
    } lodStats;
};

// ---------------------------------------------------------------------------------------------
// Loading and saving

// glTF's emissive has no unit, and viewers show an emissiveFactor of 1 as white: rgraph reads it
// relative to the exposure (Material::emissiveEv) at the EC where a factor of 1 exposes to 1,
// white before the tone curve: exposure = 1 / (1.2 · 2^EV100), so EC = log2(1.2 · 8).
inline constexpr float kGltfEmissiveEc = 3.2630344f;

// The EV100 emission relative to the exposure is taken at where no camera's is at hand (probe
// captures, the lightmap baker, a scene pass that reads no exposure state): Sunny 16's.
inline constexpr float kEmissiveEv100WithoutExposure = 15.0f;

// The folder where glTF geometry that is slower to decode than to read (KHR_draco_mesh_compression)
// is kept decoded, by the content hash of the compressed bytes ("" = none, the default; the
// runtime sets <cache>/decoded): a file that does not read back whole is decoded anew.
void setGltfDecodeCacheDir(std::string dir);

struct GltfOptions {
    bool loadImages = true;    // false: materials keep their texture references, images stay empty
    bool generateMips = true;  // fill SceneImage::mips
    bool buildLods = true;     // levels of detail for its meshes (mesh_lod.h buildMeshLods)
    // KHR_materials_variants: the variant whose materials the primitives take ("" = the file's
    // default materials). A name the file does not have is an error listing the ones it has.
    std::string variant;
    // The animation whose channels move the nodes (glTF 2.0 §3.11; translation, rotation and scale
    // of nodes; played from the frame's time, looping): "" = the file's first, "none" = none (the
    // nodes stand at their rest transforms). A name the file does not have is an error listing
    // the ones it has.
    std::string animation;
};

// Loads a .gltf (with its external .bin files and images, or data: URIs) or a .glb.
// - Every node of the default scene (or every root node when there is none) becomes a Node with
//   its world transform; cameras and KHR_lights_punctual lights take their node's transform.
// - Triangle primitives (TRIANGLES, TRIANGLE_STRIP, TRIANGLE_FAN; indexed or not) become
//   triangle lists; points and lines become Mesh::points and Mesh::lines (strips and loops as
//   segment lists), a mode glTF does not have is refused. Missing normals become flat normals;
//   missing tangents are generated by MikkTSpace from the normal map's uv set (generateTangents).
// - Materials map as DESIGN.md §5 says: smoothness = 1 - roughness, metalMask = metallic,
//   reflectance 0.5 (KHR_materials_specular / _ior are ignored), emissive in nits × strength.
//   A material whose extras hold { "rgraph": { ... } } (written by exportGlb) gets back the
//   fields glTF cannot say (model, reflectance, ao, two-colour, params).
// Errors name the file and the thing: NotFound for a missing file, InvalidInput for broken JSON,
// a missing buffer or image, an accessor out of range; Unsupported for a required extension or
// a primitive mode rgraph does not handle.
Result<Scene> loadGltf(const std::string& path, const GltfOptions& options = {});

struct SceneScriptOptions {
    std::string projectRoot;  // "" = RG_ROOT when set, else the source tree this was built from
    bool loadImages = true;   // passed on to the glTF files the script names
    bool generateMips = true;
    bool buildLods = true;  // levels of detail for the meshes without (mesh_lod.h buildMeshLods)
    std::map<std::string, std::string>
        args;  // the script's `scene.args` (rgraph --scene-arg NAME=VALUE)
    // The folder the files the script names are relative to; "" = the script's own folder (a
    // script given as source, the library's Renderer::loadSceneSource, lives elsewhere).
    std::string baseDir;
};

// Runs a Lua scene script (scene.material/sphere/plane/box/gltf/light/camera/environment, see
// scripts/scenes/README.md) in the sandboxed host and builds the scene. Every field is checked: an
// unknown field (with a suggestion), a wrong type, a value out of range, an unknown material,
// a light unit its type cannot have; errors read "file:line: scene.kind.name.field: ...".
// Without a scene.camera the scene gets a camera named "default" that frames the bounds.
Result<Scene> loadSceneScript(const std::string& path, const SceneScriptOptions& options = {});

// Writes a binary glTF: meshes, materials (metallic-roughness: roughness = 1 - smoothness; what
// glTF cannot hold goes to the material's extras.rgraph), images as embedded PNG (8 bits), one
// root node per Node, cameras (physical settings in extras) and KHR_lights_punctual lights whose
// unit glTF can say (cd for point/spot, lux for the sun). Other lights are skipped with a line
// in `warnings`. Written to a temporary file and renamed, so a failure leaves `path` untouched.
Result<void> exportGlb(const Scene& scene, const std::string& path,
                       std::vector<std::string>* warnings = nullptr);

// ---------------------------------------------------------------------------------------------
// Helpers (used by the loaders, public for tests and tools)

// Fills image.mips and image.mipLevels: the full chain down to 1x1, box filter (each texel of a
// level is the area-weighted mean of the texels of the previous level it covers, so odd sizes
// are exact); colour channels of sRGB images are averaged in linear space.
void generateMips(SceneImage& image);

// Tangents by the MikkTSpace algorithm (geometry.cpp; glTF 2.0 §3.7.2.1) from uv set `uvSlot`
// (0: uv0, 1: uv1 — the normal map's): per corner the triangle's dP/du in the plane of the
// corner's normal, weighted by the corner's angle, summed over identical vertices of the same uv
// orientation; w = +1 where the uv area is negative (v downwards, glTF's), −1 on a mirrored half.
// A vertex that triangles of both orientations share is split: the copies are appended, and the
// returned list says of which vertex each is a copy (so per-vertex data kept beside the primitive
// can follow). A vertex without a uv gradient gets any unit vector perpendicular to its normal.
std::vector<uint32_t> generateTangents(Primitive& primitive, uint32_t uvSlot = 0);

// Gives every triangle its own three vertices with the face normal (glTF: no normals means flat).
void generateFlatNormals(Primitive& primitive);

// Meshes the Lua scene makes (unit-free, in metres, centred on the origin, CCW outwards).
Primitive makeSphere(float radius, uint32_t segments,
                     uint32_t material);  // segments around, segments/2 rings
Primitive makePlane(float width, float depth, uint32_t material);  // XZ plane, normal +Y
Primitive makeBox(glm::vec3 size, uint32_t material);
// A disk in the XZ plane facing +Y (one-sided), a fan of `segments` triangles.
Primitive makeDisk(float radius, uint32_t segments, uint32_t material);
// A capsule along Y: a cylinder of `length` between two hemispheres of `radius`.
Primitive makeCapsule(float radius, float length, uint32_t segments, uint32_t material);
// Generated shapes carry lightmap uvs (Primitive::lightmapUv): a plane and a sphere their uv square,
// a box its faces in a 3 × 2 grid, each inset by this fraction of its cell.
inline constexpr float kBoxChartInset = 0.1f;
inline constexpr uint32_t kMinBoxLightmapTexels = 32;

// Recomputes Scene::boundsMin/boundsMax from the nodes' meshes.
void computeBounds(Scene& scene);

}  // namespace rg
