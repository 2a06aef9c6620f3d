// Fuzz target: glTF loading (graph/scene gltf_load.cpp over tinygltf): the input as a .glb
// (binary) or, when it starts with '{', a .gltf (JSON), with images and mips as a render loads them.
#include "fuzz_common.h"
#include "scene/scene.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const bool json = size > 0 && data[0] == '{';
    const std::string path = rg::fuzz::writeInput(data, size, json ? "fuzz.gltf" : "fuzz.glb");
    (void)rg::loadGltf(path);
    return 0;
}
