// A sharded bake's parts joined into the whole lightmap, and the dilation both finish with.
#include <algorithm>
#include <string>
#include <vector>

#include "bake/lightmap.h"

namespace rg::bake {

void dilateLightmap(Lightmap& lm) {
    std::vector<uint8_t> filled = lm.coverage;
    std::vector<glm::vec3> sum(lm.axes.size());
    for (int ring = 0; ring < 4; ++ring) {
        std::vector<uint8_t> next = filled;
        for (uint32_t y = 0; y < lm.height; ++y)
            for (uint32_t x = 0; x < lm.width; ++x) {
                const size_t i = size_t(y) * lm.width + x;
                if (filled[i]) continue;
                int count = 0;
                std::fill(sum.begin(), sum.end(), glm::vec3(0.0f));
                for (int dy = -1; dy <= 1; ++dy)
                    for (int dx = -1; dx <= 1; ++dx) {
                        const int nx = int(x) + dx, ny = int(y) + dy;
                        if (nx < 0 || ny < 0 || nx >= int(lm.width) || ny >= int(lm.height))
                            continue;
                        const size_t j = size_t(ny) * lm.width + size_t(nx);
                        if (!filled[j]) continue;
                        ++count;
                        for (size_t k = 0; k < lm.axes.size(); ++k) sum[k] += lm.lobes[k][j];
                    }
                if (count == 0) continue;
                for (size_t k = 0; k < lm.axes.size(); ++k) lm.lobes[k][i] = sum[k] / float(count);
                next[i] = 1;
            }
        filled.swap(next);
    }
}

Result<Lightmap> mergeLightmapParts(const std::vector<std::string>& paths) {
    if (paths.empty()) return fail(ErrorCode::InvalidInput, "no parts to merge");
    Lightmap whole;
    LightmapPart first;
    std::vector<std::string> byShard;  // the file of each shard
    uint64_t texels = 0;
    for (size_t p = 0; p < paths.size(); ++p) {
        const std::string& path = paths[p];
        LightmapPart part;
        auto lm = readLightmapExr(path, &part);
        if (!lm) return std::unexpected(lm.error());
        const std::string shardName =
            "shard " + std::to_string(part.shard + 1) + "/" + std::to_string(part.shards);
        if (p == 0) {
            first = part;
            byShard.assign(part.shards, "");
            whole = *lm;
            std::fill(whole.coverage.begin(), whole.coverage.end(), uint8_t(0));
            for (auto& lobe : whole.lobes) std::fill(lobe.begin(), lobe.end(), glm::vec3(0.0f));
        } else {
            auto other = [&](const std::string& what, const std::string& mine,
                             const std::string& theirs) {
                return fail(ErrorCode::InvalidInput,
                            path + ": " + shardName + " is of another bake than " + paths[0] +
                                " (" + what + " " + mine + ", not " + theirs +
                                "): every part must come from the same scene and settings");
            };
            if (lm->key != whole.key) return other("scene key", lm->key, whole.key);
            if (part.shards != first.shards)
                return other("shards", std::to_string(part.shards), std::to_string(first.shards));
            if (lm->width != whole.width || lm->height != whole.height)
                return other("size", std::to_string(lm->width) + "x" + std::to_string(lm->height),
                             std::to_string(whole.width) + "x" + std::to_string(whole.height));
            if (lm->axes != whole.axes || lm->sharpness != whole.sharpness ||
                lm->unit != whole.unit || lm->density != whole.density)
                return other("basis", "(lobes, sharpness, density or unit amplitudes)",
                             "the first part's");
            if (part.covered != first.covered)
                return other("covered texels", std::to_string(part.covered),
                             std::to_string(first.covered));
        }
        if (!byShard[part.shard].empty())
            return fail(
                ErrorCode::InvalidInput,
                path + ": " + shardName + " is given twice (also " + byShard[part.shard] + ")");
        byShard[part.shard] = path;
        uint32_t mine = 0;
        for (size_t i = 0; i < lm->coverage.size(); ++i) {
            if (!lm->coverage[i]) continue;
            if (whole.coverage[i])
                return fail(ErrorCode::InvalidInput, path + ": " + shardName +
                                                         " overlaps another part at texel (" +
                                                         std::to_string(i % whole.width) + ", " +
                                                         std::to_string(i / whole.width) + ")");
            whole.coverage[i] = 1;
            ++mine;
            for (size_t k = 0; k < whole.lobes.size(); ++k) whole.lobes[k][i] = lm->lobes[k][i];
        }
        texels += mine;
    }
    std::string missing;
    for (size_t k = 0; k < byShard.size(); ++k)
        if (byShard[k].empty())
            missing += (missing.empty() ? "" : ", ") + std::to_string(k + 1) + "/" +
                       std::to_string(byShard.size());
    if (!missing.empty())
        return fail(ErrorCode::InvalidInput,
                    "the parts of bake " + whole.key + " lack shard " + missing + " (given " +
                        std::to_string(paths.size()) + " of " + std::to_string(byShard.size()) +
                        "): a merge never writes a partial lightmap");
    if (texels != first.covered)
        return fail(ErrorCode::InvalidInput, "the parts of bake " + whole.key + " cover " +
                                                 std::to_string(texels) + " texels, the atlas " +
                                                 std::to_string(first.covered));
    dilateLightmap(whole);
    return whole;
}

}  // namespace rg::bake
