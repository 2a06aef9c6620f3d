// What the pipeline-script tests (tests/lua/test_lua*.cpp) share: the test scripts' folder, the
// first line of an error, and the ```lua examples of scripts/README.md.
#pragma once

#include <fstream>
#include <string>
#include <vector>

#include "core/result.h"

namespace rg::test {

inline const std::string kScripts = "tests/lua/scripts/";

inline std::string script(const std::string& name) {
    return std::string(RG_SOURCE_ROOT) + "/" + kScripts + name;
}

// The first line of an error (the rest is the traceback).
inline std::string firstLine(const Error& e) { return e.message.substr(0, e.message.find('\n')); }

// Every ```lua block of scripts/README.md, in order.
inline std::vector<std::string> readmeExamples() {
    std::ifstream in(std::string(RG_SOURCE_ROOT) + "/scripts/README.md");
    std::vector<std::string> blocks;
    std::string line, block;
    bool inside = false;
    while (std::getline(in, line)) {
        if (!inside && line == "```lua") {
            inside = true;
            block.clear();
        } else if (inside && line == "```") {
            inside = false;
            blocks.push_back(block);
        } else if (inside)
            block += line + "\n";
    }
    return blocks;
}

}  // namespace rg::test
