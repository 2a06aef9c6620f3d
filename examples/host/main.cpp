// A host that owns its Vulkan device and renders through rgraph's default pipeline: it creates
// the instance and device (with the features rgraph needs), builds a scene in code, renders a
// frame, changes a pass parameter, renders again and writes both frames.
//   rgraph_host OUT_DIR
#include <cstdio>
#include <string>
#include <vector>

#include <rgraph/rgraph.h>

namespace {

void vk(VkResult r, const char* what) {
    if (r != VK_SUCCESS)
        throw rgraph::Error(std::string(what) + " failed: VkResult " + std::to_string(r));
}

// The host's own device: Vulkan 1.3 with what rgraph::HostDevice lists.
struct Device {
    VkInstance instance = VK_NULL_HANDLE;
    VkPhysicalDevice physical = VK_NULL_HANDLE;
    VkDevice device = VK_NULL_HANDLE;
    uint32_t family = 0;
    VkQueue queue = VK_NULL_HANDLE;

    Device() {
        VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
        app.pApplicationName = "rgraph_host";
        app.apiVersion = VK_API_VERSION_1_3;
        VkInstanceCreateInfo ii{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
        ii.pApplicationInfo = &app;
        vk(vkCreateInstance(&ii, nullptr, &instance), "vkCreateInstance");
        uint32_t n = 0;
        vkEnumeratePhysicalDevices(instance, &n, nullptr);
        if (n == 0) throw rgraph::Error("no Vulkan device");
        std::vector<VkPhysicalDevice> devices(n);
        vkEnumeratePhysicalDevices(instance, &n, devices.data());
        physical = devices[0];
        uint32_t nf = 0;
        vkGetPhysicalDeviceQueueFamilyProperties(physical, &nf, nullptr);
        std::vector<VkQueueFamilyProperties> families(nf);
        vkGetPhysicalDeviceQueueFamilyProperties(physical, &nf, families.data());
        for (family = 0; family < nf; ++family)
            if ((families[family].queueFlags & VK_QUEUE_GRAPHICS_BIT) &&
                (families[family].queueFlags & VK_QUEUE_COMPUTE_BIT))
                break;
        float priority = 1.0f;
        VkDeviceQueueCreateInfo qi{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
        qi.queueFamilyIndex = family;
        qi.queueCount = 1;
        qi.pQueuePriorities = &priority;
        VkPhysicalDeviceVulkan13Features f13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
        f13.dynamicRendering = f13.synchronization2 = f13.maintenance4 = VK_TRUE;
        VkPhysicalDeviceVulkan12Features f12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES};
        f12.pNext = &f13;
        f12.hostQueryReset = VK_TRUE;
        VkPhysicalDeviceFeatures2 features{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
        features.pNext = &f12;
        VkPhysicalDeviceFeatures2 supported{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
        vkGetPhysicalDeviceFeatures2(physical, &supported);
        features.features = supported.features;  // whatever else the device has
        VkDeviceCreateInfo di{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
        di.pNext = &features;
        di.queueCreateInfoCount = 1;
        di.pQueueCreateInfos = &qi;
        vk(vkCreateDevice(physical, &di, nullptr, &device), "vkCreateDevice");
        vkGetDeviceQueue(device, family, 0, &queue);
    }
    ~Device() {
        if (device) vkDestroyDevice(device, nullptr);
        if (instance) vkDestroyInstance(instance, nullptr);
    }
};

// The scene, in code: a floor, three spheres of the standard material, a sun, a warm lamp and a
// decal. (Material::baseColorMap and the other maps take texture files; Light::ies a profile;
// Renderer::loadSceneSource a whole Lua scene.)
rgraph::Scene makeScene() {
    rgraph::Scene s;
    rgraph::Material floor{"floor"};
    floor.smoothness = 0.3f;
    s.materials.push_back(floor);
    const float colours[3][3] = {{0.8f, 0.1f, 0.1f}, {0.9f, 0.9f, 0.9f}, {0.1f, 0.3f, 0.8f}};
    for (int i = 0; i < 3; ++i) {
        rgraph::Material m{"ball" + std::to_string(i)};
        for (int c = 0; c < 3; ++c) m.baseColor[c] = colours[i][c];
        m.smoothness = 0.4f + 0.25f * static_cast<float>(i);
        m.metalMask = i == 1 ? 1.0f : 0.0f;
        s.materials.push_back(m);
        rgraph::Mesh ball = rgraph::makeSphere(0.5f);
        ball.name = "ball" + std::to_string(i);
        ball.material = m.name;
        ball.transform[12] = 1.2f * static_cast<float>(i - 1);  // translation x
        ball.transform[13] = 0.5f;
        s.meshes.push_back(ball);
    }
    rgraph::Mesh plane = rgraph::makePlane(8.0f, 8.0f);
    plane.material = "floor";
    s.meshes.push_back(plane);
    rgraph::Light sun;
    sun.type = rgraph::Light::Type::Sun;
    sun.intensity = 20000.0f;
    sun.unit = "lux";
    sun.direction[0] = -0.4f, sun.direction[1] = -0.8f, sun.direction[2] = -0.45f;
    s.lights.push_back(sun);
    rgraph::Light lamp;
    lamp.position[1] = 1.5f, lamp.position[2] = 1.0f;
    lamp.intensity = 1600.0f;    // lumens
    lamp.temperature = 2700.0f;  // kelvin: a warm incandescent
    s.lights.push_back(lamp);
    // A decal on the floor in front of the balls: blue, glossy (what it leaves negative stays).
    rgraph::Decal puddle{"puddle"};
    puddle.transform[0] = 1.6f, puddle.transform[5] = 0.2f, puddle.transform[10] = 0.8f;
    puddle.transform[14] = 1.0f;
    puddle.baseColor[0] = 0.05f, puddle.baseColor[1] = 0.1f, puddle.baseColor[2] = 0.4f;
    puddle.smoothness = 0.95f;
    puddle.opacity = 0.7f;
    s.decals.push_back(puddle);
    s.camera.position[1] = 1.2f, s.camera.position[2] = 3.6f;
    s.camera.target[1] = 0.45f;
    return s;
}

}  // namespace

int main(int argc, char** argv) {
    const std::string out = argc > 1 ? argv[1] : ".";
    try {
        Device host;
        auto renderer = rgraph::Renderer::create(
            rgraph::HostDevice{host.instance, host.physical, host.device, host.family, host.queue});
        renderer->setSize(640, 360);
        renderer->setScene(makeScene());
        renderer->loadPipeline(rgraph::Renderer::dataDir() + "/scripts/pipelines/deferred.lua");
        renderer->render(2);
        rgraph::writePng(out + "/host_frame0.png", renderer->readDisplay());
        // Between frames: manual exposure one stop up (exposure compensation +1), and no sky.
        renderer->setParameter("exposure_mode", std::string("manual"));
        renderer->setParameter("ec", 1.0);
        renderer->setPassEnabled("sky", false);
        renderer->render(1);
        rgraph::writePng(out + "/host_frame1.png", renderer->readDisplay());
        rgraph::writeExr(out + "/host_frame1.exr", renderer->readHdr());
        double total = 0;
        for (const auto& t : renderer->timings()) total += t.gpuMs;
        std::printf(
            "rgraph_host: wrote %s/host_frame0.png, host_frame1.png and host_frame1.exr (%zu "
            "passes, %.1f ms)\n",
            out.c_str(), renderer->timings().size(), total);
        return 0;
    } catch (const rgraph::Error& e) {
        std::fprintf(stderr, "rgraph_host: %s\n", e.what());
        return 1;
    }
}
