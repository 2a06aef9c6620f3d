// Executor: the disk cache of once-per-build outputs (setOnceCache) — which due once passes can
// be cached, their key, and their outputs restored before a frame or saved after it.
#include "executor.h"

#include <algorithm>
#include <bit>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <optional>

#include <unistd.h>

#include "core/hash.h"
#include "executor_detail.h"
#include "core/temp_path.h"

namespace rg::gpu {

void Executor::setOnceCache(std::string dir) { m_onceDir = std::move(dir); }

namespace {

void hashValue(ContentHash& h, const Value& v) {
    if (v.isBool()) {
        h.u64(1);
        h.u64(v.asBool());
    } else if (v.isNumber()) {
        h.u64(2);
        h.u64(std::bit_cast<uint64_t>(v.asNumber()));
    } else if (v.isString()) {
        h.u64(3);
        h.str(v.asString());
    } else if (v.isList()) {
        h.u64(4 + (v.asList().size() << 8));
        for (const Value& e : v.asList()) hashValue(h, e);
    } else if (v.isTable()) {
        h.u64(5 + (v.asTable().size() << 8));
        for (const auto& [k, e] : v.asTable()) {
            h.str(k);
            hashValue(h, e);
        }
    } else {
        h.u64(0);
    }
}

// A scene pass's material, every field (a capture's cache entry depends on each).
void hashMaterial(ContentHash& h, const PassMaterial& m) {
    auto strings = [&](const std::vector<std::string>& list) {
        h.u64(list.size());
        for (const std::string& s : list) h.str(s);
    };
    for (const std::string* s : {&m.name, &m.layout, &m.surface, &m.shading, &m.fixup, &m.origin})
        h.str(*s);
    h.u64((uint64_t(m.id) << 40) | (uint64_t(m.stencilValue) << 20) | m.stencilMask);
    strings(m.targets);
    h.u64(m.targetInteger.size());
    for (bool integer : m.targetInteger) h.u64(integer);
    strings(m.fills);
    strings(m.custom);
    h.u64(m.channels.size());
    for (const auto& [standard, channel] : m.channels) {
        h.str(standard);
        h.str(channel);
    }
}

void hashFile(ContentHash& h, const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    h.str(path);
    h.str(text);
}

// Bytes of a resource as the cache stores it: every mip of every layer, tightly packed (the depth
// aspect of a depth format), or the whole buffer.
uint64_t cachedBytes(const PlanResource& r) {
    if (r.kind == ResourceKind::Buffer) return r.bufferSize;
    uint64_t bytes = 0;
    for (uint32_t m = 0; m < r.mips; ++m)
        bytes += uint64_t(std::max(1u, r.width >> m)) * std::max(1u, r.height >> m) * r.layers *
                 copyTexelBytes(r.format);
    return bytes;
}

std::vector<VkBufferImageCopy> cachedRegions(const PlanResource& r, VkDeviceSize offset) {
    std::vector<VkBufferImageCopy> regions;
    for (uint32_t m = 0; m < r.mips; ++m) {
        VkBufferImageCopy c{};
        c.bufferOffset = offset;
        c.imageSubresource = {aspectOf(r.format) & ~VkImageAspectFlags(VK_IMAGE_ASPECT_STENCIL_BIT),
                              m, 0, r.layers};
        c.imageExtent = {std::max(1u, r.width >> m), std::max(1u, r.height >> m), 1};
        regions.push_back(c);
        offset += VkDeviceSize(c.imageExtent.width) * c.imageExtent.height * r.layers *
                  copyTexelBytes(r.format);
    }
    return regions;
}

constexpr char kOnceMagic[8] = {'R', 'G', 'O', 'N', 'C', 'E', '0', '1'};

}  // namespace

// The once passes due now whose outputs are a function of what the key covers: start from every
// due once pass and drop, until none is dropped, each that touches a resource written by a pass
// outside the set (a per-frame pass, a once pass not due), a transient, a host image or a stencil
// format. Its resources: everything the set writes.
Executor::OnceSet Executor::cacheableOncePasses(uint32_t slot) const {
    OnceSet set;
    const Plan& plan = m_built->plan;
    const size_t n = plan.passes.size();
    std::vector<char> in(n, 0);
    for (size_t p = 0; p < n; ++p) in[p] = m_built->instances[p]->dueOnce(m_persistentEpoch);
    if (std::find(in.begin(), in.end(), 1) == in.end())
        return set;  // every frame but the first after a build
    std::vector<std::vector<size_t>> writers(plan.resources.size());
    for (size_t p = 0; p < n; ++p)
        for (const PlanAccess& a : plan.passes[p].accesses)
            if (usageWrites(a.usage)) writers[a.resource].push_back(p);
    for (bool changed = true; changed;) {
        changed = false;
        for (size_t p = 0; p < n; ++p) {
            if (!in[p]) continue;
            for (const PlanAccess& a : plan.passes[p].accesses) {
                const PlanResource& r = plan.resources[a.resource];
                bool ok = (r.persistent || r.imported) && !m_hostImports.count(r.name) &&
                          !formatInfo(r.format).stencil;
                for (size_t w : writers[a.resource]) ok = ok && in[w];
                if (!ok) {
                    in[p] = 0;
                    changed = true;
                    break;
                }
            }
        }
    }
    std::vector<char> written(plan.resources.size(), 0), touched(plan.resources.size(), 0);
    for (size_t p = 0; p < n; ++p) {
        if (!in[p]) continue;
        set.passes.push_back(p);
        for (const PlanAccess& a : plan.passes[p].accesses) {
            touched[a.resource] = 1;
            if (usageWrites(a.usage)) written[a.resource] = 1;
        }
    }
    if (set.passes.empty()) return set;
    ContentHash h;
    h.str("rgraph once-per-build outputs, format 1");
    std::error_code ec;  // this build of the code: a pass kind's C++ may change what it writes
    h.u64(std::filesystem::file_size("/proc/self/exe", ec));
    h.u64(static_cast<uint64_t>(
        std::filesystem::last_write_time("/proc/self/exe", ec).time_since_epoch().count()));
    const VkPhysicalDeviceProperties& props = m_ctx.properties();
    h.u64((uint64_t(props.vendorID) << 32) | props.deviceID);
    h.u64(props.driverVersion);
    h.str(props.deviceName);
    h.str(m_ctx.deviceInfo().driver);
    for (size_t p : set.passes) {
        const PlanPass& pass = plan.passes[p];
        const PassDesc& desc = m_built->graph.passes[pass.desc];
        h.str(pass.name);
        h.str(desc.kind);
        hashValue(h, desc.params);
        for (const PassMaterial& m : desc.materials) hashMaterial(h, m);
        for (const Access& a : desc.accesses) {
            h.str(a.resource);
            h.u64((uint64_t(a.usage) << 1) | uint64_t(a.load));
        }
        for (const std::string& f : m_built->instances[p]->files()) hashFile(h, f);
    }
    for (size_t i = 0; i < plan.resources.size(); ++i) {
        if (!touched[i]) continue;
        const PlanResource& r = plan.resources[i];
        h.str(r.name);
        for (uint64_t v :
             {uint64_t(r.kind), uint64_t(r.format), uint64_t(r.width), uint64_t(r.height),
              uint64_t(r.layers), uint64_t(r.mips), uint64_t(r.cube), uint64_t(r.array),
              r.bufferSize, uint64_t(r.persistent)})
            h.u64(v);
        if (auto d = m_importData.find(r.name); r.imported && d != m_importData.end()) {
            h.u64(d->second.width);
            h.u64(d->second.height);
            h.u64(d->second.channels);
            h.bytes(d->second.pixels.data(), d->second.pixels.size() * sizeof(float));
        }
        if (written[i]) {
            set.resources.push_back(i);
            set.bytes += cachedBytes(r);
        }
    }
    h.u64(m_scene ? m_scene->contentHash(slot) : 0);
    set.key = h.value();
    return set;
}

namespace {

std::string onceCachePath(const std::string& dir, uint64_t key) {
    char name[32];
    std::snprintf(name, sizeof name, "%016llx.bin", static_cast<unsigned long long>(key));
    return (std::filesystem::path(dir) / "once" / name).string();
}

}  // namespace

// Records the copies between the set's resources and `staging` (their bytes back to back, as
// cachedBytes and cachedRegions lay them out), in either direction; the images go from and back to
// ShaderReadOnly, where every frame leaves a persistent texture.
void Executor::recordOnceCopies(VkCommandBuffer cmd, const OnceSet& set, VkBuffer staging,
                                bool restore) {
    const Plan& plan = m_built->plan;
    const VkImageLayout transfer =
        restore ? VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL : VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
    const VkAccessFlags2 transferAccess =
        restore ? VK_ACCESS_2_TRANSFER_WRITE_BIT : VK_ACCESS_2_TRANSFER_READ_BIT;
    if (!restore)
        memoryBarrier(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_MEMORY_WRITE_BIT,
                      VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_READ_BIT);
    VkDeviceSize offset = 0;
    for (size_t i : set.resources) {
        const PlanResource& r = plan.resources[i];
        if (r.kind == ResourceKind::Buffer) {
            VkBuffer buffer = m_built->buffers[i]->buffer();
            VkBufferCopy c{restore ? offset : 0, restore ? 0 : offset, r.bufferSize};
            vkCmdCopyBuffer(cmd, restore ? staging : buffer, restore ? buffer : staging, 1, &c);
        } else {
            VkImage image = m_built->images[i]->image();
            const VkImageAspectFlags aspect = aspectOf(r.format);
            imageBarrier(cmd, image, aspect, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT,
                         VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT,
                         VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, transferAccess,
                         VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, transfer);
            const auto regions = cachedRegions(r, offset);
            if (restore)
                vkCmdCopyBufferToImage(cmd, staging, image, transfer,
                                       static_cast<uint32_t>(regions.size()), regions.data());
            else
                vkCmdCopyImageToBuffer(cmd, image, transfer, staging,
                                       static_cast<uint32_t>(regions.size()), regions.data());
            imageBarrier(cmd, image, aspect, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT,
                         restore ? VK_ACCESS_2_TRANSFER_WRITE_BIT : VK_ACCESS_2_NONE,
                         VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_MEMORY_READ_BIT,
                         transfer, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
        }
        offset += cachedBytes(r);
    }
    if (restore)
        memoryBarrier(cmd, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                      VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT,
                      VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT);
    else
        memoryBarrier(cmd, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                      VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_READ_BIT);
}

// Restores the due once passes' outputs when the cache has them (they then skip), else marks them
// to be saved after the frame. A missing, short or mismatched file is a miss, never an error.
Result<void> Executor::onceCacheBeforeFrame(uint32_t slot) {
    m_onceToSave.reset();
    OnceSet set = cacheableOncePasses(slot);
    if (set.passes.empty()) return {};
    m_onceStats = {};
    const auto t0 = Clock::now();
    const Plan& plan = m_built->plan;
    const std::string path = onceCachePath(m_onceDir, set.key);
    m_onceStats.file = path;
    std::ifstream in(path, std::ios::binary);
    bool hit = false;
    std::optional<Buffer> staging;
    if (in) {
        char magic[8] = {};
        uint64_t key = 0, count = 0;
        in.read(magic, 8);
        in.read(reinterpret_cast<char*>(&key), 8);
        in.read(reinterpret_cast<char*>(&count), 8);
        hit = in && std::equal(magic, magic + 8, kOnceMagic) && key == set.key &&
              count == set.resources.size();
        if (hit) {
            auto buf = Buffer::create(m_ctx, "once_cache.upload", std::max<uint64_t>(set.bytes, 4),
                                      VK_BUFFER_USAGE_TRANSFER_SRC_BIT, true);
            if (!buf) return std::unexpected(buf.error());
            staging = std::move(*buf);
            auto* dst = static_cast<char*>(staging->mapped());
            for (size_t i : set.resources) {
                uint64_t bytes = 0;
                in.read(reinterpret_cast<char*>(&bytes), 8);
                if (!in || bytes != cachedBytes(plan.resources[i])) {
                    hit = false;
                    break;
                }
                in.read(dst, static_cast<std::streamsize>(bytes));
                dst += bytes;
            }
            hit = hit && in;
        }
    }
    if (!hit) {
        m_onceToSave = std::move(set);
        return {};
    }
    auto uploaded = m_ctx.submitNow([&](VkCommandBuffer cmd) {
        recordOnceCopies(cmd, set, staging->buffer(), /*restore=*/true);
    });
    if (!uploaded) return uploaded;
    for (size_t p : set.passes) m_built->instances[p]->restoredOnce(m_persistentEpoch);
    std::error_code ec;  // the entry's time orders the cache's eviction: this one is in use
    std::filesystem::last_write_time(path, std::filesystem::file_time_type::clock::now(), ec);
    m_onceStats.restoredPasses = static_cast<uint32_t>(set.passes.size());
    m_onceStats.restoreMs = msSince(t0);
    return {};
}

// Once the frame that recorded them is done: the set's outputs read back and written to the cache
// (a temporary file renamed into place, so a reader never sees half an entry), then the oldest
// entries beyond kOnceCacheEntries removed. A cache that cannot be written is skipped with a
// warning: the frame was rendered.
Result<void> Executor::onceCacheAfterFrame(VkFence fence) {
    OnceSet set = std::move(*m_onceToSave);
    m_onceToSave.reset();
    RG_VK_TRY(vkWaitForFences(m_ctx.device(), 1, &fence, VK_TRUE, UINT64_MAX));
    const auto t0 = Clock::now();
    const Plan& plan = m_built->plan;
    auto staging = Buffer::create(m_ctx, "once_cache.readback", std::max<uint64_t>(set.bytes, 4),
                                  VK_BUFFER_USAGE_TRANSFER_DST_BIT, true);
    if (!staging) return std::unexpected(staging.error());
    auto copied = m_ctx.submitNow([&](VkCommandBuffer cmd) {
        recordOnceCopies(cmd, set, staging->buffer(), /*restore=*/false);
    });
    if (!copied) return copied;
    const std::filesystem::path path = onceCachePath(m_onceDir, set.key);
    std::error_code ec;
    std::filesystem::create_directories(path.parent_path(), ec);
    const std::filesystem::path temp = tempPathBeside(path.string());
    {
        std::ofstream out(temp, std::ios::binary | std::ios::trunc);
        const uint64_t count = set.resources.size();
        out.write(kOnceMagic, 8);
        out.write(reinterpret_cast<const char*>(&set.key), 8);
        out.write(reinterpret_cast<const char*>(&count), 8);
        const auto* src = static_cast<const char*>(staging->mapped());
        for (size_t i : set.resources) {
            const uint64_t bytes = cachedBytes(plan.resources[i]);
            out.write(reinterpret_cast<const char*>(&bytes), 8);
            out.write(src, static_cast<std::streamsize>(bytes));
            src += bytes;
        }
        if (!out) {
            std::fprintf(stderr,
                         "rgraph: warning: could not write the once-per-build cache entry %s\n",
                         temp.c_str());
            std::filesystem::remove(temp, ec);
            return {};
        }
    }
    std::filesystem::rename(temp, path, ec);
    if (ec) {
        std::filesystem::remove(temp, ec);
        return {};
    }
    std::vector<std::pair<std::filesystem::file_time_type, std::filesystem::path>> entries;
    for (const auto& e : std::filesystem::directory_iterator(path.parent_path(), ec))
        if (e.path().extension() == ".bin") entries.emplace_back(e.last_write_time(ec), e.path());
    std::sort(entries.begin(), entries.end(),
              [](const auto& a, const auto& b) { return a.first > b.first; });
    for (size_t k = kOnceCacheEntries; k < entries.size(); ++k)
        std::filesystem::remove(entries[k].second, ec);
    m_onceStats.savedPasses = static_cast<uint32_t>(set.passes.size());
    m_onceStats.saveMs = msSince(t0);
    return {};
}

}  // namespace rg::gpu
