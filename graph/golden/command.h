// `rgraph test`: the golden test runner's command line.
//
//   rgraph test [PATTERN] [--update] [--report DIR] [--junit FILE] [--dir DIR] [--images DIR]
//               [--out DIR] [--device N] [--verbose]
//
// argv[1] is "test" (argv[0] the program). Returns the exit code: 0 every test passed (or was
// blessed), 1 a test failed or the device failed, 2 bad usage or a bad test script / pipeline.
#pragma once

namespace rg {

int goldenCommand(int argc, char** argv);

}  // namespace rg
