// Vulkan basics for the GPU layer: checked calls and move-only owners. Every VkResult is
// checked; a failure names the call, file:line and the result. vkDestroy* appears only in
// this folder.
#pragma once

#include <vulkan/vulkan.h>

#include <string>
#include <utility>

#include "core/result.h"

namespace rg::gpu {

const char* vkResultName(VkResult r);

inline Error vkError(const char* call, VkResult r, const char* file, int line) {
    std::string f = file;
    if (auto slash = f.find_last_of('/'); slash != std::string::npos) f = f.substr(slash + 1);
    return Error(ErrorCode::Device, std::string(call) + " failed with " + vkResultName(r) + " at " +
                                        f + ":" + std::to_string(line));
}

}  // namespace rg::gpu

// Inside a function returning Result<T>: return the failure of a Vulkan call as an Error.
#define RG_VK_TRY(call)                                                                           \
    do {                                                                                          \
        VkResult rg_vk_result_ = (call);                                                          \
        if (rg_vk_result_ != VK_SUCCESS)                                                          \
            return std::unexpected(::rg::gpu::vkError(#call, rg_vk_result_, __FILE__, __LINE__)); \
    } while (0)

// For calls that cannot fail on valid usage in a void context (a bug if they do).
#define RG_VK_CHECK(call)                                                       \
    do {                                                                        \
        VkResult rg_vk_result_ = (call);                                        \
        RG_CHECK(rg_vk_result_ == VK_SUCCESS)                                   \
            << #call << " returned " << ::rg::gpu::vkResultName(rg_vk_result_); \
    } while (0)

namespace rg::gpu {

// Move-only owner of a device-level handle destroyed with vkDestroyX(device, handle, nullptr).
template <class T, void (*Destroy)(VkDevice, T, const VkAllocationCallbacks*)>
class Owned {
public:
    Owned() = default;
    Owned(VkDevice device, T handle) : m_device(device), m_handle(handle) {}
    Owned(const Owned&) = delete;
    Owned& operator=(const Owned&) = delete;
    Owned(Owned&& o) noexcept
        : m_device(o.m_device), m_handle(std::exchange(o.m_handle, VK_NULL_HANDLE)) {}
    Owned& operator=(Owned&& o) noexcept {
        if (this != &o) {
            reset();
            m_device = o.m_device;
            m_handle = std::exchange(o.m_handle, VK_NULL_HANDLE);
        }
        return *this;
    }
    ~Owned() { reset(); }

    void reset() {
        if (m_handle != VK_NULL_HANDLE) Destroy(m_device, m_handle, nullptr);
        m_handle = VK_NULL_HANDLE;
    }
    T get() const { return m_handle; }
    T release() { return std::exchange(m_handle, VK_NULL_HANDLE); }
    explicit operator bool() const { return m_handle != VK_NULL_HANDLE; }

private:
    VkDevice m_device = VK_NULL_HANDLE;
    T m_handle = VK_NULL_HANDLE;
};

using OwnedImage = Owned<VkImage, vkDestroyImage>;
using OwnedImageView = Owned<VkImageView, vkDestroyImageView>;
using OwnedBuffer = Owned<VkBuffer, vkDestroyBuffer>;
using OwnedBufferView = Owned<VkBufferView, vkDestroyBufferView>;
using OwnedSampler = Owned<VkSampler, vkDestroySampler>;
using OwnedMemory = Owned<VkDeviceMemory, vkFreeMemory>;
using OwnedFence = Owned<VkFence, vkDestroyFence>;
using OwnedSemaphore = Owned<VkSemaphore, vkDestroySemaphore>;
using OwnedCommandPool = Owned<VkCommandPool, vkDestroyCommandPool>;
using OwnedQueryPool = Owned<VkQueryPool, vkDestroyQueryPool>;
using OwnedShaderModule = Owned<VkShaderModule, vkDestroyShaderModule>;
using OwnedPipeline = Owned<VkPipeline, vkDestroyPipeline>;
using OwnedPipelineLayout = Owned<VkPipelineLayout, vkDestroyPipelineLayout>;
using OwnedDescriptorSetLayout = Owned<VkDescriptorSetLayout, vkDestroyDescriptorSetLayout>;
using OwnedDescriptorPool = Owned<VkDescriptorPool, vkDestroyDescriptorPool>;

}  // namespace rg::gpu
