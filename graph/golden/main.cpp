// rgraph-golden: `rgraph test` as a program of its own (CTest runs each golden test through it).
// `rgraph-golden [PATTERN] [OPTIONS]` is `rgraph test [PATTERN] [OPTIONS]`.
#include <string>
#include <vector>

#include "golden/command.h"

int main(int argc, char** argv) {
    std::vector<char*> args = {argv[0], const_cast<char*>("test")};
    for (int i = 1; i < argc; ++i) args.push_back(argv[i]);
    args.push_back(nullptr);
    return rg::goldenCommand(static_cast<int>(args.size()) - 1, args.data());
}
