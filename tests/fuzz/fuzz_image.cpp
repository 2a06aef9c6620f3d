// Fuzz target: the environment image readers (graph/image): Radiance .hdr (ours) and OpenEXR,
// chosen by the input's magic number (EXR: 76 2f 31 01), as --environment reads them.
#include "fuzz_common.h"
#include "image/image.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const bool exr =
        size >= 4 && data[0] == 0x76 && data[1] == 0x2f && data[2] == 0x31 && data[3] == 0x01;
    const std::string path = rg::fuzz::writeInput(data, size, exr ? "fuzz.exr" : "fuzz.hdr");
    if (exr)
        (void)rg::readExr(path);
    else
        (void)rg::readHdr(path);
    return 0;
}
