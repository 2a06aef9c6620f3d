// Headless Vulkan context: instance without any window-system extension, one device with one
// graphics+compute queue, the memory allocator, one-shot submissions and the deletion queue.
//
// Device choice: discrete GPU, then integrated, then virtual, then CPU (lavapipe); a device
// must offer Vulkan 1.3 with dynamic rendering and synchronization2. `deviceIndex` overrides.
// Validation: RG_VALIDATION=1 (or Options::validation) enables VK_LAYER_KHRONOS_validation;
// every message it sends is printed and counted, and tests require the count to stay 0.
// Threading: one thread uses a Context at a time.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "memory.h"
#include "vk.h"

namespace rg::gpu {

struct DeviceInfo {
    uint32_t index = 0;
    std::string name;
    std::string type;  // "discrete", "integrated", "virtual", "cpu", "other"
    std::string driver;
    uint32_t apiVersion = 0;
    bool usable = false;
    std::string whyNot;  // reason when not usable
};

// A device the host application created and owns: rgraph renders with it and never destroys it.
// The device must be Vulkan 1.3 with dynamicRendering, synchronization2, maintenance4,
// hostQueryReset and imageCubeArray enabled; the queue family must do graphics, compute and
// timestamps.
struct ExternalDevice {
    VkInstance instance = VK_NULL_HANDLE;
    VkPhysicalDevice physicalDevice = VK_NULL_HANDLE;
    VkDevice device = VK_NULL_HANDLE;
    uint32_t queueFamily = 0;
    VkQueue queue = VK_NULL_HANDLE;
};

struct ContextOptions {
    std::optional<uint32_t> deviceIndex;  // --device N
    std::optional<bool> validation;       // default: RG_VALIDATION environment variable
    uint32_t framesInFlight = 2;
    // A file the VkPipelineCache starts from (when it exists and was written by the same device
    // and driver) and is saved to when the context ends; "" keeps it in memory.
    std::string pipelineCachePath;
    // Use the host's device instead of creating one (validation is then the host's choice).
    std::optional<ExternalDevice> external;
};

class Context {
public:
    static Result<std::unique_ptr<Context>> create(const ContextOptions& options = {});
    bool ownsDevice() const { return m_ownsDevice; }
    // Lists physical devices (and why any is unusable) without creating a device.
    static Result<std::vector<DeviceInfo>> listDevices();
    ~Context();
    Context(const Context&) = delete;
    Context& operator=(const Context&) = delete;

    VkInstance instance() const { return m_instance; }
    VkPhysicalDevice physicalDevice() const { return m_physical; }
    VkDevice device() const { return m_device; }
    VkQueue queue() const { return m_queue; }
    uint32_t queueFamily() const { return m_queueFamily; }
    const DeviceInfo& deviceInfo() const { return m_info; }
    const VkPhysicalDeviceProperties& properties() const { return m_properties; }
    // Whether indirect draws may start at an instance other than 0 (drawIndirectFirstInstance).
    bool drawIndirectFirstInstance() const { return m_drawIndirectFirstInstance; }
    // Whether fragment shaders may use quad operations (GL_KHR_shader_subgroup_quad; lavapipe
    // has them): every fragment shader then gets RG_QUAD_OPS (passes/shader_program.cpp).
    bool fragmentQuadOps() const { return m_fragmentQuadOps; }
    // Whether vkCmdDrawIndexedIndirectCount may be used (Vulkan 1.2's drawIndirectCount).
    bool drawIndirectCount() const { return m_drawIndirectCount; }
    Allocator& allocator() { return *m_allocator; }
    uint32_t framesInFlight() const { return m_framesInFlight; }
    double timestampPeriodNs() const { return m_properties.limits.timestampPeriod; }
    // Every pipeline is created through it (ContextOptions::pipelineCachePath).
    VkPipelineCache pipelineCache() const { return m_pipelineCache; }
    // Writes the cache to its file (atomically: a temporary, then a rename); also done on destruction.
    Result<void> savePipelineCache() const;

    bool validationEnabled() const { return m_validation; }
    uint32_t validationMessageCount() const { return m_validationMessages; }
    const std::vector<std::string>& validationMessages() const { return m_messages; }

    // Debug labels (no-ops when VK_EXT_debug_utils is absent).
    void beginLabel(VkCommandBuffer cmd, const std::string& name) const;
    void endLabel(VkCommandBuffer cmd) const;
    void setName(VkObjectType type, uint64_t handle, const std::string& name) const;

    // Records `fn` into a fresh command buffer, submits it and waits (uploads, readbacks).
    Result<void> submitNow(const std::function<void(VkCommandBuffer)>& fn);

    // Deletion queue: `fn` runs once the GPU has finished every frame in flight now.
    void deferDestroy(std::function<void()> fn);
    // Called by the executor after the fence of frame slot `slot` signalled.
    void collectGarbage(uint32_t slot);
    void setCurrentSlot(uint32_t slot) { m_currentSlot = slot; }
    Result<void> waitIdle();

private:
    Result<void> adopt(const ExternalDevice& device);
    Result<void> createDeviceObjects(const ContextOptions& options);
    Context() = default;
    static VKAPI_ATTR VkBool32 VKAPI_CALL debugCallback(VkDebugUtilsMessageSeverityFlagBitsEXT,
                                                        VkDebugUtilsMessageTypeFlagsEXT,
                                                        const VkDebugUtilsMessengerCallbackDataEXT*,
                                                        void*);

    VkInstance m_instance = VK_NULL_HANDLE;
    VkDebugUtilsMessengerEXT m_messenger = VK_NULL_HANDLE;
    VkPhysicalDevice m_physical = VK_NULL_HANDLE;
    VkDevice m_device = VK_NULL_HANDLE;
    VkQueue m_queue = VK_NULL_HANDLE;
    uint32_t m_queueFamily = 0;
    DeviceInfo m_info;
    VkPhysicalDeviceProperties m_properties{};
    std::unique_ptr<Allocator> m_allocator;
    VkPipelineCache m_pipelineCache = VK_NULL_HANDLE;
    std::string m_pipelineCachePath;
    OwnedCommandPool m_oneShotPool;
    uint32_t m_framesInFlight = 2;
    uint32_t m_currentSlot = 0;
    bool m_drawIndirectFirstInstance = false;
    bool m_fragmentQuadOps = false;
    bool m_drawIndirectCount = false;
    // One queue per frame slot, plus those pushed before the first frame.
    std::vector<std::vector<std::function<void()>>> m_deletions;

    bool m_validation = false;
    bool m_ownsDevice = true;  // false: the host's instance and device (ContextOptions::external)
    bool m_debugUtils = false;
    std::mutex m_messageLock;
    uint32_t m_validationMessages = 0;
    std::vector<std::string> m_messages;
    PFN_vkCmdBeginDebugUtilsLabelEXT m_beginLabel = nullptr;
    PFN_vkCmdEndDebugUtilsLabelEXT m_endLabel = nullptr;
    PFN_vkSetDebugUtilsObjectNameEXT m_setName = nullptr;
};

}  // namespace rg::gpu
