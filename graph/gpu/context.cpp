#include "context.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <mutex>

#include <unistd.h>

#include "core/check.h"
#include "core/temp_path.h"

namespace rg::gpu {

namespace {

constexpr const char* kValidationLayer = "VK_LAYER_KHRONOS_validation";

bool envFlag(const char* name) {
    const char* v = std::getenv(name);
    return v && *v && std::strcmp(v, "0") != 0;
}

const char* deviceTypeName(VkPhysicalDeviceType t) {
    switch (t) {
        case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU:
            return "discrete";
        case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU:
            return "integrated";
        case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU:
            return "virtual";
        case VK_PHYSICAL_DEVICE_TYPE_CPU:
            return "cpu";
        default:
            return "other";
    }
}

// Lower is better: discrete GPU, integrated, virtual, CPU.
int typeRank(VkPhysicalDeviceType t) {
    switch (t) {
        case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU:
            return 0;
        case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU:
            return 1;
        case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU:
            return 2;
        case VK_PHYSICAL_DEVICE_TYPE_CPU:
            return 3;
        default:
            return 4;
    }
}

bool hasLayer(const char* name) {
    uint32_t n = 0;
    vkEnumerateInstanceLayerProperties(&n, nullptr);
    std::vector<VkLayerProperties> layers(n);
    vkEnumerateInstanceLayerProperties(&n, layers.data());
    return std::any_of(layers.begin(), layers.end(), [&](const VkLayerProperties& l) {
        return std::strcmp(l.layerName, name) == 0;
    });
}

bool hasInstanceExtension(const char* name) {
    uint32_t n = 0;
    vkEnumerateInstanceExtensionProperties(nullptr, &n, nullptr);
    std::vector<VkExtensionProperties> exts(n);
    vkEnumerateInstanceExtensionProperties(nullptr, &n, exts.data());
    return std::any_of(exts.begin(), exts.end(), [&](const VkExtensionProperties& e) {
        return std::strcmp(e.extensionName, name) == 0;
    });
}

Result<VkInstance> createInstance(bool validation, bool debugUtils) {
    VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
    app.pApplicationName = "rgraph";
    app.pEngineName = "rgraph";
    app.apiVersion = VK_API_VERSION_1_3;
    std::vector<const char*> layers, exts;
    if (validation) layers.push_back(kValidationLayer);
    if (debugUtils) exts.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
    VkInstanceCreateInfo info{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
    info.pApplicationInfo = &app;
    info.enabledLayerCount = static_cast<uint32_t>(layers.size());
    info.ppEnabledLayerNames = layers.data();
    info.enabledExtensionCount = static_cast<uint32_t>(exts.size());
    info.ppEnabledExtensionNames = exts.data();
    VkInstance instance = VK_NULL_HANDLE;
    RG_VK_TRY(vkCreateInstance(&info, nullptr, &instance));
    return instance;
}

// Fills `info` and says whether the device can run rgraph.
DeviceInfo describe(VkPhysicalDevice pd, uint32_t index) {
    VkPhysicalDeviceDriverProperties driver{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DRIVER_PROPERTIES};
    VkPhysicalDeviceProperties2 props{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2};
    props.pNext = &driver;
    vkGetPhysicalDeviceProperties2(pd, &props);
    DeviceInfo d;
    d.index = index;
    d.name = props.properties.deviceName;
    d.type = deviceTypeName(props.properties.deviceType);
    d.driver = std::string(driver.driverName) + " " + driver.driverInfo;
    d.apiVersion = props.properties.apiVersion;
    if (props.properties.apiVersion < VK_API_VERSION_1_3) {
        d.whyNot = "Vulkan " + std::to_string(VK_API_VERSION_MAJOR(d.apiVersion)) + "." +
                   std::to_string(VK_API_VERSION_MINOR(d.apiVersion)) + " (1.3 needed)";
        return d;
    }
    VkPhysicalDeviceVulkan13Features f13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
    VkPhysicalDeviceFeatures2 f{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
    f.pNext = &f13;
    vkGetPhysicalDeviceFeatures2(pd, &f);
    if (!f13.dynamicRendering)
        d.whyNot = "no dynamicRendering";
    else if (!f13.synchronization2)
        d.whyNot = "no synchronization2";
    else if (!f13.maintenance4)
        d.whyNot = "no maintenance4";
    else if (!f.features.imageCubeArray)
        d.whyNot = "no imageCubeArray (the local light probes' cube arrays)";
    uint32_t n = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(pd, &n, nullptr);
    std::vector<VkQueueFamilyProperties> families(n);
    vkGetPhysicalDeviceQueueFamilyProperties(pd, &n, families.data());
    bool queue =
        std::any_of(families.begin(), families.end(), [](const VkQueueFamilyProperties& q) {
            return (q.queueFlags & VK_QUEUE_GRAPHICS_BIT) &&
                   (q.queueFlags & VK_QUEUE_COMPUTE_BIT) && q.timestampValidBits > 0;
        });
    if (d.whyNot.empty() && !queue) d.whyNot = "no graphics+compute queue with timestamps";
    d.usable = d.whyNot.empty();
    return d;
}

}  // namespace

Result<std::vector<DeviceInfo>> Context::listDevices() {
    auto instance = createInstance(false, false);
    if (!instance) return std::unexpected(instance.error());
    uint32_t n = 0;
    vkEnumeratePhysicalDevices(*instance, &n, nullptr);
    std::vector<VkPhysicalDevice> pds(n);
    vkEnumeratePhysicalDevices(*instance, &n, pds.data());
    std::vector<DeviceInfo> out;
    for (uint32_t i = 0; i < n; ++i) out.push_back(describe(pds[i], i));
    vkDestroyInstance(*instance, nullptr);
    return out;
}

// The host's device (ContextOptions::external): checked as far as Vulkan lets us, then adopted.
Result<void> Context::adopt(const ExternalDevice& e) {
    if (!e.instance || !e.physicalDevice || !e.device || !e.queue)
        return fail(ErrorCode::InvalidInput,
                    "host device: instance, physical device, device and queue must all be given");
    m_ownsDevice = false;
    m_instance = e.instance;
    m_physical = e.physicalDevice;
    m_device = e.device;
    m_queue = e.queue;
    m_queueFamily = e.queueFamily;
    m_info = describe(e.physicalDevice, 0);
    if (!m_info.usable)
        return fail(ErrorCode::Device,
                    "host device '" + m_info.name + "' cannot be used: " + m_info.whyNot);
    uint32_t nf = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(m_physical, &nf, nullptr);
    std::vector<VkQueueFamilyProperties> families(nf);
    vkGetPhysicalDeviceQueueFamilyProperties(m_physical, &nf, families.data());
    if (e.queueFamily >= nf || !(families[e.queueFamily].queueFlags & VK_QUEUE_GRAPHICS_BIT) ||
        !(families[e.queueFamily].queueFlags & VK_QUEUE_COMPUTE_BIT) ||
        !families[e.queueFamily].timestampValidBits)
        return fail(ErrorCode::InvalidInput, "host device: queue family " +
                                                 std::to_string(e.queueFamily) +
                                                 " must support graphics, compute and timestamps");
    // Debug labels and names when the host's instance has the extension (null otherwise).
    m_beginLabel = reinterpret_cast<PFN_vkCmdBeginDebugUtilsLabelEXT>(
        vkGetInstanceProcAddr(m_instance, "vkCmdBeginDebugUtilsLabelEXT"));
    m_endLabel = reinterpret_cast<PFN_vkCmdEndDebugUtilsLabelEXT>(
        vkGetInstanceProcAddr(m_instance, "vkCmdEndDebugUtilsLabelEXT"));
    m_setName = reinterpret_cast<PFN_vkSetDebugUtilsObjectNameEXT>(
        vkGetInstanceProcAddr(m_instance, "vkSetDebugUtilsObjectNameEXT"));
    m_debugUtils = m_beginLabel && m_endLabel && m_setName;
    return {};
}

Result<std::unique_ptr<Context>> Context::create(const ContextOptions& options) {
    std::unique_ptr<Context> ctx(new Context());
    ctx->m_framesInFlight = std::max(1u, options.framesInFlight);
    ctx->m_deletions.resize(ctx->m_framesInFlight);
    if (options.external) {
        if (auto r = ctx->adopt(*options.external); !r) return std::unexpected(r.error());
        vkGetPhysicalDeviceProperties(ctx->m_physical, &ctx->m_properties);
        if (auto r = ctx->createDeviceObjects(options); !r) return std::unexpected(r.error());
        return ctx;
    }
    bool wantValidation = options.validation.value_or(envFlag("RG_VALIDATION"));
    if (wantValidation && !hasLayer(kValidationLayer))
        return fail(ErrorCode::Device,
                    "validation requested (RG_VALIDATION=1) but VK_LAYER_KHRONOS_validation is not "
                    "installed (Debian package vulkan-validationlayers)");
    ctx->m_validation = wantValidation;
    ctx->m_debugUtils = hasInstanceExtension(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);

    auto instance = createInstance(ctx->m_validation, ctx->m_debugUtils);
    if (!instance) return std::unexpected(instance.error());
    ctx->m_instance = *instance;

    if (ctx->m_debugUtils) {
        auto createMessenger = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
            vkGetInstanceProcAddr(ctx->m_instance, "vkCreateDebugUtilsMessengerEXT"));
        ctx->m_beginLabel = reinterpret_cast<PFN_vkCmdBeginDebugUtilsLabelEXT>(
            vkGetInstanceProcAddr(ctx->m_instance, "vkCmdBeginDebugUtilsLabelEXT"));
        ctx->m_endLabel = reinterpret_cast<PFN_vkCmdEndDebugUtilsLabelEXT>(
            vkGetInstanceProcAddr(ctx->m_instance, "vkCmdEndDebugUtilsLabelEXT"));
        ctx->m_setName = reinterpret_cast<PFN_vkSetDebugUtilsObjectNameEXT>(
            vkGetInstanceProcAddr(ctx->m_instance, "vkSetDebugUtilsObjectNameEXT"));
        if (ctx->m_validation && createMessenger) {
            VkDebugUtilsMessengerCreateInfoEXT info{
                VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
            info.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT |
                                   VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
            info.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT |
                               VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                               VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
            info.pfnUserCallback = &Context::debugCallback;
            info.pUserData = ctx.get();
            RG_VK_TRY(createMessenger(ctx->m_instance, &info, nullptr, &ctx->m_messenger));
        }
    }

    // Choose the device.
    uint32_t n = 0;
    vkEnumeratePhysicalDevices(ctx->m_instance, &n, nullptr);
    std::vector<VkPhysicalDevice> pds(n);
    vkEnumeratePhysicalDevices(ctx->m_instance, &n, pds.data());
    std::vector<DeviceInfo> infos;
    for (uint32_t i = 0; i < n; ++i) infos.push_back(describe(pds[i], i));
    int chosen = -1;
    if (options.deviceIndex) {
        uint32_t want = *options.deviceIndex;
        if (want >= n)
            return fail(ErrorCode::InvalidInput, "--device " + std::to_string(want) + ": only " +
                                                     std::to_string(n) +
                                                     " Vulkan device(s) (see 'rgraph devices')");
        if (!infos[want].usable)
            return fail(ErrorCode::Device, "--device " + std::to_string(want) + " (" +
                                               infos[want].name +
                                               ") cannot be used: " + infos[want].whyNot);
        chosen = static_cast<int>(want);
    } else {
        int bestRank = 99;
        for (uint32_t i = 0; i < n; ++i) {
            if (!infos[i].usable) continue;
            VkPhysicalDeviceProperties p;
            vkGetPhysicalDeviceProperties(pds[i], &p);
            if (typeRank(p.deviceType) < bestRank) {
                bestRank = typeRank(p.deviceType);
                chosen = static_cast<int>(i);
            }
        }
    }
    if (chosen < 0) {
        std::vector<std::string> reasons;
        for (const auto& d : infos) reasons.push_back(d.name + ": " + d.whyNot);
        if (reasons.empty())
            reasons.push_back("no devices at all: install mesa-vulkan-drivers for lavapipe");
        return fail(ErrorCode::Device, "no usable Vulkan device", reasons);
    }
    ctx->m_physical = pds[static_cast<size_t>(chosen)];
    ctx->m_info = infos[static_cast<size_t>(chosen)];
    vkGetPhysicalDeviceProperties(ctx->m_physical, &ctx->m_properties);

    uint32_t nf = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(ctx->m_physical, &nf, nullptr);
    std::vector<VkQueueFamilyProperties> families(nf);
    vkGetPhysicalDeviceQueueFamilyProperties(ctx->m_physical, &nf, families.data());
    for (uint32_t i = 0; i < nf; ++i) {
        if ((families[i].queueFlags & VK_QUEUE_GRAPHICS_BIT) &&
            (families[i].queueFlags & VK_QUEUE_COMPUTE_BIT) && families[i].timestampValidBits) {
            ctx->m_queueFamily = i;
            break;
        }
    }

    float priority = 1.0f;
    VkDeviceQueueCreateInfo queueInfo{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
    queueInfo.queueFamilyIndex = ctx->m_queueFamily;
    queueInfo.queueCount = 1;
    queueInfo.pQueuePriorities = &priority;

    VkPhysicalDeviceVulkan12Features supported12{
        VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES};
    VkPhysicalDeviceFeatures2 supported{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
    supported.pNext = &supported12;
    vkGetPhysicalDeviceFeatures2(ctx->m_physical, &supported);
    VkPhysicalDeviceVulkan13Features f13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
    f13.dynamicRendering = VK_TRUE;
    f13.synchronization2 = VK_TRUE;
    // Required by Vulkan 1.3; glslang's SPIR-V 1.6 uses LocalSizeId, which needs it.
    f13.maintenance4 = VK_TRUE;
    VkPhysicalDeviceVulkan12Features f12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES};
    f12.pNext = &f13;
    f12.hostQueryReset = VK_TRUE;
    // The G-buffer's draws culled on the GPU draw as many commands as a count buffer says
    // (vkCmdDrawIndexedIndirectCount, passes/scene_pass.cpp); without it, every command.
    f12.drawIndirectCount = supported12.drawIndirectCount;
    ctx->m_drawIndirectCount = supported12.drawIndirectCount == VK_TRUE;
    VkPhysicalDeviceFeatures2 features{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
    features.pNext = &f12;
    // Only what shaders use and the device has.
    features.features.shaderStorageImageReadWithoutFormat =
        supported.features.shaderStorageImageReadWithoutFormat;
    features.features.shaderStorageImageWriteWithoutFormat =
        supported.features.shaderStorageImageWriteWithoutFormat;
    features.features.samplerAnisotropy = supported.features.samplerAnisotropy;
    features.features.fragmentStoresAndAtomics = supported.features.fragmentStoresAndAtomics;
    features.features.independentBlend = supported.features.independentBlend;
    // Indirect draws that start at an instance (the shadow passes' batches of casters).
    features.features.drawIndirectFirstInstance = supported.features.drawIndirectFirstInstance;
    ctx->m_drawIndirectFirstInstance = supported.features.drawIndirectFirstInstance == VK_TRUE;
    features.features.imageCubeArray =
        VK_TRUE;  // cube textures of several cubes (light probes); required by describe()

    VkDeviceCreateInfo info{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
    info.pNext = &features;
    info.queueCreateInfoCount = 1;
    info.pQueueCreateInfos = &queueInfo;
    RG_VK_TRY(vkCreateDevice(ctx->m_physical, &info, nullptr, &ctx->m_device));
    vkGetDeviceQueue(ctx->m_device, ctx->m_queueFamily, 0, &ctx->m_queue);
    if (auto r = ctx->createDeviceObjects(options); !r) return std::unexpected(r.error());
    return ctx;
}

// What rgraph creates on the device, its own or the host's: the allocator, the one-shot command
// pool and the pipeline cache.
Result<void> Context::createDeviceObjects(const ContextOptions& options) {
    m_allocator = std::make_unique<Allocator>(m_physical, m_device);
    // Quad operations in fragment shaders (Vulkan 1.1's subgroup properties); RG_QUAD_OPS=0 turns
    // their use off (to compare the shaders' two paths).
    VkPhysicalDeviceSubgroupProperties subgroup{
        VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SUBGROUP_PROPERTIES};
    VkPhysicalDeviceProperties2 properties{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2};
    properties.pNext = &subgroup;
    vkGetPhysicalDeviceProperties2(m_physical, &properties);
    const char* quadEnv = std::getenv("RG_QUAD_OPS");
    m_fragmentQuadOps = (subgroup.supportedStages & VK_SHADER_STAGE_FRAGMENT_BIT) &&
                        (subgroup.supportedOperations & VK_SUBGROUP_FEATURE_QUAD_BIT) &&
                        !(quadEnv && std::strcmp(quadEnv, "0") == 0);

    VkCommandPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
    poolInfo.flags = VK_COMMAND_POOL_CREATE_TRANSIENT_BIT;
    poolInfo.queueFamilyIndex = m_queueFamily;
    VkCommandPool pool = VK_NULL_HANDLE;
    RG_VK_TRY(vkCreateCommandPool(m_device, &poolInfo, nullptr, &pool));
    m_oneShotPool = OwnedCommandPool(m_device, pool);

    // The pipeline cache, from its file when that holds this device's and driver's data (the
    // header's vendor, device and cache UUID; anything else starts empty).
    m_pipelineCachePath = options.pipelineCachePath;
    std::vector<char> initial;
    if (!options.pipelineCachePath.empty()) {
        std::ifstream in(options.pipelineCachePath, std::ios::binary);
        initial.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
        VkPipelineCacheHeaderVersionOne header{};
        const bool fits =
            initial.size() >= sizeof header &&
            (std::memcpy(&header, initial.data(), sizeof header), true) &&
            header.headerVersion == VK_PIPELINE_CACHE_HEADER_VERSION_ONE &&
            header.vendorID == m_properties.vendorID && header.deviceID == m_properties.deviceID &&
            std::memcmp(header.pipelineCacheUUID, m_properties.pipelineCacheUUID, VK_UUID_SIZE) ==
                0;
        if (!fits) initial.clear();
    }
    VkPipelineCacheCreateInfo cacheInfo{VK_STRUCTURE_TYPE_PIPELINE_CACHE_CREATE_INFO};
    cacheInfo.initialDataSize = initial.size();
    cacheInfo.pInitialData = initial.empty() ? nullptr : initial.data();
    RG_VK_TRY(vkCreatePipelineCache(m_device, &cacheInfo, nullptr, &m_pipelineCache));
    return {};
}

Result<void> Context::savePipelineCache() const {
    if (m_pipelineCachePath.empty() || !m_pipelineCache) return {};
    size_t size = 0;
    RG_VK_TRY(vkGetPipelineCacheData(m_device, m_pipelineCache, &size, nullptr));
    std::vector<char> data(size);
    RG_VK_TRY(vkGetPipelineCacheData(m_device, m_pipelineCache, &size, data.data()));
    const std::string tmp = tempPathBeside(m_pipelineCachePath);
    {
        std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
        out.write(data.data(), static_cast<std::streamsize>(size));
        if (!out) return fail(ErrorCode::Io, "cannot write the pipeline cache '" + tmp + "'");
    }
    if (std::rename(tmp.c_str(), m_pipelineCachePath.c_str()) != 0) {
        std::remove(tmp.c_str());
        return fail(ErrorCode::Io,
                    "cannot replace the pipeline cache '" + m_pipelineCachePath + "'");
    }
    return {};
}

Context::~Context() {
    if (m_device) {
        vkDeviceWaitIdle(m_device);
        for (uint32_t s = 0; s < m_deletions.size(); ++s) collectGarbage(s);
        if (m_pipelineCache) {
            (void)
                savePipelineCache();  // best effort: a cache that cannot be written is only slower next time
            vkDestroyPipelineCache(m_device, m_pipelineCache, nullptr);
        }
        m_oneShotPool.reset();
        m_allocator.reset();
        if (m_ownsDevice) vkDestroyDevice(m_device, nullptr);
    }
    if (m_messenger) {
        auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
            vkGetInstanceProcAddr(m_instance, "vkDestroyDebugUtilsMessengerEXT"));
        if (destroy) destroy(m_instance, m_messenger, nullptr);
    }
    if (m_instance && m_ownsDevice) vkDestroyInstance(m_instance, nullptr);
    // RG_VALIDATION_LOG=FILE: one line per validated device, "messages N", appended (O_APPEND
    // writes of one short line do not interleave), so a test suite can print its total
    // (tools/test.sh) — messages at device destruction (leaked objects) included.
    if (const char* log = std::getenv("RG_VALIDATION_LOG"); log && *log && m_validation) {
        if (std::FILE* f = std::fopen(log, "a")) {
            std::fprintf(f, "messages %u\n", m_validationMessages);
            std::fclose(f);
        }
    }
}

VKAPI_ATTR VkBool32 VKAPI_CALL Context::debugCallback(
    VkDebugUtilsMessageSeverityFlagBitsEXT severity, VkDebugUtilsMessageTypeFlagsEXT,
    const VkDebugUtilsMessengerCallbackDataEXT* data, void* user) {
    auto* self = static_cast<Context*>(user);
    std::lock_guard<std::mutex> guard(self->m_messageLock);  // pipelines compile on several threads
    self->m_validationMessages++;
    std::string msg = std::string(severity >= VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT
                                      ? "validation error: "
                                      : "validation warning: ") +
                      (data && data->pMessage ? data->pMessage : "");
    std::fprintf(stderr, "rgraph: %s\n", msg.c_str());
    if (self->m_messages.size() < 64) self->m_messages.push_back(msg);
    return VK_FALSE;
}

void Context::beginLabel(VkCommandBuffer cmd, const std::string& name) const {
    if (!m_beginLabel) return;
    VkDebugUtilsLabelEXT label{VK_STRUCTURE_TYPE_DEBUG_UTILS_LABEL_EXT};
    label.pLabelName = name.c_str();
    m_beginLabel(cmd, &label);
}

void Context::endLabel(VkCommandBuffer cmd) const {
    if (m_endLabel) m_endLabel(cmd);
}

void Context::setName(VkObjectType type, uint64_t handle, const std::string& name) const {
    if (!m_setName || !handle) return;
    VkDebugUtilsObjectNameInfoEXT info{VK_STRUCTURE_TYPE_DEBUG_UTILS_OBJECT_NAME_INFO_EXT};
    info.objectType = type;
    info.objectHandle = handle;
    info.pObjectName = name.c_str();
    m_setName(m_device, &info);
}

Result<void> Context::submitNow(const std::function<void(VkCommandBuffer)>& fn) {
    VkCommandBufferAllocateInfo alloc{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    alloc.commandPool = m_oneShotPool.get();
    alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    alloc.commandBufferCount = 1;
    VkCommandBuffer cmd = VK_NULL_HANDLE;
    RG_VK_TRY(vkAllocateCommandBuffers(m_device, &alloc, &cmd));
    VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    RG_VK_TRY(vkBeginCommandBuffer(cmd, &begin));
    fn(cmd);
    RG_VK_TRY(vkEndCommandBuffer(cmd));
    VkFenceCreateInfo fenceInfo{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    VkFence fence = VK_NULL_HANDLE;
    RG_VK_TRY(vkCreateFence(m_device, &fenceInfo, nullptr, &fence));
    OwnedFence owned(m_device, fence);
    VkCommandBufferSubmitInfo cmdInfo{VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO};
    cmdInfo.commandBuffer = cmd;
    VkSubmitInfo2 submit{VK_STRUCTURE_TYPE_SUBMIT_INFO_2};
    submit.commandBufferInfoCount = 1;
    submit.pCommandBufferInfos = &cmdInfo;
    RG_VK_TRY(vkQueueSubmit2(m_queue, 1, &submit, fence));
    RG_VK_TRY(vkWaitForFences(m_device, 1, &fence, VK_TRUE, UINT64_MAX));
    vkFreeCommandBuffers(m_device, m_oneShotPool.get(), 1, &cmd);
    return {};
}

void Context::deferDestroy(std::function<void()> fn) {
    m_deletions[m_currentSlot].push_back(std::move(fn));
}

void Context::collectGarbage(uint32_t slot) {
    auto pending = std::move(m_deletions[slot]);
    m_deletions[slot].clear();
    for (auto& fn : pending) fn();
}

Result<void> Context::waitIdle() {
    RG_VK_TRY(vkDeviceWaitIdle(m_device));
    for (uint32_t s = 0; s < m_deletions.size(); ++s) collectGarbage(s);
    return {};
}

}  // namespace rg::gpu
