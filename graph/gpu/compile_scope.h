#pragma once
// Executor::build prepares passes on several threads, one at a time under the build's lock, which
// a thread gives up only while the driver compiles a pipeline: vkCreate*Pipelines may run
// concurrently with any other call on the device (the pipeline cache is internally synchronised),
// and it is most of a pass's set-up (~430 of ~500 ms for the default pipeline on lavapipe).
// Everything else a prepare touches — the shader compiler's caches, descriptor pools, the scene —
// stays single-threaded.
#include <mutex>

namespace rg::gpu {

// The lock the current thread holds while it prepares a pass (null outside a parallel build).
inline thread_local std::unique_lock<std::mutex>* t_prepareLock = nullptr;

// Wrap each pipeline compile: other threads' prepares go on meanwhile.
class UnlockedForCompile {
public:
    UnlockedForCompile() : m_lock(t_prepareLock) {
        if (m_lock) m_lock->unlock();
    }
    ~UnlockedForCompile() {
        if (m_lock) m_lock->lock();
    }
    UnlockedForCompile(const UnlockedForCompile&) = delete;
    UnlockedForCompile& operator=(const UnlockedForCompile&) = delete;

private:
    std::unique_lock<std::mutex>* m_lock;
};

}  // namespace rg::gpu
