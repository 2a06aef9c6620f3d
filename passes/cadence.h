#pragma once
// A pass's `cadence` parameter: every frame, or once per build (passes/builtin_kinds.cpp's
// compute and mips kinds, passes/scene_pass_capture.cpp's probe capture).
#include <string>

#include "core/check.h"
#include "gpu/pass_kind.h"
#include "passes.h"
#include "shader_program.h"

namespace rg::passes {

using gpu::PassSetup;
using gpu::RecordContext;

// params.cadence of the compute, mips and scene (capture) kinds. "frame" (default): the pass records every frame.
// "once": it records after each prepare (new shader, scene or size) and after each clearing of the
// persistent resources (FrameInfo::persistentEpoch), then never again until one of those happens —
// for what depends only on the scene's environment or on nothing (filtered probes, lookup tables).
// The plan's barriers still run when it skips; a persistent texture keeps its contents through them
// (it starts and ends every frame in ShaderReadOnly).
class Cadence {
public:
    Result<void> parse(const PassSetup& setup) {
        const PassDesc& desc = setup.desc;
        const std::string c =
            desc.params["cadence"].isString() ? desc.params["cadence"].asString() : "frame";
        if (c != "frame" && c != "once")
            return fail(ErrorCode::InvalidInput, passPrefix(desc) + "params.cadence: unknown '" +
                                                     c + "', expected one of: 'frame', 'once'");
        m_once = c == "once";
        m_recorded = false;
        // What a pass writes once must still be there in the frames it skips.
        if (m_once)
            for (const Access& a : desc.accesses)
                if (usageWrites(a.usage) && !setup.resources.find(a.resource)->plan->persistent)
                    return fail(ErrorCode::InvalidInput,
                                passPrefix(desc) +
                                    "params.cadence: 'once' writes only persistent resources; '" +
                                    a.resource + "' is not (declare it with persistent = true)");
        return {};
    }
    // True when the pass records this frame (and remembers that it did).
    bool due(const RecordContext& rc) {
        if (m_once && m_recorded && m_epoch == rc.frame.persistentEpoch) return false;
        m_recorded = true;
        m_epoch = rc.frame.persistentEpoch;
        return true;
    }

    // The disk cache of once-per-build outputs (Executor::setOnceCache): whether the pass records
    // once and has yet to for `epoch`, and the cache's telling it that its outputs were restored.
    bool dueOnce(uint64_t epoch) const { return m_once && !(m_recorded && m_epoch == epoch); }
    void restored(uint64_t epoch) {
        m_recorded = true;
        m_epoch = epoch;
    }

private:
    bool m_once = false, m_recorded = false;
    uint64_t m_epoch = 0;
};

}  // namespace rg::passes
