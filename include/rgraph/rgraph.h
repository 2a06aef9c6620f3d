// rgraph as a library: a render graph declared in Lua, rendering on a Vulkan device that rgraph
// creates or the host application owns. The interface is plain C++ and Vulkan handles; nothing
// of Lua, glslang or the graph compiler shows here. Errors are thrown as rgraph::Error with the
// same messages as the command line (a script's file:line, the pass and the field).
//
//   auto r = rgraph::Renderer::create();                    // or create(rgraph::HostDevice{...})
//   r->loadPipeline(rgraph::Renderer::dataDir() + "/scripts/pipelines/deferred.lua");
//   r->setScene(scene);                                     // or loadScene("scene.lua" / ".glb")
//   r->setSize(1280, 720);
//   r->render();
//   rgraph::writePng("frame.png", r->readDisplay());
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <variant>
#include <vector>

#include <vulkan/vulkan.h>

// librgraph is built with hidden visibility: what this header declares is its whole interface.
#pragma GCC visibility push(default)

namespace rgraph {

// Every failure: a script error (file:line: field: what was expected), a device error, bad input.
class Error : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

// The host's Vulkan device. rgraph renders with it and never destroys it. It must be Vulkan 1.3
// with dynamicRendering, synchronization2, maintenance4, hostQueryReset (1.2) and imageCubeArray
// enabled; the queue family must support graphics, compute and timestamps. The host must not use
// the queue from another thread while rgraph renders.
struct HostDevice {
    VkInstance instance = VK_NULL_HANDLE;
    VkPhysicalDevice physicalDevice = VK_NULL_HANDLE;
    VkDevice device = VK_NULL_HANDLE;
    uint32_t queueFamily = 0;
    VkQueue queue = VK_NULL_HANDLE;
};

struct Options {
    int device = -1;  // the Vulkan device index when rgraph creates the device (-1: the best)
    bool validation = false;  // the Khronos validation layer, when rgraph creates the instance
    std::string dataDir;      // scripts/, materials/, shaders/ ("" = the installed ones: dataDir())
    std::string cacheDir;     // SPIR-V, pipeline and generated-shader caches ("" = the default)
    // Restore what the passes that run once per build write (environment filtering, probe capture,
    // lookup tables) from cacheDir's once/ when the same passes, shaders, scene and device made it
    // before, and save it there otherwise (`rgraph render` does the same). Not for frames the host
    // records into its own command buffer.
    bool onceCache = true;
};

// A scene made in code. Units: metres, lumens/candela/lux/nits as the light says, seconds.
// A coarser index list over a mesh's vertices, and how far its surface lies from the full one
// (metres, in the mesh's own space): the camera's passes draw the coarsest whose error spans at
// most a pixel, the sun's shadow maps the coarsest within a texel (and never finer than the camera's).
struct MeshLod {
    std::vector<uint32_t> indices;
    float error = 0.0f;
};
struct Mesh {
    std::string name;
    std::vector<float> positions;   // xyz per vertex
    std::vector<float> normals;     // xyz per vertex (unit)
    std::vector<float> uvs;         // uv per vertex, or empty
    std::vector<uint32_t> indices;  // triangles, counter-clockwise seen from outside
    std::vector<MeshLod> lods;  // levels of detail, finest first (makeSphere fills them), or empty
    std::string material;       // a Material's name
    float transform[16] = {1, 0, 0, 0, 0, 1, 0, 0,
                           0, 0, 1, 0, 0, 0, 0, 1};  // column-major, model to world
    // It moves after the scene loads (Renderer::setTransform): its draws carry this frame's and
    // the last frame's transforms, so the pipeline writes its motion (TAA follows it). What is
    // computed once leaves it out: probe captures and the ray casts' shadows.
    bool dynamic = false;
};
// Meshes as rgraph's Lua scenes make them (centred on the origin): the same vertices, so a scene
// built from them renders as the Lua scene does.
Mesh makeSphere(float radius, uint32_t segments = 48);
Mesh makePlane(float width, float depth);
Mesh makeBox(float width, float height, float depth);

struct Material {
    std::string name;
    std::string model = "standard";           // a material the pipeline declares (rg.material)
    float baseColor[3] = {0.5f, 0.5f, 0.5f};  // linear
    float smoothness = 0.5f, metalMask = 0.0f, reflectance = 0.5f, ao = 1.0f;
    float emissive[3] = {0, 0, 0};  // nits
    float opacity = 1.0f;
    // Opaque; Mask: cut out where opacity (× the base colour map's alpha) < alphaCutoff; Blend:
    // drawn by the forward pass, blended with `opacity`.
    enum class Alpha { Opaque, Mask, Blend } alpha = Alpha::Opaque;
    float alphaCutoff = 0.5f;
    bool doubleSided = false;
    // Texture files (PNG or JPEG), as glTF's maps, each multiplying its factor: base colour (sRGB;
    // its alpha × opacity), metallic-roughness (linear; g roughness, b metallic), tangent-space
    // normal (× normalScale), occlusion (r), emissive (sRGB). "" for none.
    std::string baseColorMap, metallicRoughnessMap, normalMap, occlusionMap, emissiveMap;
    float normalScale = 1.0f;
    std::map<std::string, double> params;  // the model's own parameters, by name (checked)
};

struct Light {
    enum class Type { Point, Spot, Sun, Sphere, Disk, Rect, Tube } type = Type::Point;
    float position[3] = {0, 0, 0};
    float direction[3] = {0, -1, 0};  // the way the light travels (spot, sun, disk, rect)
    float color[3] = {1, 1, 1};
    float intensity = 1000.0f;
    std::string unit = "lm";  // "lm", "cd", "lux" (sun), "nits", "ev100" (area lights)
    float radius = 0, width = 0, height = 0, length = 0;  // area lights, metres
    float innerAngle = 0.0f, outerAngle = 0.785398f;      // spot half-angles, radians
    float range = 0.0f;                                   // metres, 0 = unlimited
    bool shadows = false;
    // Colour temperature in kelvin, multiplying `color` (0: none): the black body's chromaticity,
    // or the CIE daylight locus's with `daylight` (4000 K and up).
    float temperature = 0.0f;
    bool daylight = false;
    // An IES (LM-63) profile for a point or spot light (a file; "" for none), and how it sets the
    // intensity: "mask" (the declared intensity shaped by I / I_max) or "intensity" (its candela).
    std::string ies;
    std::string iesMode = "mask";
};

// A deferred decal: a box (the unit cube [-0.5, 0.5]³ through `transform`) that blends, where it
// encloses a surface of the G-buffer, the parameters it sets, with `opacity`. A parameter left at
// a negative value is not blended.
struct Decal {
    std::string name;
    float transform[16] = {1, 0, 0, 0, 0, 1, 0, 0,
                           0, 0, 1, 0, 0, 0, 0, 1};  // column-major, unit box to world
    float opacity = 1.0f;
    float baseColor[3] = {-1, -1, -1};  // linear
    float smoothness = -1.0f, metalMask = -1.0f, reflectance = -1.0f;
    bool normal = false;  // the surface's normal towards the box's +Y axis
};

struct Camera {
    float position[3] = {0, 1, 5};
    float target[3] = {0, 0, 0};
    float verticalFovDegrees = 45.0f;
    float aperture = 16.0f, shutter = 1.0f / 125.0f, iso = 100.0f;  // f-number, seconds, ISO
};

struct Scene {
    std::vector<Mesh> meshes;
    std::vector<Material> materials;
    std::vector<Light> lights;
    std::vector<Decal> decals;
    Camera camera;
    std::string environment = "sky";  // "sky", "none", or an equirectangular .hdr/.exr file
};

// An image read back: `channels` floats per pixel, rows top to bottom.
struct Image {
    uint32_t width = 0, height = 0, channels = 0;
    std::vector<float> pixels;
};
void writePng(const std::string& path, const Image& display);  // display values in [0, 1]
void writeExr(const std::string& path, const Image& image);    // linear floats (layer "hdr")

// An image of the host's (a swapchain image, one of its own targets) that rgraph copies into an
// imported texture at each frame's start, or an exported texture into at its end. `layout` is the
// image's layout before the frame, and rgraph leaves it so after; the sizes must match the
// texture's (formats may differ: it is a blit).
struct HostImage {
    VkImage image = VK_NULL_HANDLE;
    uint32_t width = 0, height = 0;
    VkImageLayout layout = VK_IMAGE_LAYOUT_GENERAL;
};

struct PassTiming {
    std::string name;
    double gpuMs = 0.0;
};

using Value = std::variant<double, bool, std::string>;

class Renderer {
public:
    // rgraph creates its own Vulkan instance and device.
    static std::unique_ptr<Renderer> create(const Options& options = {});
    // rgraph renders on the host's device (see HostDevice for what it must have enabled).
    static std::unique_ptr<Renderer> create(const HostDevice& device, const Options& options = {});
    ~Renderer();
    Renderer(const Renderer&) = delete;
    Renderer& operator=(const Renderer&) = delete;

