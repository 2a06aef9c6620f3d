// rgraph as a library (include/rgraph/rgraph.h), through its public interface only: a device the
// host owns, a scene built in code against the same scene from its Lua file, parameters and pass
// toggles between frames, and errors as exceptions with the command line's file:line messages.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <unistd.h>
#include <vector>

#include <rgraph/rgraph.h>

namespace {

namespace fs = std::filesystem;
const std::string kRoot = RG_SOURCE_ROOT;

rgraph::Options options() {
    rgraph::Options o;
    o.dataDir = kRoot;  // the source tree (an installed copy finds its own share/rgraph)
    o.validation = true;
    return o;
}

// Validation messages on the host's instance (a test fails on any).
int g_validationMessages = 0;
VKAPI_ATTR VkBool32 VKAPI_CALL onValidation(VkDebugUtilsMessageSeverityFlagBitsEXT,
                                            VkDebugUtilsMessageTypeFlagsEXT,
                                            const VkDebugUtilsMessengerCallbackDataEXT* data,
                                            void*) {
    ++g_validationMessages;
    std::fprintf(stderr, "host validation: %s\n", data && data->pMessage ? data->pMessage : "");
    return VK_FALSE;
}

// The host's Vulkan 1.3 device with what rgraph::HostDevice asks for.
struct HostVulkan {
    VkDebugUtilsMessengerEXT messenger = VK_NULL_HANDLE;
    VkInstance instance = VK_NULL_HANDLE;
    VkPhysicalDevice physical = VK_NULL_HANDLE;
    VkDevice device = VK_NULL_HANDLE;
    uint32_t family = 0;
    VkQueue queue = VK_NULL_HANDLE;
    HostVulkan() {
        VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
        app.apiVersion = VK_API_VERSION_1_3;
        VkInstanceCreateInfo ii{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
        ii.pApplicationInfo = &app;
        // The validation layer on the host's instance too (it reports to stdout: ctest shows it).
        const char* layer = "VK_LAYER_KHRONOS_validation";
        ii.enabledLayerCount = 1;
        ii.ppEnabledLayerNames = &layer;
        const char* extension = VK_EXT_DEBUG_UTILS_EXTENSION_NAME;
        ii.enabledExtensionCount = 1;
        ii.ppEnabledExtensionNames = &extension;
        if (vkCreateInstance(&ii, nullptr, &instance) != VK_SUCCESS) return;
        VkDebugUtilsMessengerCreateInfoEXT mi{
            VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
        mi.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT |
                             VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
        mi.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                         VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT;
        mi.pfnUserCallback = &onValidation;
        auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
            vkGetInstanceProcAddr(instance, "vkCreateDebugUtilsMessengerEXT"));
        if (create) create(instance, &mi, nullptr, &messenger);
        uint32_t n = 1;
        vkEnumeratePhysicalDevices(instance, &n, &physical);
        float priority = 1.0f;
        VkDeviceQueueCreateInfo qi{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
        qi.queueFamilyIndex = 0;
        qi.queueCount = 1;
        qi.pQueuePriorities = &priority;
        VkPhysicalDeviceVulkan13Features f13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
        f13.dynamicRendering = f13.synchronization2 = f13.maintenance4 = VK_TRUE;
        VkPhysicalDeviceVulkan12Features f12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES};
        f12.pNext = &f13;
        f12.hostQueryReset = VK_TRUE;
        VkPhysicalDeviceFeatures2 f{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
        vkGetPhysicalDeviceFeatures2(physical, &f);
        f.pNext = &f12;
        VkDeviceCreateInfo di{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
        di.pNext = &f;
        di.queueCreateInfoCount = 1;
        di.pQueueCreateInfos = &qi;
        if (vkCreateDevice(physical, &di, nullptr, &device) != VK_SUCCESS) return;
        vkGetDeviceQueue(device, family, 0, &queue);
    }
    ~HostVulkan() {
        if (device) vkDestroyDevice(device, nullptr);
        auto destroy = instance
                           ? reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
                                 vkGetInstanceProcAddr(instance, "vkDestroyDebugUtilsMessengerEXT"))
                           : nullptr;
        if (destroy && messenger) destroy(instance, messenger, nullptr);
        if (instance) vkDestroyInstance(instance, nullptr);
        EXPECT_EQ(g_validationMessages, 0) << "validation messages on the host's device";
    }
};

// The same scene twice: in code, and as a Lua scene file. With the features a Lua scene has
// beyond the basics: texture maps, an alpha-masked cut-out, a decal, a light of a colour
// temperature and an IES profile, when `dir` holds the texture. (Each of them left out of the
// Lua file alone moves the mean relative difference by 1.7e-4 (the IES) to 0.27 (the texture),
// well over the bound below.)
rgraph::Scene sceneInCode(const fs::path& dir = {}) {
    rgraph::Scene s;
    rgraph::Material floor{"floor"};
    floor.smoothness = 0.3f;
    rgraph::Material red{"red"};
    red.baseColor[0] = 0.8f, red.baseColor[1] = 0.1f, red.baseColor[2] = 0.1f;
    red.smoothness = 0.6f;
    s.materials = {floor, red};
    rgraph::Mesh ball = rgraph::makeSphere(0.5f);
    ball.material = "red";
    ball.transform[13] = 0.5f;
    rgraph::Mesh plane = rgraph::makePlane(6.0f, 6.0f);
    plane.material = "floor";
    s.meshes = {ball, plane};
    rgraph::Light sun;
    sun.type = rgraph::Light::Type::Sun;
    sun.intensity = 20000.0f;
    sun.unit = "lux";
    sun.direction[0] = -0.4f, sun.direction[1] = -0.8f, sun.direction[2] = -0.45f;
    s.lights = {sun};
    s.camera.position[1] = 1.2f, s.camera.position[2] = 3.0f;
    s.camera.target[1] = 0.4f;
    if (dir.empty()) return s;

    rgraph::Material checker{"checker"};
    checker.baseColorMap = (dir / "checker.png").string();
    checker.smoothness = 0.7f;
    rgraph::Material cutout{"cutout"};
    cutout.baseColorMap = (dir / "checker.png").string();
    cutout.alpha = rgraph::Material::Alpha::Mask;
    cutout.alphaCutoff = 0.4f;
    cutout.doubleSided = true;
    s.materials.push_back(checker);
    s.materials.push_back(cutout);
    rgraph::Mesh box = rgraph::makeBox(0.6f, 0.6f, 0.6f);
    box.material = "checker";
    box.transform[12] = -1.3f, box.transform[13] = 0.3f;
    rgraph::Mesh card = rgraph::makeBox(0.8f, 0.8f, 0.02f);
    card.material = "cutout";
    card.transform[12] = 1.2f, card.transform[13] = 0.4f, card.transform[14] = 0.5f;
    s.meshes.push_back(box);
    s.meshes.push_back(card);
    rgraph::Light warm;
    warm.position[0] = 1.0f, warm.position[1] = 1.0f, warm.position[2] = 1.0f;
    warm.intensity = 800.0f;
    warm.temperature = 2700.0f;
    rgraph::Light down;
    down.type = rgraph::Light::Type::Spot;
    down.position[0] = -1.3f, down.position[1] = 2.0f;
    down.intensity = 1200.0f;
    down.outerAngle = 1.0471976f;  // 60°
    down.ies = kRoot + "/tests/unit/ies/downlight_2002.ies";
    s.lights.push_back(warm);
    s.lights.push_back(down);
    rgraph::Decal stain{"stain"};
    stain.transform[0] = 1.0f, stain.transform[5] = 0.4f, stain.transform[10] = 1.0f;
    stain.transform[12] = 0.4f, stain.transform[14] = 0.8f;
    stain.baseColor[0] = 0.1f, stain.baseColor[1] = 0.2f, stain.baseColor[2] = 0.8f;
    stain.smoothness = 0.9f;
    stain.opacity = 0.8f;
    s.decals = {stain};
    return s;
}
const char* kSceneLua = R"(local scene = require "scene"
scene.material "floor" { smoothness = 0.3 }
scene.material "red" { base_color = { 0.8, 0.1, 0.1 }, smoothness = 0.6 }
scene.sphere "ball" { radius = 0.5, position = { 0, 0.5, 0 }, material = "red" }
scene.plane "plane" { size = { 6, 6 }, material = "floor" }
scene.light "sun" { type = "sun", intensity = 20000, unit = "lux", direction = { -0.4, -0.8, -0.45 } }
scene.camera "main" { position = { 0, 1.2, 3 }, target = { 0, 0.4, 0 }, fov = 45, aperture = 16, shutter = 1 / 125, iso = 100 }
scene.environment "sky" { kind = "sky" }
scene.material "checker" { base_color_map = "checker.png", smoothness = 0.7 }
scene.material "cutout" { base_color_map = "checker.png", alpha = "mask", alpha_cutoff = 0.4, double_sided = true }
scene.box "box" { size = { 0.6, 0.6, 0.6 }, position = { -1.3, 0.3, 0 }, material = "checker" }
scene.box "card" { size = { 0.8, 0.8, 0.02 }, position = { 1.2, 0.4, 0.5 }, material = "cutout" }
scene.light "warm" { type = "point", position = { 1, 1, 1 }, intensity = 800, temperature = 2700 }
scene.light "down" { type = "spot", position = { -1.3, 2, 0 }, direction = { 0, -1, 0 }, intensity = 1200, outer_angle = 60,
                     ies = "IES" }
scene.decal "stain" { position = { 0.4, 0, 0.8 }, size = { 1, 0.4, 1 }, base_color = { 0.1, 0.2, 0.8 }, smoothness = 0.9, opacity = 0.8 }
)";

// An 8x8 checker of 2x2 squares, opaque orange and transparent blue: the cut-out's mask.
void writeChecker(const fs::path& file) {
    rgraph::Image img{8, 8, 4, std::vector<float>(8 * 8 * 4)};
    for (uint32_t y = 0; y < 8; ++y)
        for (uint32_t x = 0; x < 8; ++x) {
            const bool on = ((x / 2) + (y / 2)) % 2 == 0;
            float* p = &img.pixels[(y * 8 + x) * 4];
            p[0] = on ? 0.9f : 0.1f, p[1] = on ? 0.5f : 0.2f, p[2] = on ? 0.1f : 0.8f;
            p[3] = on ? 1.0f : 0.0f;
        }
    rgraph::writePng(file.string(), img);
}

std::string sceneLua() {
    std::string lua = kSceneLua;
    lua.replace(lua.find("IES"), 3, kRoot + "/tests/unit/ies/downlight_2002.ies");
    return lua;
}

TEST(Library, RendersOnTheHostsDeviceAndTheHostReadsTheImage) {
    HostVulkan host;
    ASSERT_TRUE(host.device) << "no Vulkan 1.3 device for the host";
    auto r = rgraph::Renderer::create(
        rgraph::HostDevice{host.instance, host.physical, host.device, host.family, host.queue},
        options());
    r->setSize(160, 90);
    r->setScene(sceneInCode());
    r->loadPipeline(kRoot + "/scripts/pipelines/deferred.lua");
    r->render(2);
    rgraph::Image hdr = r->readHdr(), display = r->readDisplay();
    ASSERT_EQ(hdr.width, 160u);
    ASSERT_EQ(display.height, 90u);
    // The ball's centre is red and lit, in nits.
    const float* ball = &hdr.pixels[(45u * 160u + 80u) * hdr.channels];
    EXPECT_GT(ball[0], 100.0f);
    EXPECT_GT(ball[0], 3.0f * ball[1]);
    EXPECT_FALSE(r->timings().empty());
    EXPECT_NE(r->planJson().find("\"passes\""), std::string::npos);
    // A parameter and a pass toggle between frames: without the sky pass the sky is black.
    const float sky = display.pixels[(5u * 160u + 80u) * display.channels + 2];
    EXPECT_GT(sky, 0.1f);
    r->setPassEnabled("sky", false);
    r->setParameter("bloom_mix_stops", -8.0);
    r->render(1);
    rgraph::Image after = r->readDisplay();
    EXPECT_LT(after.pixels[(5u * 160u + 80u) * after.channels + 2], 0.02f);
}

TEST(Library, ASceneInCodeRendersAsTheSameSceneFromItsLuaFile) {
    const fs::path dir =
        fs::temp_directory_path() / ("rgraph_library_" + std::to_string(::getpid()));
    fs::create_directories(dir);
    std::ofstream(dir / "scene.lua") << sceneLua();
    writeChecker(dir / "checker.png");
    enum class From { Code, File, Source };
    auto render = [&](From from) {
        auto r = rgraph::Renderer::create(options());
        r->setSize(160, 90);
        if (from == From::Code)
            r->setScene(sceneInCode(dir));
        else if (from == From::File)
            r->loadScene((dir / "scene.lua").string());
        else
            r->loadSceneSource("library_scene", sceneLua(), dir.string());
        r->loadPipeline(kRoot + "/scripts/pipelines/deferred.lua");
        r->setParameter("exposure_mode", std::string("manual"));
        r->render(1);
        return r->readHdr();
    };
    rgraph::Image a = render(From::Code), b = render(From::File), c = render(From::Source);
    fs::remove_all(dir);
    EXPECT_EQ(c.pixels, b.pixels);  // the Lua file and the same Lua as source
    ASSERT_EQ(a.pixels.size(), b.pixels.size());
    double worst = 0, sum = 0;
    for (size_t i = 0; i < a.pixels.size(); ++i) {
        const double d =
            std::fabs(a.pixels[i] - b.pixels[i]) / std::max(std::fabs(b.pixels[i]), 1e-3f);
        worst = std::max(worst, d);
        sum += d;
    }
    const double mean = sum / static_cast<double>(a.pixels.size());
    std::printf("in code vs Lua file: mean relative difference %.3g, worst %.3g\n", mean, worst);
    EXPECT_LT(mean, 1e-5);  // the golden suite's HDR bound
    EXPECT_LT(worst, 0.02);
}

TEST(Library, TheNextRendererRestoresWhatOncePassesWrote) {
    // Options::onceCache (on by default): the first renderer saves what the once-per-build passes
    // wrote (environment filtering, the probe capture, the DFG table) in cacheDir/once, the next
    // one restores it and renders the same image as a renderer that records them.
    const fs::path cache =
        fs::temp_directory_path() / ("rgraph_library_once_" + std::to_string(::getpid()));
    fs::remove_all(cache);
    auto render = [&](bool onceCache) {
        rgraph::Options o = options();
        o.cacheDir = cache.string();
        o.onceCache = onceCache;
        auto r = rgraph::Renderer::create(o);
        r->setSize(160, 90);
        r->loadPipeline(kRoot + "/scripts/pipelines/deferred.lua");
        r->setParameter("exposure_mode", std::string("manual"));
        r->render(1);
        return r->readHdr();
    };
    auto entries = [&] {
        size_t n = 0;
        std::error_code ec;
        for (const auto& e : fs::directory_iterator(cache / "once", ec))
            n += e.path().extension() == ".bin";
        return n;
    };
    const rgraph::Image recorded = render(false);
    EXPECT_EQ(entries(), 0u);
    const rgraph::Image saved = render(true);
    EXPECT_EQ(entries(), 1u);
    const rgraph::Image restored = render(true);
    EXPECT_EQ(entries(), 1u);
    fs::remove_all(cache);
    ASSERT_EQ(recorded.pixels.size(), restored.pixels.size());
    ASSERT_EQ(recorded.pixels.size(), saved.pixels.size());
    size_t differ = 0;
    for (size_t i = 0; i < recorded.pixels.size(); ++i)
        differ += recorded.pixels[i] != restored.pixels[i] || recorded.pixels[i] != saved.pixels[i];
    EXPECT_EQ(differ, 0u);
}

TEST(Library, ErrorsAreExceptionsWithFileAndLine) {
    auto r = rgraph::Renderer::create(options());
    try {
        r->loadPipelineSource(
            "broken", "local rg = require \"rg\"\nrg.resource \"x\" { format = \"rgba9\" }\n");
        FAIL() << "a broken script loaded";
    } catch (const rgraph::Error& e) {
        EXPECT_NE(std::string(e.what()).find("broken.lua:2:"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("rgba9"), std::string::npos) << e.what();
    }
    r->loadPipeline(kRoot + "/scripts/pipelines/deferred.lua");
    EXPECT_THROW(r->setParameter("no_such_param", 1.0), rgraph::Error);
    EXPECT_THROW(r->setParameter("ec", 100.0), rgraph::Error);  // out of range
    EXPECT_THROW(r->setPassEnabled("no_such_pass", false), rgraph::Error);
    rgraph::Scene bad = sceneInCode();
    bad.meshes[0].indices.push_back(100000);
    EXPECT_THROW(r->setScene(bad), rgraph::Error);
    rgraph::Scene lumens = sceneInCode();
    lumens.lights[0].unit = "lm";  // a sun is given in lux (seed 000 tbl:8)
    try {
        r->setScene(lumens);
        FAIL() << "a sun in lumens was accepted";
    } catch (const rgraph::Error& e) {
        EXPECT_NE(std::string(e.what()).find("unit 'lm'"), std::string::npos) << e.what();
    }
}

// A change that cannot be served — a resource the pipeline does not have kept for reading, a
// switch that leaves a kept pass without its input, a size out of range — throws and changes
// nothing: its frames are those of a renderer that never saw the failures, and it takes the next
// valid change.
TEST(Library, AFailedChangeLeavesTheRendererAsItWas) {
    auto reference = rgraph::Renderer::create(options());
    reference->setSize(64, 36);
    reference->loadPipeline(kRoot + "/scripts/pipelines/deferred.lua");
    reference->render(4);
    const rgraph::Image expected = reference->readDisplay();
    reference.reset();
    auto r = rgraph::Renderer::create(options());
    r->setSize(64, 36);
    r->loadPipeline(kRoot + "/scripts/pipelines/deferred.lua");
    r->render(2);
    try {
        r->keep("nosuch.thing");
        FAIL() << "an unknown resource was kept";
    } catch (const rgraph::Error& e) {
        EXPECT_NE(std::string(e.what()).find("'nosuch.thing'"), std::string::npos) << e.what();
    }
    EXPECT_THROW(r->keep("../../etc/passwd"), rgraph::Error);
    try {
        r->setPassEnabled("tonemap", false);
        FAIL() << "tonemap switched off although the display it writes is exported";
    } catch (const rgraph::Error& e) {
        EXPECT_NE(
            std::string(e.what()).find("'display' is exported (an output or a capture) but not "
                                       "written: its writers 'tonemap' and 'fxaa' are disabled"),
            std::string::npos)
            << e.what();
    }
    EXPECT_THROW(r->setSize(0, 36), rgraph::Error);
    r->render(2);  // the scene the renderer had (the failed keep's reload gave it back), unchanged
    const rgraph::Image after = r->readDisplay();
    ASSERT_EQ(expected.pixels.size(), after.pixels.size());
    EXPECT_EQ(expected.pixels, after.pixels);
    // The next valid change is taken: a kept resource reads back, a switch applies.
    r->keep("GB1");
    r->render(1);
    EXPECT_EQ(r->readResource("GB1").width, 64u);
    r->setPassEnabled("sky", false);
    r->render(1);
    EXPECT_NE(r->readDisplay().pixels, after.pixels);
}

// The host's own images through the graph, in the host's command buffer: the host clears image A,
// rgraph copies it into its imported texture `src`, a copy pass writes `output`, rgraph copies
// that into the host's image B; the host submits, reads B back and finds A's colour.
TEST(Library, HostImagesInAndOutThroughTheHostsCommandBuffer) {
    HostVulkan host;
    ASSERT_TRUE(host.device);
    constexpr uint32_t w = 64, h = 32;
    VkPhysicalDeviceMemoryProperties mem;
    vkGetPhysicalDeviceMemoryProperties(host.physical, &mem);
    auto memoryType = [&](uint32_t bits, VkMemoryPropertyFlags want) {
        for (uint32_t i = 0; i < mem.memoryTypeCount; ++i)
            if ((bits & (1u << i)) && (mem.memoryTypes[i].propertyFlags & want) == want) return i;
        return 0u;
    };
    std::vector<VkDeviceMemory> memories;
    auto image = [&]() {
        VkImageCreateInfo ii{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
        ii.imageType = VK_IMAGE_TYPE_2D;
        ii.format = VK_FORMAT_R8G8B8A8_UNORM;
        ii.extent = {w, h, 1};
        ii.mipLevels = ii.arrayLayers = 1;
        ii.samples = VK_SAMPLE_COUNT_1_BIT;
        ii.usage = VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
        VkImage img = VK_NULL_HANDLE;
        vkCreateImage(host.device, &ii, nullptr, &img);
        VkMemoryRequirements req;
        vkGetImageMemoryRequirements(host.device, img, &req);
        VkMemoryAllocateInfo ai{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
        ai.allocationSize = req.size;
        ai.memoryTypeIndex = memoryType(req.memoryTypeBits, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
        VkDeviceMemory m = VK_NULL_HANDLE;
        vkAllocateMemory(host.device, &ai, nullptr, &m);
        vkBindImageMemory(host.device, img, m, 0);
        memories.push_back(m);
        return img;
    };
    VkImage a = image(), b = image();
    VkBufferCreateInfo bi{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
    bi.size = w * h * 4;
    bi.usage = VK_BUFFER_USAGE_TRANSFER_DST_BIT;
    VkBuffer readback = VK_NULL_HANDLE;
    vkCreateBuffer(host.device, &bi, nullptr, &readback);
    VkMemoryRequirements req;
    vkGetBufferMemoryRequirements(host.device, readback, &req);
    VkMemoryAllocateInfo ai{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
    ai.allocationSize = req.size;
    ai.memoryTypeIndex = memoryType(req.memoryTypeBits, VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT |
                                                            VK_MEMORY_PROPERTY_HOST_COHERENT_BIT);
    VkDeviceMemory readbackMemory = VK_NULL_HANDLE;
    vkAllocateMemory(host.device, &ai, nullptr, &readbackMemory);
    vkBindBufferMemory(host.device, readback, readbackMemory, 0);
    {
        auto r = rgraph::Renderer::create(
            rgraph::HostDevice{host.instance, host.physical, host.device, host.family, host.queue},
            options());
        r->setSize(w, h);
        r->importImage(
            "src",
            {a, w, h,
             VK_IMAGE_LAYOUT_GENERAL});  // before the load: the import is the texture's contents
        r->exportImage("output", {b, w, h, VK_IMAGE_LAYOUT_GENERAL});
        r->loadPipelineSource("host_images", R"(local rg = require "rg"
rg.resource "src" { format = "rgba8", import = true }
rg.resource "output" { format = "rgba8" }
rg.pass "copy" { kind = "copy", reads = { "src" }, writes = { "output" } }
rg.output "output"
)");
        VkCommandPoolCreateInfo pi{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
        pi.queueFamilyIndex = host.family;
        VkCommandPool pool = VK_NULL_HANDLE;
        vkCreateCommandPool(host.device, &pi, nullptr, &pool);
        VkCommandBufferAllocateInfo ci{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
        ci.commandPool = pool;
        ci.commandBufferCount = 1;
        VkCommandBuffer cmd = VK_NULL_HANDLE;
        vkAllocateCommandBuffers(host.device, &ci, &cmd);
        VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
        vkBeginCommandBuffer(cmd, &begin);
        VkImageMemoryBarrier2 toGeneral{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2};
        toGeneral.srcStageMask = toGeneral.dstStageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
        toGeneral.dstAccessMask = VK_ACCESS_2_MEMORY_WRITE_BIT | VK_ACCESS_2_MEMORY_READ_BIT;
        toGeneral.oldLayout = VK_IMAGE_LAYOUT_UNDEFINED;
        toGeneral.newLayout = VK_IMAGE_LAYOUT_GENERAL;
        toGeneral.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
        VkImageMemoryBarrier2 barriers[2] = {toGeneral, toGeneral};
        barriers[0].image = a;
        barriers[1].image = b;
        VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
        dep.imageMemoryBarrierCount = 2;
        dep.pImageMemoryBarriers = barriers;
        vkCmdPipelineBarrier2(cmd, &dep);
        const VkClearColorValue colour{{0.25f, 0.5f, 0.75f, 1.0f}};
        const VkImageSubresourceRange range{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
        vkCmdClearColorImage(cmd, a, VK_IMAGE_LAYOUT_GENERAL, &colour, 1, &range);
        r->record(cmd);  // rgraph's frame, into the host's command buffer
        VkBufferImageCopy copy{};
        copy.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
        copy.imageExtent = {w, h, 1};
        VkMemoryBarrier2 done{VK_STRUCTURE_TYPE_MEMORY_BARRIER_2};
        done.srcStageMask = done.dstStageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
        done.srcAccessMask = VK_ACCESS_2_MEMORY_WRITE_BIT;
        done.dstAccessMask = VK_ACCESS_2_MEMORY_READ_BIT;
        VkDependencyInfo dep2{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
        dep2.memoryBarrierCount = 1;
        dep2.pMemoryBarriers = &done;
        vkCmdPipelineBarrier2(cmd, &dep2);
        vkCmdCopyImageToBuffer(cmd, b, VK_IMAGE_LAYOUT_GENERAL, readback, 1, &copy);
        vkEndCommandBuffer(cmd);
        VkSubmitInfo submit{VK_STRUCTURE_TYPE_SUBMIT_INFO};
        submit.commandBufferCount = 1;
        submit.pCommandBuffers = &cmd;
        ASSERT_EQ(vkQueueSubmit(host.queue, 1, &submit, VK_NULL_HANDLE), VK_SUCCESS);
        vkQueueWaitIdle(host.queue);
        void* data = nullptr;
        vkMapMemory(host.device, readbackMemory, 0, VK_WHOLE_SIZE, 0, &data);
        const uint8_t* px = static_cast<const uint8_t*>(data) + (h / 2 * w + w / 2) * 4;
        EXPECT_EQ(px[0], 64);  // 0.25 · 255, rounded
        EXPECT_EQ(px[1], 128);
        EXPECT_EQ(px[2], 191);
        vkUnmapMemory(host.device, readbackMemory);
        vkDestroyCommandPool(host.device, pool, nullptr);
    }
    vkDestroyBuffer(host.device, readback, nullptr);
    vkFreeMemory(host.device, readbackMemory, nullptr);
    vkDestroyImage(host.device, a, nullptr);
    vkDestroyImage(host.device, b, nullptr);
    for (VkDeviceMemory m : memories) vkFreeMemory(host.device, m, nullptr);
}

}  // namespace

// A dynamic mesh moves where the host puts it, and the pipeline writes its motion; a mesh declared
// static stays, and moving it is an error naming it.
TEST(Library, ADynamicMeshMovesAndWritesItsMotion) {
    rgraph::Scene s;
    s.environment = "none";
    rgraph::Material glow{"glow"};
    glow.baseColor[0] = glow.baseColor[1] = glow.baseColor[2] = 0.0f;
    glow.emissive[0] = glow.emissive[1] = glow.emissive[2] = 50.0f;
    s.materials.push_back(glow);
    rgraph::Mesh mover = rgraph::makeBox(0.6f, 0.6f, 0.6f);
    mover.name = "mover";
    mover.material = "glow";
    mover.dynamic = true;
    rgraph::Mesh post = rgraph::makeBox(0.3f, 0.3f, 0.3f);
    post.name = "post";
    post.material = "glow";
    post.transform[12] = 1.2f;
    s.meshes = {mover, post};
    s.camera.position[0] = 0.0f, s.camera.position[1] = 0.0f, s.camera.position[2] = 5.0f;
    s.camera.target[1] = 0.0f;
    auto r = rgraph::Renderer::create(options());
    r->setSize(64, 64);
    r->setScene(s);
    r->keep("motion");
    r->loadPipeline(kRoot + "/scripts/pipelines/deferred.lua");
    r->render(2);
    // 0.1 m to the right between two frames, seen 4.7 m away (the box's front face) by a 45°
    // field: 0.1 / (2 · 4.7 · tan 22.5°) of the image's width.
    float moved[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0.1f, 0, 0, 1};
    r->setTransform("mover", moved);
    r->render(1);
    const rgraph::Image m = r->readResource("motion");
    ASSERT_EQ(m.width, 64u);
    const float want = 0.1f / (2.0f * 4.7f * std::tan(0.3926991f));
    const float got = m.pixels[(32 * 64 + 33) * m.channels];
    std::printf("library: the dynamic mesh's motion %.5f uv, expected %.5f\n", got, want);
    EXPECT_NEAR(got, want, 0.01f * want);
    // The static post: drawn (it glows in the display), and without motion.
    EXPECT_GT(r->readDisplay().pixels[(32 * 64 + 50) * 4], 0.5f);
    EXPECT_EQ(m.pixels[(32 * 64 + 50) * m.channels], 0.0f);
    // Standing still again: no motion.
    r->render(1);
    EXPECT_EQ(r->readResource("motion").pixels[(32 * 64 + 33) * m.channels], 0.0f);
    // A reload (another kept resource) places it where the host put it: moved on by 0.1 m more,
    // it moves 0.1 m (0.2 m had the reload put it back at its Mesh::transform).
    r->keep("GB1");
    r->render(1);
    moved[12] = 0.2f;
    r->setTransform("mover", moved);
    r->render(1);
    const float again = r->readResource("motion").pixels[(32 * 64 + 33) * m.channels];
    EXPECT_NEAR(again, want, 0.01f * want);
    try {
        r->setTransform("post", moved);
        FAIL() << "a static mesh was moved";
    } catch (const rgraph::Error& e) {
        EXPECT_NE(std::string(e.what()).find("node 'post' was declared static"), std::string::npos)
            << e.what();
    }
    EXPECT_THROW(r->setTransform("nosuch", moved), rgraph::Error);
}
