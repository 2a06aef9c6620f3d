#pragma once
// What the Executor's source files share: the physical resources and pass instances of a build
// (Executor::Built), and the clock its build and frame timings are taken with.
#include <chrono>
#include <memory>
#include <string>
#include <vector>

#include "executor.h"

namespace rg::gpu {

using Clock = std::chrono::steady_clock;
inline double msSince(Clock::time_point t) {
    return std::chrono::duration<double, std::milli>(Clock::now() - t).count();
}

// Physical resources and pass instances of one plan. Shared pointers, so an incremental rebuild
// can reuse what did not change while the old build stays intact until the new one succeeds.
struct Executor::Built {
    Plan plan;  // owned here so pass instances and the table may point into it
    GraphDesc graph;
    std::vector<std::shared_ptr<OwnedMemory>> heaps;
    std::vector<std::shared_ptr<Image>> images;    // by plan resource index
    std::vector<std::shared_ptr<Buffer>> buffers;  // by plan resource index
    ResourceTable table;
    std::vector<std::shared_ptr<PassInstance>> instances;  // by plan pass index
    std::vector<std::string>
        sourceStamps;  // by plan pass index: its files' times and sizes when prepared
    // What its passes were prepared against: a build against another scene or other generated
    // headers prepares every pass again.
    uint64_t sceneId = 0;
    std::string generatedDir;
};

}  // namespace rg::gpu