    // Where the installed scripts/, materials/ and shaders/ are (Options::dataDir overrides).
    static std::string dataDir();

    // A pipeline script (file, or Lua source with the name its errors should say). Loading is
    // transactional: a script that fails leaves the previous pipeline in place.
    void loadPipeline(const std::string& file);
    void loadPipelineSource(const std::string& name, const std::string& lua);
    // The scene the pipeline's scene passes draw: a .lua, .gltf or .glb file, or one made in code.
    // Takes effect at the next loadPipeline (or right away when a pipeline is loaded).
    void loadScene(const std::string& file);
    void setScene(const Scene& scene);
    // A Lua scene (scripts/scenes/README.md) given as source, with the name its errors should
    // say: everything a scene file can declare (textures, decals, probes, IES lights, glTF files,
    // the lightmap). Relative paths in it are taken from `baseDir` ("" = the current directory).
    void loadSceneSource(const std::string& name, const std::string& lua,
                         const std::string& baseDir = "");
    void setSize(uint32_t width, uint32_t height);  // takes effect at the next load

    // A pipeline parameter (rg.param) by name, checked against its type and range; a pass
    // switched on or off. Both apply from the next frame, as rg.frame's changes do.
    void setParameter(const std::string& name, const Value& value);
    void setPassEnabled(const std::string& pass, bool enabled);
    // A camera cut before the next frame: every history (TAA's, SSR's, the exposure) and the
    // camera's last frame start afresh, as a script's ctx.cut() does.
    void cameraCut();
    // Places a dynamic mesh (Mesh::dynamic, by name; or a Lua scene object with a `path`, which
    // it then no longer follows) at `transform` (column-major, model to world) from the next
    // frame, and again after the renderer reloads (setSize, keep, loadPipeline; a new scene starts
    // without). A mesh the scene lacks or one not dynamic is an error.
    void setTransform(const std::string& mesh, const float transform[16]);

    // Renders `frames` frames (submitting on rgraph's queue, or the host's) and waits for them.
    void render(uint32_t frames = 1);
    // Records one frame into the host's command buffer (begun, outside a render pass) for the host
    // to submit on the queue it gave; the host waits for it before recording the next but one.
    // No per-pass timings for such frames.
    void record(VkCommandBuffer commandBuffer);
    // The host's images in and out of the graph, every frame from the next (see HostImage): into
    // an imported texture (rg.resource { import = true }; give it before loadPipeline, as its
    // contents), or from an exported texture (the output, or one named by keep()). An image with
    // a null handle stops it.
    void importImage(const std::string& resource, const HostImage& image);
    void exportImage(const std::string& resource, const HostImage& image);
    Image readDisplay() const;  // the display image (tone-mapped, sRGB-encoded)
    Image readHdr() const;      // the HDR image in absolute nits (cd/m²)
    Image readResource(const std::string& name) const;  // a texture named by keep(), as stored
    void keep(const std::string& resource);   // exported for readResource (from the next load)
    std::vector<PassTiming> timings() const;  // per pass, the last frame
    std::string planJson() const;             // the compiled plan (as `rgraph graph --format json`)

private:
    struct Impl;
    explicit Renderer(std::unique_ptr<Impl> impl);
    std::unique_ptr<Impl> m;
};

}  // namespace rgraph

#pragma GCC visibility pop
